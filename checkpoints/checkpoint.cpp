#include "checkpoints/checkpoint.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
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
  if (n % 4 && !s.empty()) {  // the padding bits of the last digit are zero
    char ch = s.back();
    int v = ch <= '9' ? ch - '0' : ch - 'a' + 10;
    if (v >> (n % 4)) throw std::runtime_error("finished bitmap has bits past its end");
  }
  return bits;
}

nlohmann::json search_json(const SearchState& st) {
  nlohmann::json in_flight = nlohmann::json::array();
  for (const InFlightSubproblem& f : st.in_flight) {
    nlohmann::json path = nlohmann::json::array();
    for (const Decision& d : f.path) path.push_back({d.var, d.value});
    in_flight.push_back({{"index", f.index}, {"path", path}, {"counted", counters_json(f.counted)}});
  }
  return {{"fingerprint", st.fingerprint},
          {"subproblems", st.subproblem_count},
          {"subproblem_hash", fmt::format("{:016x}", st.subproblem_hash)},
          {"finished", bitmap_hex(st.finished)},
          {"finished_counts", counters_json(st.finished_counts)},
          {"in_flight", in_flight},
          {"restarts", st.restarts},
          {"restart_nodes", st.restart_nodes},
          {"seconds", st.seconds}};
}

// Structural checks beyond the JSON types: a state that passes them replays or is refused by
// the engine with a clear message, never misread.
void require(bool ok, const char* what) {
  if (!ok) throw std::runtime_error(what);
}

double seconds_from(const nlohmann::json& j) {
  double s = j.get<double>();
  require(std::isfinite(s) && s >= 0, "seconds must be a finite number >= 0");
  return s;
}

SearchState search_from(const nlohmann::json& j) {
  require(j.is_object(), "the search state is not an object");
  SearchState st;
  st.fingerprint = j.at("fingerprint").get<std::string>();
  st.subproblem_count = j.at("subproblems").get<std::uint64_t>();
  require(st.subproblem_count <= (std::uint64_t(1) << 32), "too many subproblems");
  const std::string hash = j.at("subproblem_hash").get<std::string>();
  require(hash.size() == 16 && hash.find_first_not_of("0123456789abcdef") == std::string::npos,
          "subproblem_hash is not 16 hex digits");
  st.subproblem_hash = std::stoull(hash, nullptr, 16);
  st.finished = bitmap_from(j.at("finished").get<std::string>(), st.subproblem_count);
  st.finished_counts = counters_from(j.at("finished_counts"));
  std::vector<bool> seen(st.subproblem_count, false);
  for (const auto& f : j.at("in_flight")) {
    InFlightSubproblem s;
    s.index = f.at("index").get<std::uint64_t>();
    require(s.index < st.subproblem_count, "an in-flight subproblem index is out of range");
    require(!st.finished[s.index], "an in-flight subproblem is also finished");
    require(!seen[s.index], "an in-flight subproblem is listed twice");
    seen[s.index] = true;
    for (const auto& d : f.at("path")) {
      require(d.is_array() && d.size() == 2, "a decision is not a [variable, value] pair");
      s.path.push_back({d.at(0).get<int>(), d.at(1).get<int>()});
      require(s.path.back().var >= 0 && s.path.back().value >= 0, "a decision is negative");
    }
    s.counted = counters_from(f.at("counted"));
    st.in_flight.push_back(std::move(s));
  }
  require(st.in_flight.empty() || st.subproblem_count > 0, "in-flight subproblems without subproblems");
  st.restarts = j.at("restarts").get<std::uint64_t>();
  st.restart_nodes = j.at("restart_nodes").get<std::uint64_t>();
  st.seconds = seconds_from(j.at("seconds"));
  return st;
}

nlohmann::json portfolio_json(const PortfolioState& ps) {
  nlohmann::json cands = nlohmann::json::array();
  for (const auto& c : ps.candidates)
    cands.push_back({{"name", c.name},
                     {"empty", c.empty},
                     {"slices", c.slices},
                     {"nodes", c.nodes},
                     {"seconds", c.seconds},
                     {"engine", c.engine ? search_json(*c.engine) : nlohmann::json(nullptr)}});
  return {{"fingerprint", ps.fingerprint},
          {"round", ps.round},
          {"next", ps.next},
          {"seconds", ps.seconds},
          {"candidates", cands}};
}

