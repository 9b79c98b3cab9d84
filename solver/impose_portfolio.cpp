#include "solver/impose_portfolio.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <numeric>
#include <set>
#include <sstream>
#include <thread>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/input.hpp"
#include "base/json_input.hpp"
#include "base/parallel.hpp"
#include "base/parse.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit {
namespace {

using Clock = std::chrono::steady_clock;

// Colours as digits of a mixed radix (k1, k2, rest): pi_1 adds 1 to the first digit, pi_2 to
// the second. With k2 = 1 this is C/k1 disjoint k1-cycles (0 1 .. k1-1)(k1 .. 2k1-1)...
std::string block_cycles(std::uint32_t c, std::uint32_t k, std::uint32_t stride) {
  std::vector<std::uint32_t> p(c);
  for (std::uint32_t x = 0; x < c; ++x) {
    std::uint32_t digit = (x / stride) % k;
    p[x] = x - digit * stride + ((digit + 1) % k) * stride;
  }
  return fmt::format("{}", fmt::join(p, ","));
}

std::string key_of(TileKind kind, std::uint32_t colours, const std::string& spec) {
  return fmt::format("{}/{}/{}", kind_name(kind), colours, spec);
}

bool valid_spec(TileKind kind, std::uint32_t colours, const std::string& spec) {
  try {
    TilingProblem p = complete_packing_problem(kind, colours);
    build_group(p, spec);
    return true;
  } catch (const InputError&) {
    return false;
  }
}

}  // namespace

std::vector<std::string> candidate_groups(TileKind kind, std::uint32_t colours) {
  const std::uint32_t C = colours, K = C * C;
  std::vector<std::string> out;
  std::set<std::string> seen;
  auto add = [&](const std::string& spec) {
    if (seen.insert(spec).second && valid_spec(kind, C, spec)) out.push_back(spec);
  };
  std::vector<std::uint32_t> divisors;
  for (std::uint32_t k = C; k >= 2; --k)
    if (C % k == 0) divisors.push_back(k);
  const bool wang = kind == TileKind::Wang;
  // One generator: translation (K/k)(i, j) of order k with C/k disjoint k-cycles.
  for (std::uint32_t k : divisors) {
    std::string pi = block_cycles(C, k, 1);
    std::uint32_t s = K / k;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> dirs = {{0, 1}, {1, 1}, {1, 2}, {1, 3}};
    for (auto [i, j] : dirs) {
      if (j >= k && !(i == 0 && j == 1) && !(i == 1 && j == 1)) continue;
      if (std::gcd(std::gcd(i, j), k) != 1) continue;
      add(fmt::format("t={},{}:pi={}", s * i % K, s * j % K, pi));
      if (wang) add(fmt::format("t={},{}:pih={}", s * i % K, s * j % K, pi));
    }
  }
  // Two generators with commuting permutations acting on different digits.
  for (std::uint32_t k1 : divisors)
    for (std::uint32_t k2 : divisors) {
      if (C % (k1 * k2) != 0) continue;
      std::string p1 = block_cycles(C, k1, 1), p2 = block_cycles(C, k2, k1);
      add(fmt::format("t=0,{}:pi={};t={},0:pi={}", K / k1, p1, K / k2, p2));
      add(fmt::format("t=0,{}:pi={};t={},{}:pi={}", K / k1, p1, K / k2, K / k2, p2));
    }
  if (wang) {
    // One generator per edge direction: a group of order k^2 (up to C^2 for k = C).
    for (std::uint32_t k : divisors) {
      std::string pi = block_cycles(C, k, 1);
      add(fmt::format("t=0,{}:pih={};t={},0:piv={}", K / k, pi, K / k, pi));
    }
  }
  return out;
}

