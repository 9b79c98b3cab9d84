// The portfolio: candidate subspace searches in doubling time slices over solve(), resumable
// and shardable (portfolio.hpp).
#include "solver/portfolio.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <atomic>
#include <cassert>
#include <chrono>
#include <cmath>
#include <mutex>
#include <numeric>
#include <optional>
#include <set>
#include <thread>

#include "base/error.hpp"
#include "base/signals.hpp"
#include "solver/colour_lift_model.hpp"
#include "solver/impose_domain.hpp"
#include "solver/sat_cnf.hpp"
#include "solver/solve.hpp"
#include "tilesets/constructions.hpp"

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

std::vector<std::string> lift_candidates(TileKind kind, std::uint32_t colours) {
  std::vector<std::string> out;
  if (kind != TileKind::Corner) return out;  // Wang packings are constructed for every C
  for (std::uint32_t m = colours / 2; m >= 2; --m) {
    if (colours % m != 0 || !construct_packing(kind, m)) continue;
    out.push_back(fmt::format("lift:{}", m));
    if (sat_solver_available()) out.push_back(fmt::format("lift-sat:{}", m));
  }
  return out;
}

std::vector<std::string> default_candidates(TileKind kind, std::uint32_t colours) {
  std::vector<std::string> out = candidate_groups(kind, colours);
  for (auto& l : lift_candidates(kind, colours)) out.push_back(l);
  out.push_back(kPlainSearch);
  return out;
}

// ---- the candidate families ----------------------------------------------------------------
// A family turns a name into a runnable subspace search. To add one, write its maker and add a
// row to kFamilies: the portfolio, its checkpoints, shards and statistics then take it like
// the others (solver/README.md).
namespace {

SearchResult run_plain(const TilingProblem& p, SearchOptions o) {
  return solve(p, o);
}

Candidate make_plain(const TilingProblem&, const std::string& name, const std::string&) {
  return {name, "plain", "", true, true, run_plain};
}

Candidate make_impose(const TilingProblem& problem, const std::string& name, const std::string& spec) {
  const std::string group = build_group(problem, spec).spec_text();  // InputError for a bad group
  auto run = [spec](const TilingProblem& p, SearchOptions o) {
    o.impose = spec;
    return solve(p, o);
  };
  return {name, "impose", group, true, true, run};
}

Candidate make_sat(const TilingProblem& problem, const std::string& name, const std::string& spec) {
  const std::string group = build_group(problem, spec).spec_text();
  auto run = [spec](const TilingProblem& p, SearchOptions o) {
    o.impose = spec;
    o.formulation = Formulation::Sat;
    o.run.shard = {};  // a sat candidate runs in one shard (see run_portfolio)
    o.save_checkpoint = nullptr;
    o.resume_state.reset();
    return solve(p, o);
  };
  return {name, "sat", group, false, false, run};
}

// Colour-quotient lifts A = B + m*E over a packing B of m colours (colour_lift_model.hpp): the engine's
// tile-per-cell quotient, most constrained first ("lift:SPEC"), or its CNF for cadical
// ("lift-sat:SPEC", one run per slice like "sat:").
Candidate make_lift(const TilingProblem& problem, const std::string& name, const std::string& spec) {
  make_lift_problem(problem.set.kind(), problem.set.colours(), parse_lift_spec(spec));  // InputError when impossible
  auto run = [spec](const TilingProblem& p, SearchOptions o) {
    o.lift = spec;
    o.formulation = Formulation::Cell;
    return solve(p, o);
  };
  return {name, "lift", "", true, true, run};
}

Candidate make_lift_sat(const TilingProblem& problem, const std::string& name, const std::string& spec) {
  make_lift_problem(problem.set.kind(), problem.set.colours(), parse_lift_spec(spec));
  auto run = [spec](const TilingProblem& p, SearchOptions o) {
    o.lift = spec;
    o.formulation = Formulation::Sat;
    o.run.shard = {};  // runs in one shard (see run_portfolio)
    o.save_checkpoint = nullptr;
    o.resume_state.reset();
    return solve(p, o);
  };
  return {name, "lift-sat", "", false, false, run};
}

struct Family {
  const char* prefix;  // a name starting with it belongs to the family (the rest is its argument)
  bool exact;          // the name is the prefix itself
  Candidate (*make)(const TilingProblem&, const std::string& name, const std::string& arg);
};

constexpr Family kFamilies[] = {
    {"plain", true, make_plain}, {"impose:", false, make_impose},     {"sat:", false, make_sat},
    {"lift:", false, make_lift}, {"lift-sat:", false, make_lift_sat},
};

}  // namespace

