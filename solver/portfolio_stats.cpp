// Portfolio statistics: load, save, record, order, report, merge (portfolio_stats.hpp).
#include "solver/portfolio_stats.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/atomic_file.hpp"
#include "base/error.hpp"

namespace tilekit {
namespace {

std::string key_of(TileKind kind, std::uint32_t colours, const std::string& spec) {
  return fmt::format("{}/{}/{}", kind_name(kind), colours, spec);
}

}  // namespace

double GroupStats::median_seconds() const {
  if (success_seconds.empty()) return 0;
  std::vector<double> v = success_seconds;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

std::string PortfolioStats::default_path() {
  if (const char* p = std::getenv("TILEKIT_PORTFOLIO_STATS"); p && *p) return p;
  std::filesystem::path base;
  if (const char* x = std::getenv("XDG_DATA_HOME"); x && *x)
    base = x;
  else if (const char* h = std::getenv("HOME"); h && *h)
    base = std::filesystem::path(h) / ".local" / "share";
  else
    base = ".";
  return (base / "tilekit" / "portfolio-stats.json").string();
}

PortfolioStats PortfolioStats::load(const std::string& path) {
  PortfolioStats s;
  std::ifstream in(path, std::ios::binary);
  if (!in) return s;
  std::stringstream buf;
  buf << in.rdbuf();
  try {
    nlohmann::json j = nlohmann::json::parse(buf.str());
    if (!j.is_object() || j.value("version", 0) != 1 || !j.contains("groups") || !j["groups"].is_object())
      throw InputError("not a Tilekit portfolio statistics file (version 1)");
    for (const auto& [key, g] : j["groups"].items()) {
      auto a = key.find('/'), b = a == std::string::npos ? a : key.find('/', a + 1);
      bool key_ok = b != std::string::npos && (key.substr(0, a) == "corner" || key.substr(0, a) == "wang") &&
                    b > a + 1 && b - a - 1 <= 3 &&
                    key.substr(a + 1, b - a - 1).find_first_not_of("0123456789") == std::string::npos;
      if (!key_ok || !g.is_object() || !g.contains("tries") || !g["tries"].is_number_unsigned() ||
          !g.contains("successes") || !g["successes"].is_number_unsigned() || !g.contains("success_seconds") ||
          !g["success_seconds"].is_array())
        throw InputError(fmt::format("entry '{}' is malformed", key));
      for (const auto& t : g["success_seconds"])
        if (!t.is_number()) throw InputError(fmt::format("entry '{}' is malformed", key));
    }
    s.groups_ = j["groups"];
  } catch (const nlohmann::json::exception& e) {
    throw InputError(
        fmt::format("{}: corrupt portfolio statistics ({}); delete the file to start afresh", path, e.what()));
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}; delete the file to start afresh", path, e.what()));
  }
  return s;
}

void PortfolioStats::save(const std::string& path) const {
  std::filesystem::path p(path);
  if (p.has_parent_path()) {
    std::error_code ec;
    std::filesystem::create_directories(p.parent_path(), ec);
  }
  nlohmann::json j = {{"version", 1}, {"groups", groups_}};
  write_file_atomic(path, j.dump(1) + "\n");
}

void PortfolioStats::record(TileKind kind, std::uint32_t colours, const std::string& spec, bool success,
                            double seconds) {
  auto& g = groups_[key_of(kind, colours, spec)];
  if (!g.is_object()) g = {{"tries", 0u}, {"successes", 0u}, {"success_seconds", nlohmann::json::array()}};
  g["tries"] = g["tries"].get<std::uint64_t>() + 1;
  if (success) {
    g["successes"] = g["successes"].get<std::uint64_t>() + 1;
    g["success_seconds"].push_back(seconds);
    while (g["success_seconds"].size() > 64) g["success_seconds"].erase(0);
  }
}

std::optional<GroupStats> PortfolioStats::find(TileKind kind, std::uint32_t colours, const std::string& spec) const {
  GroupStats tmp;
  auto it = groups_.find(key_of(kind, colours, spec));
  if (it == groups_.end()) return std::nullopt;
  tmp.tries = (*it)["tries"].get<std::uint64_t>();
  tmp.successes = (*it)["successes"].get<std::uint64_t>();
  tmp.success_seconds = (*it)["success_seconds"].get<std::vector<double>>();
  return tmp;
}

std::vector<std::string> PortfolioStats::order(TileKind kind, std::uint32_t colours,
                                               const std::vector<std::string>& specs) const {
  struct Ranked {
    int tier;
    double key;
    std::size_t pos;
    std::string spec;
  };
  std::vector<Ranked> r;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    auto g = find(kind, colours, specs[i]);
    if (!g || g->tries == 0)
      r.push_back({1, 0, i, specs[i]});
    else if (g->successes > 0) {
      // Expected time to a success: median success time over the success rate.
      double rate = double(g->successes) / double(g->tries);
      r.push_back({0, g->median_seconds() / rate, i, specs[i]});
    } else {
      r.push_back({2, double(g->tries), i, specs[i]});
    }
  }
  std::stable_sort(r.begin(), r.end(), [](const Ranked& a, const Ranked& b) {
    return a.tier != b.tier ? a.tier < b.tier : a.key != b.key ? a.key < b.key : a.pos < b.pos;
  });
  std::vector<std::string> out;
  for (auto& x : r) out.push_back(x.spec);
  return out;
}

nlohmann::json PortfolioStats::report() const {
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& [key, g] : groups_.items()) {
    auto a = key.find('/'), b = key.find('/', a + 1);
    GroupStats s;
    s.success_seconds = g["success_seconds"].get<std::vector<double>>();
    rows.push_back({{"kind", key.substr(0, a)},
                    {"colors", std::stoul(key.substr(a + 1, b - a - 1))},
                    {"group", key.substr(b + 1)},
                    {"tries", g["tries"]},
                    {"successes", g["successes"]},
                    {"median_seconds", s.median_seconds()}});
  }
  return {{"groups", rows}};
}

void PortfolioStats::merge(const PortfolioStats& other) {
  for (const auto& [key, g] : other.groups_.items()) {
    auto& mine = groups_[key];
    if (!mine.is_object()) {
      mine = g;
      continue;
    }
    mine["tries"] = mine["tries"].get<std::uint64_t>() + g["tries"].get<std::uint64_t>();
    mine["successes"] = mine["successes"].get<std::uint64_t>() + g["successes"].get<std::uint64_t>();
    for (const auto& t : g["success_seconds"]) mine["success_seconds"].push_back(t);
    while (mine["success_seconds"].size() > 64) mine["success_seconds"].erase(0);
  }
}

}  // namespace tilekit