PortfolioState portfolio_from(const nlohmann::json& j) {
  require(j.is_object(), "the portfolio state is not an object");
  PortfolioState ps;
  ps.fingerprint = j.at("fingerprint").get<std::string>();
  ps.round = j.at("round").get<std::uint64_t>();
  ps.next = j.at("next").get<std::uint64_t>();
  ps.seconds = seconds_from(j.at("seconds"));
  std::vector<std::string> names;
  for (const auto& c : j.at("candidates")) {
    PortfolioCandidateState cs;
    cs.name = c.at("name").get<std::string>();
    require(!cs.name.empty(), "a candidate has no name");
    require(std::find(names.begin(), names.end(), cs.name) == names.end(), "a candidate is listed twice");
    names.push_back(cs.name);
    cs.empty = c.at("empty").get<bool>();
    cs.slices = c.at("slices").get<std::uint64_t>();
    cs.nodes = c.at("nodes").get<std::uint64_t>();
    cs.seconds = seconds_from(c.at("seconds"));
    if (!c.at("engine").is_null()) cs.engine = search_from(c.at("engine"));
    ps.candidates.push_back(std::move(cs));
  }
  require(!ps.candidates.empty(), "the portfolio has no candidates");
  require(ps.next <= ps.candidates.size(), "the schedule position is past the candidate list");
  require(ps.round <= 64, "the round is out of range");
  return ps;
}

}  // namespace

std::string encode_checkpoint(const CheckpointFile& f) {
  if (f.search.has_value() == f.portfolio.has_value())
    throw std::logic_error("a checkpoint holds exactly one of a search and a portfolio state");
  nlohmann::json body = {{"request", f.request}};
  if (f.search)
    body["search"] = search_json(*f.search);
  else
    body["portfolio"] = portfolio_json(*f.portfolio);
  return seal_checkpoint(kMagic, kCheckpointVersion, body.dump());
}

std::string encode_checkpoint(const SearchState& st) {
  return encode_checkpoint(CheckpointFile{nullptr, st, {}});
}

std::string seal_checkpoint(std::string_view magic, int version, std::string_view body) {
  return fmt::format("{} {}\nbytes {} fnv1a64 {:016x}\n{}", magic, version, body.size(), fnv1a64(body), body);
}

std::string_view open_checkpoint(std::string_view text, std::string_view magic, int oldest, int newest,
                                 const std::string& origin, int* version_read) {
  auto bad = [&](const std::string& why) { return InputError(fmt::format("checkpoint {}: {}", origin, why)); };
  auto eol1 = text.find('\n');
  if (eol1 == std::string_view::npos || text.substr(0, magic.size()) != magic || text.size() <= magic.size() ||
      text[magic.size()] != ' ')
    throw bad("not a Tilekit checkpoint file" +
              (magic == kMagic ? std::string() : fmt::format(" of this kind ({})", magic)));
  std::string ver(text.substr(magic.size() + 1, eol1 - magic.size() - 1));
  int version = 0;
  auto [p, ec] = std::from_chars(ver.data(), ver.data() + ver.size(), version);
  if (ec != std::errc() || p != ver.data() + ver.size() || version < oldest || version > newest)
    throw bad(oldest == newest
                  ? fmt::format("format version {} is not supported (this build reads version {})", ver, newest)
                  : fmt::format("format version {} is not supported (this build reads versions {} to {})", ver, oldest,
                                newest));
  if (version_read) *version_read = version;
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

CheckpointFile decode_checkpoint_file(std::string_view text, const std::string& origin) {
  auto bad = [&](const std::string& why) { return InputError(fmt::format("checkpoint {}: {}", origin, why)); };
  int version = 0;
  std::string_view body = open_checkpoint(text, kMagic, 1, kCheckpointVersion, origin, &version);
  CheckpointFile f;
  try {
    nlohmann::json j = nlohmann::json::parse(body);
    require(j.is_object(), "the body is not an object");
    if (version == 1) {
      f.request = nullptr;
      f.search = search_from(j);
    } else {
      f.request = j.at("request");
      require(f.request.is_null() || f.request.is_object(), "the request is not an object");
      const bool search = j.contains("search"), portfolio = j.contains("portfolio");
      require(search != portfolio, "the body holds neither or both of a search and a portfolio state");
      if (search)
        f.search = search_from(j.at("search"));
      else
        f.portfolio = portfolio_from(j.at("portfolio"));
    }
  } catch (const std::exception& e) {
    throw bad(fmt::format("corrupt body ({})", e.what()));
  }
  return f;
}

SearchState decode_checkpoint(std::string_view text, const std::string& origin) {
  CheckpointFile f = decode_checkpoint_file(text, origin);
  if (!f.search) throw InputError(fmt::format("checkpoint {}: holds a portfolio, not a single search", origin));
  return std::move(*f.search);
}

void write_checkpoint(const std::string& path, const CheckpointFile& file) {
  write_file_atomic(path, encode_checkpoint(file));
}

void write_checkpoint(const std::string& path, const SearchState& state) {
  write_file_atomic(path, encode_checkpoint(state));
}

CheckpointFile read_checkpoint_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("checkpoint {}: cannot read: {}", path, std::strerror(errno)));
  std::stringstream b;
  b << in.rdbuf();
  return decode_checkpoint_file(b.str(), path);
}