Candidate make_candidate(const TilingProblem& problem, const std::string& name) {
  for (const Family& f : kFamilies) {
    const std::string prefix = f.prefix;
    if (f.exact ? name == prefix : name.rfind(prefix, 0) == 0) return f.make(problem, name, name.substr(prefix.size()));
  }
  if (name.find('=') != std::string::npos) return make_impose(problem, name, name);  // a bare group spec
  throw InputError(
      fmt::format("unknown portfolio candidate '{}' (plain, SPEC, impose:SPEC, sat:SPEC, lift:M or lift-sat:M)", name));
}

// ---- the scheduler -----------------------------------------------------------------------
std::string portfolio_fingerprint(const TilingProblem& problem, const SearchOptions& options,
                                  const PortfolioOptions& portfolio) {
  SearchOptions base;
  base.mode = SearchMode::First;
  base.run.seed = options.run.seed;
  base.run.shard = options.run.shard;
  std::vector<std::string> names = portfolio.candidates.empty()
                                       ? default_candidates(problem.set.kind(), problem.set.colours())
                                       : portfolio.candidates;
  std::sort(names.begin(), names.end());
  nlohmann::json j = nlohmann::json::parse(search_fingerprint(problem, base));
  for (const char* k : {"formulation", "ordering", "restarts", "restart_base", "subproblems"}) j.erase(k);
  j["portfolio"] = 1;
  j["candidates"] = names;
  j["first_slice"] = portfolio.first_slice;
  return j.dump();
}

namespace {

// Two lanes when there are threads to spare. Candidates that restart from scratch each slice
// (cadical's: sat, lift-sat) are one thread each and lose everything at the end of a slice, so
// in the engine's round-robin they reach a long enough slice only after every engine candidate
// has had as long (C=8 corner: about 90 s for a 3 s cadical run). With two or more threads
// they run in a side lane instead, one at a time on their own doubling schedule, beside the
// engine candidates, which then get one thread fewer. The first solution in either lane cancels
// the other (RunSettings::cancel). On one thread every candidate takes its turn in one lane.
class Scheduler {
 public:
  Scheduler(const TilingProblem& p, const SearchOptions& o, const PortfolioOptions& po) : p_(p), o_(o), po_(po) {}

  PortfolioResult run();

 private:
  void save() {  // holds mu_
    if (!po_.save_checkpoint) return;
    state_.seconds = prior_seconds_ + elapsed();
    po_.save_checkpoint(state_);
    ++out_.checkpoints;
  }
  double elapsed() const { return std::chrono::duration<double>(Clock::now() - t0_).count(); }
  void start();
  bool mine(std::size_t i) const {  // a candidate that cannot be split runs in one shard
    return candidates_[i].splittable || o_.run.shard.owns(i);
  }
  bool on_side(std::size_t i) const { return side_lane_ && !candidates_[i].resumable; }
  bool live(std::size_t i) const { return mine(i) && !state_.candidates[i].empty; }  // holds mu_
  // The length of a slice in `round`, cut to the time left; 0 when the time limit has passed.
  double slice_seconds(std::uint64_t round) const {
    double seconds = po_.first_slice * double(std::uint64_t(1) << std::min<std::uint64_t>(round, 20));
    seconds = std::min(seconds, Deadline(o_.run.time_limit, t0_).seconds_left());
    return std::max(seconds, 0.0);
  }
  bool stopping() const {
    return cancel_.load() || (o_.run.catch_signals && SignalCatcher::caught());
  }
  void slice(std::size_t i, double seconds, int threads);
  void side();

