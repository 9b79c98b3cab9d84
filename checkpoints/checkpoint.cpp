#include "checkpoints/checkpoint.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/hash.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit {

namespace {

constexpr std::string_view kMagic = "TILEKIT-CHECKPOINT";

nlohmann::json counters_json(const SearchCounters& c) {
  return {{"solutions", c.solutions}, {"orbits", c.orbits}, {"nodes", c.nodes}};
}

SearchCounters counters_from(const nlohmann::json& j) {
  SearchCounters c;
  c.solutions = j.at("solutions").get<std::uint64_t>();
  c.orbits = j.at("orbits").get<std::uint64_t>();
  c.nodes = j.at("nodes").get<std::uint64_t>();
  return c;
}

std::string bitmap_hex(const std::vector<bool>& bits) {
  std::string s((bits.size() + 3) / 4, '0');
  for (std::size_t i = 0; i < bits.size(); ++i)
    if (bits[i]) {
      char& ch = s[i / 4];
      int v = (ch <= '9' ? ch - '0' : ch - 'a' + 10) | (1 << (i % 4));
      ch = "0123456789abcdef"[v];
    }
  return s;
}

std::vector<bool> bitmap_from(const std::string& s, std::size_t n) {
  if (s.size() != (n + 3) / 4) throw std::runtime_error("finished bitmap has the wrong length");
  std::vector<bool> bits(n);
  for (std::size_t i = 0; i < n; ++i) {
    char ch = s[i / 4];
    int v = ch >= '0' && ch <= '9' ? ch - '0' : ch >= 'a' && ch <= 'f' ? ch - 'a' + 10 : -1;
    if (v < 0) throw std::runtime_error("finished bitmap is not hexadecimal");
    bits[i] = (v >> (i % 4)) & 1;
  }
  return bits;
}

}  // namespace

std::string encode_checkpoint(const SearchState& st) {
  nlohmann::json in_flight = nlohmann::json::array();
  for (const InFlightSubproblem& f : st.in_flight) {
    nlohmann::json path = nlohmann::json::array();
    for (const Decision& d : f.path) path.push_back({d.var, d.value});
    in_flight.push_back({{"index", f.index}, {"path", path}, {"counted", counters_json(f.counted)}});
  }
  nlohmann::json body = {{"fingerprint", st.fingerprint},
                         {"subproblems", st.subproblem_count},
                         {"subproblem_hash", fmt::format("{:016x}", st.subproblem_hash)},
                         {"finished", bitmap_hex(st.finished)},
                         {"finished_counts", counters_json(st.finished_counts)},
                         {"in_flight", in_flight},
                         {"restarts", st.restarts},
                         {"restart_nodes", st.restart_nodes},
                         {"seconds", st.seconds}};
  return seal_checkpoint(kMagic, kCheckpointVersion, body.dump());
}

std::string seal_checkpoint(std::string_view magic, int version, std::string_view body) {
  return fmt::format("{} {}\nbytes {} fnv1a64 {:016x}\n{}", magic, version, body.size(), fnv1a64(body), body);
}

std::string_view open_checkpoint(std::string_view text, std::string_view magic, int version, const std::string& origin) {
  auto bad = [&](const std::string& why) { return InputError(fmt::format("checkpoint {}: {}", origin, why)); };
  auto eol1 = text.find('\n');
  if (eol1 == std::string_view::npos || text.substr(0, magic.size()) != magic || text.size() <= magic.size() ||
      text[magic.size()] != ' ')
    throw bad("not a Tilekit checkpoint file" + (magic == kMagic ? std::string() : fmt::format(" of this kind ({})", magic)));
  std::string ver(text.substr(magic.size() + 1, eol1 - magic.size() - 1));
  if (ver != std::to_string(version))
    throw bad(fmt::format("format version {} is not supported (this build reads version {})", ver, version));
  auto eol2 = text.find('\n', eol1 + 1);
  if (eol2 == std::string_view::npos) throw bad("truncated (no header)");
  std::string header(text.substr(eol1 + 1, eol2 - eol1 - 1));
  std::size_t bytes = 0;
  unsigned long long sum = 0;
  char word1[16] = {}, word2[16] = {};
  if (std::sscanf(header.c_str(), "%15s %zu %15s %llx", word1, &bytes, word2, &sum) != 4 ||
      std::string(word1) != "bytes" || std::string(word2) != "fnv1a64")
    throw bad("corrupt header");
  std::string_view body = text.substr(eol2 + 1);
  if (body.size() < bytes) throw bad(fmt::format("truncated ({} of {} bytes)", body.size(), bytes));
  if (body.size() > bytes) throw bad(fmt::format("corrupt ({} bytes after the end)", body.size() - bytes));
  if (fnv1a64(body) != sum) throw bad("corrupt (checksum mismatch)");
  return body;
}

