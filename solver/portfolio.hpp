#pragma once
// The search portfolio of `tilekit pack --method auto|search`: a scheduler
// over solve(). Candidates are subspace searches (the plain search, imposed groups, the SAT
// encoding of a group, ...); they run in rounds of time slices that double each round (Luby
// and Zuckerman's doubling idea: the total work is within a constant of the best candidate's
// alone), each slice on all threads with the candidate's engine resumed from where its last
// slice stopped. With two or more threads, the candidates that restart each slice (cadical's)
// run in a side lane of their own beside the engine's (portfolio.cpp, Scheduler). The first
// solution ends the run; a candidate whose subspace is exhausted is dropped. The schedule and every candidate's engine state are a PortfolioState, which the
// caller checkpoints (checkpoints/checkpoint.hpp) exactly like a single search. A resumed state
// is checked, not trusted: its candidates must be those its fingerprint names, and "exhausted"
// is re-derived (every candidate runs again; a finished engine state ends at once).
//
// Candidate names: "plain" (the whole space), "SPEC" or "impose:SPEC" (only the packings
// invariant under the group SPEC, solver/impose_group.hpp), "sat:SPEC" (the same subspace as
// CNF for cadical), "lift:M" / "lift-sat:M" (colour-quotient lifts over a packing of M colours,
// solver/colour_lift_model.hpp, searched by the engine or by cadical). How to add a family:
// solver/README.md.
//
// Shards (options.run.shard): every resumable candidate's dives are split between the
// shards (parallel_search.hpp); a candidate that cannot be split (sat) runs in one shard only,
// candidate i in shard i mod N. So shards 0..N-1 together run one portfolio.
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "solver/portfolio_stats.hpp"
#include "solver/problem.hpp"
#include "solver/search_state.hpp"

namespace tilekit {

// The name of the plain (unconstrained) search among the candidates.
inline constexpr const char* kPlainSearch = "plain";

// A runnable subspace search.
struct Candidate {
  std::string name;        // as named
  std::string family;      // "plain", "impose", "sat", ...
  std::string group;       // canonical group spec ("" for none)
  bool resumable = true;   // its engine state carries over between slices (and checkpoints)
  bool splittable = true;  // runs in every shard on its share of the dives
  // Runs one slice. `options` holds mode First, threads, seed, time limit, shard, signals,
  // progress, on_solution and, for a resumable candidate, resume_state/save_checkpoint.
  std::function<SearchResult(const TilingProblem&, SearchOptions)> run;
};

// The candidate a name stands for. Throws InputError for an unknown family or a bad group.
Candidate make_candidate(const TilingProblem& problem, const std::string& name);

// Candidate groups for the complete packing of `kind` over C colours, all valid, in a default
// order (largest cyclic groups first):
//   translations of order k (k | C, k > 1) paired with a permutation made of k-cycles, and
//   products of two such generators with commuting permutations (k1 * k2 | C for corner; for
//   Wang also one generator on the horizontal and one on the vertical colours).
std::vector<std::string> candidate_groups(TileKind kind, std::uint32_t colours);
// Colour-quotient lift candidates for corner packings over C colours: "lift:M" for every divisor
// M of C (2 <= M <= C/2) with a known packing over M colours (construct_packing), largest M
// first, each followed by "lift-sat:M" when cadical is on PATH.
std::vector<std::string> lift_candidates(TileKind kind, std::uint32_t colours);
// candidate_groups(), lift_candidates() and then the plain search.
std::vector<std::string> default_candidates(TileKind kind, std::uint32_t colours);

struct PortfolioOptions {
  std::string stats_path;               // "" = PortfolioStats::default_path(); "-" = do not persist
  double first_slice = 0.25;            // seconds per candidate in round 0; doubles each round
  std::vector<std::string> candidates;  // empty = default_candidates()
  // Checkpoints, as in SearchOptions: called with the whole state at the start, every
  // options.run.checkpoint_every seconds (inside a slice), after each slice and at the end.
  std::function<void(const PortfolioState&)> save_checkpoint;
  std::optional<PortfolioState> resume_state;
};

struct PortfolioResult {
  bool found = false;
  bool complete = false;  // every candidate's subspace was exhausted: no solution in any
  bool interrupted = false, timed_out = false;
  int signal = 0;
  std::string winner;       // the candidate that found the solution
  SearchResult result;      // of the winning slice (found[0] = the validated packing)
  std::uint64_t nodes = 0;  // all slices, this run and the ones it resumed
  double seconds = 0, total_seconds = 0;
  std::size_t checkpoints = 0;
  SearchStats stats;                              // every slice of this run, summed (solver/search_stats.hpp)
  nlohmann::json runs = nlohmann::json::array();  // per candidate: slices, nodes, seconds, found, empty

  // The run as one search of the whole problem: the winning slice's result (its packing and
  // group) with the totals of every slice, formulation "portfolio", and complete only when the
  // plain search, the whole space, was exhausted (exhausted subspaces prove nothing about it).
  SearchResult as_search_result(int threads) const;
};

// The fingerprint a portfolio checkpoint must match: the problem, seed and shard (as
// search_fingerprint() of the plain search), the set of candidates and the first slice.
std::string portfolio_fingerprint(const TilingProblem& problem, const SearchOptions& options,
                                  const PortfolioOptions& portfolio);

// Runs the portfolio (options.mode must be First) until a solution is found, every candidate
// is exhausted, options.run.time_limit (0 = none) passes or a signal comes (run.catch_signals).
// Throws InputError for bad candidates, options or a checkpoint of another portfolio.
PortfolioResult run_portfolio(const TilingProblem& problem, const SearchOptions& options,
                              const PortfolioOptions& portfolio = {});

// How far each candidate is from exhausting its subspace: Knuth's estimate of its search tree
// (solver/knuth_estimate.hpp, `probes` random root-to-leaf dives) and the node rate of one
// slice of `seconds` on options.run.threads threads. The projected time to exhaust the tree
// is tree_nodes / rate; a first solution may come much sooner, so it bounds the distance from
// above, not below. Candidates solved by cadical (sat, lift-sat) have no engine tree: they are
// listed with estimable = false and not run.
struct CandidateEstimate {
  std::string name, family;
  bool estimable = false;
  double log10_tree_nodes = 0;  // Knuth's estimate of the whole tree, as a logarithm
  std::uint64_t probes = 0;
  std::uint64_t nodes = 0;  // searched in the timed slice
  double seconds = 0;       // of the slice (wall)
  bool found = false;       // the slice found a packing
};
std::vector<CandidateEstimate> estimate_candidates(const TilingProblem& problem, const SearchOptions& options,
                                                   const PortfolioOptions& portfolio, std::uint64_t probes,
                                                   double seconds);

}  // namespace tilekit