  const TilingProblem& p_;
  const SearchOptions& o_;
  const PortfolioOptions& po_;
  PortfolioState state_;  // with out_ and fresh_, guarded by mu_ while the side lane runs
  std::vector<Candidate> candidates_;
  PortfolioStats fresh_;  // this run's slices, merged into the statistics file at the end
  PortfolioResult out_;
  std::mutex mu_;
  bool side_lane_ = false;            // the restarting candidates run in their own lane
  std::atomic<bool> side_busy_{false};  // the side lane has candidates left to run
  std::atomic<bool> cancel_{false};     // a solution was found: every lane stops
  std::mutex solution_mu_;
  std::optional<std::size_t> reported_by_;  // the candidate whose packing was reported
  Clock::time_point t0_ = Clock::now();
  double prior_seconds_ = 0;
};

void Scheduler::start() {
  const std::string fp = portfolio_fingerprint(p_, o_, po_);
  if (po_.resume_state) {
    state_ = *po_.resume_state;
    if (state_.fingerprint != fp)
      throw InputError("checkpoint does not match this portfolio (different problem, seed, shard or candidates)");
    // The schedule's candidates must be the ones the fingerprint names (a checksum proves only
    // that the file is as written, not that its parts agree).
    std::vector<std::string> listed, named =
        po_.candidates.empty() ? default_candidates(p_.set.kind(), p_.set.colours()) : po_.candidates;
    for (const auto& c : state_.candidates) listed.push_back(c.name);
    std::sort(listed.begin(), listed.end());
    std::sort(named.begin(), named.end());
    if (listed != named)
      throw InputError(fmt::format("checkpoint lists the candidates {} but its fingerprint names {}",
                                   fmt::join(listed, ","), fmt::join(named, ",")));
    // "Exhausted" is re-derived, not trusted: every candidate marked empty is scheduled again.
    // An engine candidate resumes its own engine state, which the engine checks against its
    // split (check_search_state) and, when every subproblem is finished, ends at once as
    // exhausted; a restarting one (cadical) runs again. So the run ends "no packing exists"
    // only when the searches themselves say so again.
    for (auto& c : state_.candidates) c.empty = false;
    prior_seconds_ = state_.seconds;
  } else {
    std::vector<std::string> names =
        po_.candidates.empty() ? default_candidates(p_.set.kind(), p_.set.colours()) : po_.candidates;
    if (!po_.stats_path.empty() && po_.stats_path != "-")  // learned order first
      names = PortfolioStats::load(po_.stats_path).order(p_.set.kind(), p_.set.colours(), names);
    state_.fingerprint = fp;
    for (const auto& n : names) state_.candidates.push_back({n, false, 0, 0, 0, std::nullopt});
  }
  std::set<std::string> seen;
  for (const auto& c : state_.candidates) {
    if (!seen.insert(c.name).second) throw InputError(fmt::format("portfolio candidate '{}' is listed twice", c.name));
    candidates_.push_back(make_candidate(p_, c.name));
  }
  if (candidates_.empty()) throw InputError("the portfolio has no candidates");
  bool restarting = false, engine = false;
  for (std::size_t i = 0; i < candidates_.size(); ++i) {
    if (!live(i)) continue;
    (candidates_[i].resumable ? engine : restarting) = true;
  }
  side_lane_ = o_.run.threads >= 2 && restarting && engine;
  side_busy_ = side_lane_;
}

void Scheduler::slice(std::size_t i, double seconds, int threads) {
  const Candidate& cand = candidates_[i];
  SearchOptions o = o_;
  o.mode = SearchMode::First;
  o.run.threads = threads;
  o.run.time_limit = seconds;
  o.run.cancel = &cancel_;
  // Both lanes may find a packing at once: the first to report it wins, and only its packing
  // reaches the caller's hook (which is never called concurrently).
  o.on_solution = [this, i](const Tiling& t) {
    std::lock_guard lock(solution_mu_);
    if (reported_by_) return;
    reported_by_ = i;
    cancel_ = true;
    if (o_.on_solution) o_.on_solution(t);
  };
  o.estimate_probes = 0;
  o.save_checkpoint = nullptr;
  o.resume_state.reset();
  {
    std::lock_guard lock(mu_);
    o.title = fmt::format("portfolio {} round {}", cand.name, on_side(i) ? state_.side_round : state_.round);
    if (cand.resumable) {
      o.resume_state = state_.candidates[i].engine;
      o.run.checkpoint_every = po_.save_checkpoint ? o_.run.checkpoint_every : 0;
      o.save_checkpoint = [this, i](const SearchState& st) {
        std::lock_guard lock(mu_);
        state_.candidates[i].engine = st;
        save();
      };
    }
  }
  // A resumed engine reports its nodes cumulatively, the resumed state's included.
  const std::uint64_t nodes_before = o.resume_state ? counted_nodes(*o.resume_state) : 0;
  SearchResult r = cand.run(p_, o);
  assert(r.found.size() <= 1);
  bool success = !r.found.empty();
  if (success) {
    std::lock_guard lock(solution_mu_);
    if (!reported_by_) reported_by_ = i;  // a path that did not call the hook
    success = reported_by_ == i;          // else the other lane's packing was reported first
  }
  std::lock_guard lock(mu_);
  PortfolioCandidateState& cs = state_.candidates[i];
  cs.slices += 1;
  cs.nodes += r.nodes - std::min(r.nodes, nodes_before);
  cs.seconds += r.seconds;
  out_.stats += r.stats;
  // A slice cut short by a signal or by the other lane's solution says nothing about the candidate.
  if (!r.interrupted && (success || !cancel_.load()))
    fresh_.record(p_.set.kind(), p_.set.colours(), cand.name, success, r.seconds);
  if (success) {
    out_.found = true;
    out_.winner = cand.name;
    out_.result = std::move(r);
    cancel_ = true;
    return;
  }
  if (r.complete) cs.empty = true;  // exhausted without a solution: never scheduled again
  if (r.interrupted) {
    out_.interrupted = true;
    out_.signal = r.signal;
  }
}

// The side lane: the restarting candidates in doubling rounds of their own, one thread.
void Scheduler::side() {
  for (;;) {
    std::size_t i = 0;
    double seconds = 0;
    {
      std::lock_guard lock(mu_);
      bool any = false;
      for (std::size_t k = 0; k < candidates_.size(); ++k) any = any || (on_side(k) && live(k));
      if (!any || stopping() || out_.interrupted) break;
      if (state_.side_next >= candidates_.size()) {
        ++state_.side_round;
        state_.side_next = 0;
        continue;
      }
      i = std::size_t(state_.side_next);
      if (!on_side(i) || !live(i)) {
        ++state_.side_next;
        continue;
      }
      seconds = slice_seconds(state_.side_round);
      if (seconds <= 0) break;
    }
    slice(i, seconds, 1);
    std::lock_guard lock(mu_);
    if (out_.found || out_.interrupted) break;
    ++state_.side_next;
    save();
  }
  side_busy_ = false;
}

PortfolioResult Scheduler::run() {
  start();
  {
    std::lock_guard lock(mu_);
    save();  // the first checkpoint, before any work
  }
  std::thread side_lane;
  if (side_lane_) side_lane = std::thread([this] { side(); });
  bool lanes_done = false;  // the engine lane ran out of candidates
  for (;;) {
    if (o_.run.catch_signals && SignalCatcher::caught()) {
      std::lock_guard lock(mu_);
      out_.interrupted = true;
      out_.signal = SignalCatcher::caught();
      break;
    }
    std::size_t i = 0;
    double seconds = 0;
    {
      std::lock_guard lock(mu_);
      if (out_.found || out_.interrupted) break;
      bool any = false;
      for (std::size_t k = 0; k < candidates_.size(); ++k) any = any || (!on_side(k) && live(k));
      if (!any) {  // only the side lane's candidates may be left: its end is the run's
        lanes_done = true;
        break;
      }
      if (state_.next >= candidates_.size()) {
        ++state_.round;
        state_.next = 0;
        continue;
      }
      i = std::size_t(state_.next);
      if (on_side(i) || !live(i)) {
        ++state_.next;
        continue;
      }
      seconds = slice_seconds(state_.round);
      if (seconds <= 0) {
        out_.timed_out = true;
        break;
      }
    }
    slice(i, seconds, side_busy_ ? o_.run.threads - 1 : o_.run.threads);
    std::lock_guard lock(mu_);
    if (out_.found || out_.interrupted) break;
    ++state_.next;
    save();
  }
  if (!lanes_done) cancel_ = true;  // whatever ended the engine lane ends the side lane
  if (side_lane.joinable()) side_lane.join();
  std::lock_guard lock(mu_);
  if (lanes_done && !out_.found && !out_.interrupted) {
    bool any = false;
    for (std::size_t k = 0; k < candidates_.size(); ++k) any = any || live(k);
    (any ? out_.timed_out : out_.complete) = true;
  }
  if (out_.found) out_.timed_out = out_.complete = false;
  save();
  out_.seconds = elapsed();
  out_.total_seconds = prior_seconds_ + out_.seconds;
  out_.nodes = 0;
  for (std::size_t i = 0; i < candidates_.size(); ++i) {
    const auto& cs = state_.candidates[i];
    out_.nodes += cs.nodes;
    if (cs.slices == 0) continue;
    out_.runs.push_back({{"group", cs.name},
                         {"tries", cs.slices},
                         {"nodes", cs.nodes},
                         {"seconds", cs.seconds},
                         {"found", out_.found && out_.winner == cs.name},
                         {"empty", cs.empty}});
  }
  if (!po_.stats_path.empty() && po_.stats_path != "-") {
    PortfolioStats latest = PortfolioStats::load(po_.stats_path);  // others may have written meanwhile
    latest.merge(fresh_);
    latest.save(po_.stats_path);
  }
  return out_;
}

}  // namespace

