#include "checkpoints/checkpoint.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/hash.hpp"
#include "base/input.hpp"
#include "base/json_input.hpp"
#include "solver/solve.hpp"
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
    if (i < n)
      bits[i] = bit;
    else if (bit)
      throw j.error("bits set beyond the last subproblem");
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
  nlohmann::json each = nlohmann::json::array();
  for (const SearchCounters& c : st.finished_each) each.push_back({c.solutions, c.orbits, c.nodes});
  return {{"fingerprint", st.fingerprint},
          {"subproblems", st.subproblem_count},
          {"subproblem_hash", fmt::format("{:016x}", st.subproblem_hash)},
          {"finished", bitmap_hex(st.finished)},
          {"finished_counts", counters_json(st.finished_counts)},
          {"finished_each", each},
          {"in_flight", in_flight},
          {"restarts", st.restarts},
          {"restart_nodes", st.restart_nodes},
          {"seconds", st.seconds}};
}

// Types and ranges through JsonIn (each problem names its JSON path), then the structure
// through check_search_state (solver/search_state.hpp): a state that passes replays to the
// uninterrupted result or is refused by the engine with a clear message, never misread.
SearchState search_from(const JsonIn& j) {
  SearchState st;
  st.fingerprint = j.at("fingerprint").string();
  st.subproblem_count = j.at("subproblems").unsigned_integer(kMaxSubproblems);
  const JsonIn hash = j.at("subproblem_hash");
  const std::string hex = hash.string(16);
  auto [end, ec] = std::from_chars(hex.data(), hex.data() + hex.size(), st.subproblem_hash, 16);
  if (hex.size() != 16 || ec != std::errc() || end != hex.data() + hex.size())
    throw hash.error("not 16 hexadecimal digits");
  st.finished = bitmap_from(j.at("finished"), st.subproblem_count);
  st.finished_counts = counters_from(j.at("finished_counts"));
  const JsonIn each = j.at("finished_each");
  for (std::size_t i = 0, n = each.array(0, st.subproblem_count); i < n; ++i) {
    const JsonIn c = each[i];
    c.array(3, 3);
    st.finished_each.push_back({c[0].unsigned_integer(), c[1].unsigned_integer(), c[2].unsigned_integer()});
  }
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
    throw j.error(fmt::format("inconsistent: {}", e.what()));
  }
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
          {"side_round", ps.side_round},
          {"side_next", ps.side_next},
          {"seconds", ps.seconds},
          {"candidates", cands}};
}

