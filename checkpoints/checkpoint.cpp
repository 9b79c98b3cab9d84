#include "checkpoints/checkpoint.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <limits>
#include <nlohmann/json.hpp>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/hash.hpp"
#include "base/input.hpp"
#include "base/json_input.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit {

namespace {

constexpr std::string_view kMagic = "TILEKIT-CHECKPOINT";

nlohmann::json counters_json(const SearchCounters& c) {
  return {{"solutions", c.solutions}, {"orbits", c.orbits}, {"nodes", c.nodes}};
}

SearchCounters counters_from(const JsonIn& j) {
  SearchCounters c;
  c.solutions = j.at("solutions").unsigned_integer();
  c.orbits = j.at("orbits").unsigned_integer();
  c.nodes = j.at("nodes").unsigned_integer();
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

std::vector<bool> bitmap_from(const JsonIn& j, std::uint64_t n) {
  const std::string s = j.string(kMaxSubproblems / 4 + 1);
  if (s.size() != (n + 3) / 4) throw j.error(fmt::format("{} hex digits for {} subproblems", s.size(), n));
  std::vector<bool> bits(n);
  for (std::size_t i = 0; i < s.size() * 4; ++i) {
    char ch = s[i / 4];
    int v = ch >= '0' && ch <= '9' ? ch - '0' : ch >= 'a' && ch <= 'f' ? ch - 'a' + 10 : -1;
    if (v < 0) throw j.error("not hexadecimal");
    const bool bit = (v >> (i % 4)) & 1;
    if (i < n) bits[i] = bit;
    else if (bit) throw j.error("bits set beyond the last subproblem");
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
  std::string text = body.dump();
  return fmt::format("{} {}\nbytes {} fnv1a64 {:016x}\n{}", kMagic, kCheckpointVersion, text.size(), fnv1a64(text),
                     text);
}

SearchState decode_checkpoint(std::string_view text, const std::string& origin) {
  auto bad = [&](const std::string& why) { return InputError(fmt::format("checkpoint {}: {}", origin, why)); };
  auto eol1 = text.find('\n');
  if (eol1 == std::string_view::npos || text.substr(0, kMagic.size()) != kMagic || text.size() <= kMagic.size() ||
      text[kMagic.size()] != ' ')
    throw bad("not a Tilekit checkpoint file");
  std::string version(text.substr(kMagic.size() + 1, eol1 - kMagic.size() - 1));
  if (version != std::to_string(kCheckpointVersion))
    throw bad(
        fmt::format("format version {} is not supported (this build reads version {})", version, kCheckpointVersion));
  auto eol2 = text.find('\n', eol1 + 1);
  if (eol2 == std::string_view::npos) throw bad("truncated (no header)");
  std::string header(text.substr(eol1 + 1, eol2 - eol1 - 1));
  // "bytes <decimal> fnv1a64 <16 hex digits>", exactly.
  std::uint64_t bytes = 0, sum = 0;
  auto field = [&](std::string_view& rest, std::string_view word, std::uint64_t& value, int base) {
    if (!rest.starts_with(word) || rest.size() <= word.size() || rest[word.size()] != ' ') return false;
    rest.remove_prefix(word.size() + 1);
    const auto space = std::min(rest.find(' '), rest.size());
    auto [end, ec] = std::from_chars(rest.data(), rest.data() + space, value, base);
    if (space == 0 || ec != std::errc() || end != rest.data() + space) return false;
    rest.remove_prefix(std::min(space + 1, rest.size()));
    return true;
  };
  std::string_view rest = header;
  if (!field(rest, "bytes", bytes, 10) || !field(rest, "fnv1a64", sum, 16) || !rest.empty() ||
      header.size() - header.rfind(' ') - 1 != 16)
    throw bad("corrupt header");
  std::string_view body = text.substr(eol2 + 1);
  if (body.size() < bytes) throw bad(fmt::format("truncated ({} of {} bytes)", body.size(), bytes));
  if (body.size() > bytes) throw bad(fmt::format("corrupt ({} bytes after the end)", body.size() - bytes));
  if (fnv1a64(body) != sum) throw bad("corrupt (checksum mismatch)");
  SearchState st;
  const nlohmann::json doc = parse_json_input(body, fmt::format("checkpoint {}", origin));
  const JsonIn j(doc, fmt::format("checkpoint {}", origin));
  st.fingerprint = j.at("fingerprint").string();
  st.subproblem_count = j.at("subproblems").unsigned_integer(kMaxSubproblems);
  const JsonIn hash = j.at("subproblem_hash");
  const std::string hex = hash.string(16);
  auto [end, ec] = std::from_chars(hex.data(), hex.data() + hex.size(), st.subproblem_hash, 16);
  if (hex.empty() || ec != std::errc() || end != hex.data() + hex.size()) throw hash.error("not a hexadecimal hash");
  st.finished = bitmap_from(j.at("finished"), st.subproblem_count);
  st.finished_counts = counters_from(j.at("finished_counts"));
  const JsonIn in_flight = j.at("in_flight");
  const std::size_t n = in_flight.array(0, st.subproblem_count);
  for (std::size_t k = 0; k < n; ++k) {
    const JsonIn f = in_flight[k];
    InFlightSubproblem s;
    s.index = f.at("index").unsigned_integer();
    const JsonIn path = f.at("path");
    const std::size_t len = path.array(0, kMaxDecisionPath);
    for (std::size_t i = 0; i < len; ++i) {
      const JsonIn d = path[i];
      d.array(2, 2);
      s.path.push_back({int(d[0].integer(0, std::numeric_limits<int>::max())),
                        int(d[1].integer(0, std::numeric_limits<int>::max()))});
    }
    s.counted = counters_from(f.at("counted"));
    st.in_flight.push_back(std::move(s));
  }
  st.restarts = j.at("restarts").unsigned_integer();
  st.restart_nodes = j.at("restart_nodes").unsigned_integer();
  st.seconds = j.at("seconds").number(0);
  try {
    check_search_state(st);
  } catch (const InputError& e) {
    throw bad(fmt::format("inconsistent: {}", e.what()));
  }
  return st;
}

void write_checkpoint(const std::string& path, const SearchState& state) {
  write_file_atomic(path, encode_checkpoint(state));
}

SearchState read_checkpoint(const std::string& path) { return decode_checkpoint(read_input_file(path, "checkpoint"), path); }

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