SearchResult PortfolioResult::as_search_result(int threads) const {
  SearchResult r = result;
  r.nodes = nodes;
  r.seconds = seconds;
  r.total_seconds = total_seconds;
  r.threads = threads;
  r.interrupted = interrupted;
  r.signal = signal;
  r.timed_out = timed_out;
  r.checkpoints = checkpoints;
  r.formulation = "portfolio";
  r.stats = stats;
  bool plain_ran = false;
  for (const auto& row : runs) plain_ran = plain_ran || row["group"] == kPlainSearch;
  r.complete = complete && plain_ran;
  return r;
}

PortfolioResult run_portfolio(const TilingProblem& problem, const SearchOptions& options,
                              const PortfolioOptions& portfolio) {
  if (options.mode != SearchMode::First)
    throw RequestError("mode", "the portfolio finds one packing: use it with `mode` first");
  if (portfolio.first_slice <= 0) throw InputError("the portfolio's first slice must be positive");
  PortfolioOptions po = portfolio;
  if (po.stats_path.empty()) po.stats_path = PortfolioStats::default_path();
  std::optional<SignalCatcher> signals;
  if (options.run.catch_signals) signals.emplace();
  return Scheduler(problem, options, po).run();
}

std::vector<CandidateEstimate> estimate_candidates(const TilingProblem& problem, const SearchOptions& options,
                                                   const PortfolioOptions& portfolio, std::uint64_t probes,
                                                   double seconds) {
  if (probes < 1) throw RequestError("probes", "`probes` needs at least 1 probe");
  if (!(seconds > 0) || !std::isfinite(seconds))
    throw RequestError("probe_seconds", fmt::format("`probe_seconds` must be positive, got {}", seconds));
  const std::vector<std::string> names = portfolio.candidates.empty()
                                             ? default_candidates(problem.set.kind(), problem.set.colours())
                                             : portfolio.candidates;
  std::set<std::string> seen;  // refused as a run refuses them (Scheduler::start)
  for (const std::string& name : names)
    if (!seen.insert(name).second) throw InputError(fmt::format("portfolio candidate '{}' is listed twice", name));
  std::vector<CandidateEstimate> out;
  // The run's own time limit bounds every probe and slice together; a signal ends the list.
  const Deadline deadline(options.run.time_limit);
  for (const std::string& name : names) {
    if (deadline.expired() || (options.run.catch_signals && SignalCatcher::caught())) break;
    const Candidate c = make_candidate(problem, name);
    CandidateEstimate e;
    e.name = c.name;
    e.family = c.family;
    e.estimable = c.resumable;  // an engine search: its tree can be probed (cadical's cannot)
    if (e.estimable) {
      SearchOptions o = options;
      o.mode = SearchMode::First;
      o.run.time_limit = std::max(1e-3, std::min(seconds, deadline.seconds_left()));
      o.run.checkpoint_path.clear();
      o.run.checkpoint_every = 0;
      o.estimate_probes = probes;
      o.save_checkpoint = nullptr;
      o.resume_state.reset();
      o.title = fmt::format("estimate {}", c.name);
      const SearchResult r = c.run(problem, o);
      e.log10_tree_nodes = r.estimated_log10_nodes;
      e.probes = r.estimated_probes;
      e.nodes = r.nodes;
      e.seconds = r.seconds;
      e.found = !r.found.empty();
    }
    out.push_back(e);
    if (options.run.catch_signals && SignalCatcher::caught()) break;
  }
  return out;
}

}  // namespace tilekit