SearchState read_checkpoint(const std::string& path) {
  CheckpointFile f = read_checkpoint_file(path);
  if (!f.search) throw InputError(fmt::format("checkpoint {}: holds a portfolio, not a single search", path));
  return std::move(*f.search);
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

SearchResult solve_checkpointed(const TilingProblem& problem, SearchOptions options, const nlohmann::json& request) {
  SearchOptions plain = options;  // the fingerprint does not depend on the file names
  plain.checkpoint_path.clear();
  plain.resume_path.clear();
  std::string here = search_fingerprint(problem, plain);
  if (!options.resume_path.empty()) {
    CheckpointFile f = read_checkpoint_file(options.resume_path);
    if (!f.search)
      throw InputError(fmt::format("checkpoint {} holds a portfolio run, not a single search", options.resume_path));
    std::string diff = fingerprint_difference(here, f.search->fingerprint);
    if (!diff.empty())
      throw InputError(fmt::format("checkpoint {} does not match this search: {}", options.resume_path, diff));
    options.resume_state = std::move(*f.search);
  }
  if (!options.checkpoint_path.empty()) {
    std::string path = options.checkpoint_path;
    options.save_checkpoint = [path, request](const SearchState& s) {
      write_checkpoint(path, CheckpointFile{request, s, {}});
    };
  }
  return solve(problem, options);
}

PortfolioResult run_portfolio_checkpointed(const TilingProblem& problem, const SearchOptions& options,
                                           PortfolioOptions portfolio, const nlohmann::json& request) {
  if (!options.resume_path.empty()) {
    CheckpointFile f = read_checkpoint_file(options.resume_path);
    if (!f.portfolio)
      throw InputError(fmt::format("checkpoint {} holds a single search, not a portfolio run", options.resume_path));
    std::string diff =
        fingerprint_difference(portfolio_fingerprint(problem, options, portfolio), f.portfolio->fingerprint);
    if (!diff.empty())
      throw InputError(fmt::format("checkpoint {} does not match this portfolio: {}", options.resume_path, diff));
    portfolio.resume_state = std::move(*f.portfolio);
  }
  if (!options.checkpoint_path.empty()) {
    std::string path = options.checkpoint_path;
    portfolio.save_checkpoint = [path, request](const PortfolioState& s) {
      write_checkpoint(path, CheckpointFile{request, {}, s});
    };
    portfolio.checkpoint_every = options.checkpoint_every;
  }
  SearchOptions o = options;
  o.checkpoint_path.clear();
  o.resume_path.clear();
  return run_portfolio(problem, o, portfolio);
}

}  // namespace tilekit