// The portfolio's schedule (solver/portfolio.hpp): at least one candidate, named, each once;
// the position inside the candidate list; the round bounded (slices last first_slice * 2^round
// seconds, so 64 rounds are beyond any run); every candidate's engine state checked as above.
PortfolioState portfolio_from(const JsonIn& j) {
  PortfolioState ps;
  ps.fingerprint = j.at("fingerprint").string();
  ps.round = j.at("round").unsigned_integer(64);
  ps.next = j.at("next").unsigned_integer();
  if (auto r = j.find("side_round")) ps.side_round = r->unsigned_integer(64);  // absent before the side lane
  if (auto n = j.find("side_next")) ps.side_next = n->unsigned_integer();
  ps.seconds = j.at("seconds").number(0);
  const JsonIn cands = j.at("candidates");
  const std::size_t n = cands.array(1, 1 << 16);
  for (std::size_t k = 0; k < n; ++k) {
    const JsonIn c = cands[k];
    PortfolioCandidateState cs;
    cs.name = c.at("name").string(4096);
    if (cs.name.empty()) throw c.at("name").error("a candidate has no name");
    for (const auto& other : ps.candidates)
      if (other.name == cs.name) throw c.at("name").error(fmt::format("candidate {} is listed twice", cs.name));
    cs.empty = c.at("empty").boolean();
    cs.slices = c.at("slices").unsigned_integer();
    cs.nodes = c.at("nodes").unsigned_integer();
    cs.seconds = c.at("seconds").number(0);
    if (auto e = c.find("engine")) cs.engine = search_from(*e);
    ps.candidates.push_back(std::move(cs));
  }
  if (ps.next > ps.candidates.size())
    throw j.at("next").error(
        fmt::format("schedule position {} is past the {} candidates", ps.next, ps.candidates.size()));
  if (ps.side_next > ps.candidates.size())
    throw j.at("side_next").error(
        fmt::format("side-lane position {} is past the {} candidates", ps.side_next, ps.candidates.size()));
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

CheckpointFile decode_checkpoint_file(std::string_view text, const std::string& origin) {
  auto bad = [&](const std::string& why) { return InputError(fmt::format("checkpoint {}: {}", origin, why)); };
  std::string_view body = open_checkpoint(text, kMagic, kCheckpointVersion, kCheckpointVersion, origin);
  const std::string where = fmt::format("checkpoint {}", origin);
  const nlohmann::json doc = parse_json_input(body, where);
  const JsonIn j(doc, where);
  j.object();
  CheckpointFile f;
  const JsonIn request = j.at("request");
  if (!request.raw().is_null()) request.object();
  f.request = request.raw();
  const auto search = j.find("search"), portfolio = j.find("portfolio");
  if (search.has_value() == portfolio.has_value())
    throw bad("the body holds neither or both of a search and a portfolio state");
  if (search)
    f.search = search_from(*search);
  else
    f.portfolio = portfolio_from(*portfolio);
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
  return decode_checkpoint_file(read_input_file(path, "checkpoint"), path);
}

SearchState read_checkpoint(const std::string& path) {
  CheckpointFile f = read_checkpoint_file(path);
  if (!f.search) throw InputError(fmt::format("checkpoint {}: holds a portfolio, not a single search", path));
  return std::move(*f.search);
}

std::string fingerprint_difference(const std::string& here, const std::string& checkpoint) {
  if (here == checkpoint) return {};
  // The checkpoint's fingerprint is outside input (JSON held as text in a string field): it goes
  // through the same depth-limited parser as every other document, and anything but an object
  // of parameters is simply "different".
  nlohmann::json a, b;
  try {
    a = parse_json_input(here, "fingerprint");
    b = parse_json_input(checkpoint, "fingerprint");
  } catch (const InputError&) {
    return "the search parameters differ";
  }
  if (!a.is_object() || !b.is_object()) return "the search parameters differ";
  auto shown = [](const nlohmann::json& v) {
    std::string s = v.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    return s.size() > 200 ? s.substr(0, 197) + "..." : s;
  };
  std::vector<std::string> diffs;
  for (auto it = a.begin(); it != a.end(); ++it) {
    auto other = b.find(it.key());
    if (other == b.end() || *other != it.value())
      diffs.push_back(fmt::format("{} is {} here but {} in the checkpoint", it.key(), shown(it.value()),
                                  other == b.end() ? std::string("absent") : shown(*other)));
  }
  for (auto it = b.begin(); it != b.end(); ++it)
    if (!a.contains(it.key()))
      diffs.push_back(fmt::format("{} is only in the checkpoint", utf8_or_question_marks(it.key().substr(0, 200))));
  if (diffs.empty()) return "the search parameters differ";
  return fmt::format("{}", fmt::join(diffs, "; "));
}

CheckpointFile read_resume_file(const TilingProblem& problem, const SearchOptions& options,
                                const PortfolioOptions* portfolio) {
  const std::string& path = options.run.resume_path;
  CheckpointFile f = read_checkpoint_file(path);
  if (portfolio) {
    if (!f.portfolio) throw InputError(fmt::format("checkpoint {} holds a single search, not a portfolio run", path));
    SearchOptions plain = options;
    plain.run.checkpoint_path.clear();
    plain.run.resume_path.clear();
    std::string diff = fingerprint_difference(portfolio_fingerprint(problem, plain, *portfolio), f.portfolio->fingerprint);
    if (!diff.empty()) throw InputError(fmt::format("checkpoint {} does not match this portfolio: {}", path, diff));
  } else {
    if (!f.search) throw InputError(fmt::format("checkpoint {} holds a portfolio run, not a single search", path));
    SearchOptions plain = options;  // the fingerprint does not depend on the file names
    plain.run.checkpoint_path.clear();
    plain.run.resume_path.clear();
    std::string diff = fingerprint_difference(search_fingerprint(problem, plain), f.search->fingerprint);
    if (!diff.empty()) throw InputError(fmt::format("checkpoint {} does not match this search: {}", path, diff));
  }
  return f;
}

std::string rank_checkpoint_path(const std::string& path, int rank) {
  return rank == 0 ? path : fmt::format("{}.rank-{}", path, rank);
}

std::vector<std::string> rank_checkpoint_files(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path p(path);
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  const std::string prefix = p.filename().string() + ".rank-";
  std::vector<std::string> out;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() > prefix.size() && name.compare(0, prefix.size(), prefix) == 0 &&
        name.find_first_not_of("0123456789", prefix.size()) == std::string::npos)
      out.push_back((p.parent_path() / name).string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

SearchResult solve_checkpointed(const TilingProblem& problem, SearchOptions options, const nlohmann::json& request) {
  const int rank = options.run.work ? options.run.work->rank() : 0;
  if (rank == 0 && !options.run.resume_path.empty())
    options.resume_state = std::move(*read_resume_file(problem, options, nullptr).search);
  if (options.run.work && rank == 0 && !options.run.resume_path.empty()) {
    // An MPI run: what every rank of the earlier runs checkpointed, whatever their number.
    for (const std::string& f : rank_checkpoint_files(options.run.resume_path)) {
      SearchOptions other = options;
      other.run.resume_path = f;
      const CheckpointFile part = read_resume_file(problem, other, nullptr);
      try {
        merge_search_states(*options.resume_state, *part.search);
      } catch (const InputError& e) {
        throw InputError(fmt::format("checkpoint {}: {}", f, e.what()));
      }
    }
  } else if (options.run.work && rank == 0 && !options.run.checkpoint_path.empty()) {
    // A fresh MPI run: another run's rank files beside the checkpoint are not this run's.
    for (const std::string& f : rank_checkpoint_files(options.run.checkpoint_path)) std::filesystem::remove(f);
  }
  if (rank != 0) {  // takes its jobs (resumed ones with their paths) from the root
    options.run.resume_path.clear();
    if (!options.run.checkpoint_path.empty())
      options.run.checkpoint_path = rank_checkpoint_path(options.run.checkpoint_path, rank);
  }
  if (!options.run.checkpoint_path.empty()) {
    std::string path = options.run.checkpoint_path;
    options.save_checkpoint = [path, request](const SearchState& s) {
      write_checkpoint(path, CheckpointFile{request, s, {}});
    };
  }
  return solve(problem, options);
}

PortfolioResult run_portfolio_checkpointed(const TilingProblem& problem, const SearchOptions& options,
                                           PortfolioOptions portfolio, const nlohmann::json& request) {
  if (!options.run.resume_path.empty())
    portfolio.resume_state = std::move(*read_resume_file(problem, options, &portfolio).portfolio);
  if (!options.run.checkpoint_path.empty()) {
    std::string path = options.run.checkpoint_path;
    portfolio.save_checkpoint = [path, request](const PortfolioState& s) {
      write_checkpoint(path, CheckpointFile{request, {}, s});
    };
  }
  SearchOptions o = options;
  o.run.checkpoint_path.clear();
  o.run.resume_path.clear();
  return run_portfolio(problem, o, portfolio);
}

}  // namespace tilekit