SearchState decode_checkpoint(std::string_view text, const std::string& origin) {
  auto bad = [&](const std::string& why) { return InputError(fmt::format("checkpoint {}: {}", origin, why)); };
  std::string_view body = open_checkpoint(text, kMagic, kCheckpointVersion, origin);
  SearchState st;
  try {
    nlohmann::json j = nlohmann::json::parse(body);
    st.fingerprint = j.at("fingerprint").get<std::string>();
    st.subproblem_count = j.at("subproblems").get<std::uint64_t>();
    st.subproblem_hash = std::stoull(j.at("subproblem_hash").get<std::string>(), nullptr, 16);
    st.finished = bitmap_from(j.at("finished").get<std::string>(), st.subproblem_count);
    st.finished_counts = counters_from(j.at("finished_counts"));
    for (const auto& f : j.at("in_flight")) {
      InFlightSubproblem s;
      s.index = f.at("index").get<std::uint64_t>();
      for (const auto& d : f.at("path")) s.path.push_back({d.at(0).get<int>(), d.at(1).get<int>()});
      s.counted = counters_from(f.at("counted"));
      st.in_flight.push_back(std::move(s));
    }
    st.restarts = j.at("restarts").get<std::uint64_t>();
    st.restart_nodes = j.at("restart_nodes").get<std::uint64_t>();
    st.seconds = j.at("seconds").get<double>();
  } catch (const std::exception& e) {
    throw bad(fmt::format("corrupt body ({})", e.what()));
  }
  return st;
}

void write_checkpoint(const std::string& path, const SearchState& state) {
  write_file_atomic(path, encode_checkpoint(state));
}

SearchState read_checkpoint(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("checkpoint {}: cannot read: {}", path, std::strerror(errno)));
  std::stringstream b;
  b << in.rdbuf();
  return decode_checkpoint(b.str(), path);
}

std::string fingerprint_difference(const std::string& here, const std::string& checkpoint) {
  if (here == checkpoint) return {};
  nlohmann::json a, b;
  try {
    a = nlohmann::json::parse(here);
    b = nlohmann::json::parse(checkpoint);
  } catch (const std::exception&) {
    return "the search parameters differ";
  }
  std::vector<std::string> diffs;
  for (auto it = a.begin(); it != a.end(); ++it) {
    auto other = b.find(it.key());
    std::string theirs = other == b.end() ? "absent" : other->dump();
    if (other == b.end() || *other != it.value())
      diffs.push_back(fmt::format("{} is {} here but {} in the checkpoint", it.key(), it.value().dump(), theirs));
  }
  for (auto it = b.begin(); it != b.end(); ++it)
    if (!a.contains(it.key())) diffs.push_back(fmt::format("{} is only in the checkpoint", it.key()));
  if (diffs.empty()) return "the search parameters differ";
  return fmt::format("{}", fmt::join(diffs, "; "));
}

SearchResult solve_checkpointed(const TilingProblem& problem, SearchOptions options) {
  SearchOptions plain = options;  // the fingerprint does not depend on the file names
  plain.checkpoint_path.clear();
  plain.resume_path.clear();
  std::string here = search_fingerprint(problem, plain);
  if (!options.resume_path.empty()) {
    SearchState st = read_checkpoint(options.resume_path);
    std::string diff = fingerprint_difference(here, st.fingerprint);
    if (!diff.empty())
      throw InputError(fmt::format("checkpoint {} does not match this search: {}", options.resume_path, diff));
    options.resume_state = std::move(st);
  }
  if (!options.checkpoint_path.empty()) {
    std::string path = options.checkpoint_path;
    options.save_checkpoint = [path](const SearchState& s) { write_checkpoint(path, s); };
  }
  return solve(problem, options);
}

}  // namespace tilekit