double GroupStats::median_seconds() const {
  if (success_seconds.empty()) return 0;
  std::vector<double> v = success_seconds;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

std::string PortfolioStats::default_path() {
  if (const char* p = std::getenv("TILEKIT_PORTFOLIO_STATS"); p && *p) return p;
  std::filesystem::path base;
  if (const char* x = std::getenv("XDG_DATA_HOME"); x && *x) base = x;
  else if (const char* h = std::getenv("HOME"); h && *h) base = std::filesystem::path(h) / ".local" / "share";
  else base = ".";
  return (base / "tilekit" / "portfolio-stats.json").string();
}

PortfolioStats PortfolioStats::load(const std::string& path) {
  PortfolioStats s;
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return s;
  const std::string origin = path + " (portfolio statistics; delete the file to start afresh)";
  const nlohmann::json doc = parse_json_input(read_input_file(path, "portfolio statistics file"), origin);
  const JsonIn j(doc, origin);
  if (j.at("version").integer() != 1) throw j.at("version").error("this build reads version 1");
  const JsonIn groups = j.at("groups");
  groups.object();
  for (const auto& [key, value] : groups.raw().items()) {
    const JsonIn g = groups.at(key);
    // key: KIND/C/SPEC (report() splits it)
    const auto a = key.find('/'), b = a == std::string::npos ? a : key.find('/', a + 1);
    if (b == std::string::npos || (key.substr(0, a) != "wang" && key.substr(0, a) != "corner"))
      throw g.error("the key is not KIND/COLOURS/GROUP");
    parse_integer(std::string_view(key).substr(a + 1, b - a - 1), 1, 255, g.path() + " colours");
    const std::uint64_t tries = g.at("tries").unsigned_integer();
    g.at("successes").unsigned_integer(tries);  // never more successes than tries
    const JsonIn seconds = g.at("success_seconds");
    const std::size_t n = seconds.array(0, 64);
    for (std::size_t i = 0; i < n; ++i) seconds[i].number(0);
  }
  s.groups_ = groups.raw();
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
    if (!g || g->tries == 0) r.push_back({1, 0, i, specs[i]});
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

PortfolioResult run_portfolio(TileKind kind, std::uint32_t colours, const SearchOptions& options,
                              const PortfolioOptions& portfolio) {
  checked_thread_count(options.threads);
  const auto t0 = Clock::now();
  const TilingProblem problem = complete_packing_problem(kind, colours);
  const std::string stats_path = portfolio.stats_path.empty() ? PortfolioStats::default_path() : portfolio.stats_path;
  const bool persist = stats_path != "-";
  PortfolioStats stats = persist ? PortfolioStats::load(stats_path) : PortfolioStats{};

  std::vector<std::string> specs = portfolio.specs;
  if (specs.empty()) {
    specs = candidate_groups(kind, colours);
    if (portfolio.include_plain) specs.push_back(kPlainSearch);
  }
  auto group_part = [](const std::string& s) { return s.rfind("sat:", 0) == 0 ? s.substr(4) : s; };
  for (auto& s : specs)
    if (s != kPlainSearch) build_group(problem, group_part(s));  // a bad user-given candidate is an InputError
  specs = stats.order(kind, colours, specs);

  const auto deadline = options.time_limit > 0
                            ? t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(options.time_limit))
                            : Clock::time_point::max();
  std::atomic<bool> found{false};
  std::atomic<std::uint64_t> next_task{0}, nodes{0};
  std::mutex mu;
  PortfolioResult out;
  PortfolioStats fresh;  // this run's tries, merged into the file at the end
  std::map<std::string, nlohmann::json> per_spec;
  std::exception_ptr failure;
  std::set<std::string> exhausted;  // subspaces proved empty: never scheduled again

  auto worker = [&] {
    try {
      while (!found.load()) {
        std::uint64_t task = next_task++;
        std::uint64_t round = task / specs.size();
        const std::string& spec = specs[task % specs.size()];
        {
          std::lock_guard<std::mutex> lock(mu);
          if (exhausted.size() == specs.size()) return;
          if (exhausted.count(spec)) continue;
        }
        double slice = portfolio.first_slice * double(std::uint64_t(1) << std::min<std::uint64_t>(round, 20));
        double left = std::chrono::duration<double>(deadline - Clock::now()).count();
        if (left <= 0) return;
        SearchOptions o;
        o.mode = SearchMode::First;
        o.threads = 1;
        o.seed = options.seed * 7919 + task;
        o.time_limit = std::min(slice, left);
        SearchResult r;
        nlohmann::json group;
        if (spec == kPlainSearch) {
          r = solve(problem, o);
        } else {
          SymmetricControl ctl;
          ctl.stop = &found;
          ctl.sat = spec.rfind("sat:", 0) == 0;
          SymmetricResult sr = solve_symmetric(problem, build_group(problem, group_part(spec)), o, ctl);
          r = std::move(sr.result);
          group = std::move(sr.group);
        }
        nodes += r.nodes;
        bool success = !r.found.empty();
        std::lock_guard<std::mutex> lock(mu);
        if (r.complete && !success) exhausted.insert(spec);
        auto& row = per_spec[spec];
        if (row.is_null()) row = {{"group", spec}, {"tries", 0}, {"nodes", 0}, {"seconds", 0.0}, {"found", false}};
        row["tries"] = row["tries"].get<int>() + 1;
        row["nodes"] = row["nodes"].get<std::uint64_t>() + r.nodes;
        row["seconds"] = row["seconds"].get<double>() + r.seconds;
        // A slice cut short by another worker's success says nothing about this group.
        bool cut_short = !success && found.load() && r.seconds < o.time_limit * 0.9;
        if (!cut_short) fresh.record(kind, colours, spec, success, r.seconds);
        if (success && !found.exchange(true)) {
          row["found"] = true;
          out.found = true;
          out.spec = spec;
          out.result = std::move(r);
          out.group = std::move(group);
        }
        if (options.progress && !success)
          std::cerr << fmt::format("portfolio: {} round {} ({:.2f} s slice): nothing yet\n", spec, round, o.time_limit);
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(mu);
      if (!failure) failure = std::current_exception();
      found = true;
    }
  };
  std::atomic<int> running{options.threads};
  std::vector<std::thread> pool;
  for (int i = 0; i < options.threads; ++i)
    pool.emplace_back([&] {
      worker();
      --running;
    });
  while (running.load() > 0) {  // fold an external stop into first-found-wins
    if (portfolio.stop && portfolio.stop->load()) found = true;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  for (auto& th : pool) th.join();
  if (failure) std::rethrow_exception(failure);

  out.nodes = nodes.load();
  out.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  for (const auto& spec : specs)
    if (per_spec.count(spec)) out.runs.push_back(per_spec[spec]);
  if (out.found && options.on_solution) options.on_solution(out.result.found.front());
  if (persist) {
    PortfolioStats latest = PortfolioStats::load(stats_path);  // others may have written meanwhile
    latest.merge(fresh);
    latest.save(stats_path);
  }
  return out;
}

}  // namespace tilekit
