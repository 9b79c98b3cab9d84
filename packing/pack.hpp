#pragma once
// `tilekit pack` as a library function: a PackRequest in, a PackOutcome out. The policy:
//   first mode, complete set: find_packing (database hit, construction, then the search
//     portfolio, unless --method or --impose/--plain say otherwise);
//   otherwise: one search (solve(), under the imposed group with --impose).
// Every search keeps checkpoints (--checkpoint/--resume, also the portfolio's), takes shards,
// threads, time limits and signals (SIGTERM/SIGINT/SIGUSR1: checkpoint, outcome.interrupted),
// and stores its run and its solutions in the results database. `--resume FILE` alone
// continues the run FILE describes (request.hpp).
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "packing/request.hpp"
#include "solver/problem.hpp"

namespace tilekit {

struct PackOutcome {
  PackRequest request;  // as run (a resumed run: filled in from the checkpoint)
  TilingProblem problem;
  std::string method;                       // what answered: "db", "construct" or "search"
  SearchResult result;                      // counts, nodes, times; found[0] = the packing in first mode
  std::string construction;                 // method "construct": which one
  nlohmann::json group = nullptr;           // the imposed group of the packing or search (to_json())
  nlohmann::json portfolio = nullptr;       // {"winner": name or null, "runs": [...]} when it ran
  std::optional<std::uint64_t> orbit_size;  // of the packing found, under the packing symmetry
  std::string db_path;
  std::int64_t run_id = 0;
  std::size_t stored = 0;    // new solutions stored by this run
  std::string checkpoint;    // the checkpoint file kept ("" = none)
  bool interrupted = false;  // a signal stopped it (after the checkpoint): exit 3
  int signal = 0;
  std::string not_found;  // first mode without a packing: why (exit 1)
};

// Runs the request. `given` names the fields the caller set (for a resumed run, which takes the
// others from its checkpoint: request.hpp). Throws InputError for bad input (before the database
// is touched) and NotFound when the construct method has no construction.
PackOutcome run_pack(PackRequest request, const PackFields& given = {});

// The portfolio statistics of the given files added up (one file: itself; none: the default
// file), filtered by kind ("" = all) and colours (0 = all); with `out`, the sum is also written
// there (merging the files of a cluster run's shards).
// {"stats": [paths], "groups": [{kind, colors, group, tries, successes, median_seconds}]}
nlohmann::json portfolio_report(const std::vector<std::string>& stats_files, const std::string& kind,
                                std::int64_t colours, const std::string& out = "");

// `pack --estimate PROBES`: for a first-mode search of a complete set, every portfolio candidate's
// distance (solver/portfolio.hpp estimate_candidates), as
// {"kind", "colors", "threads", "probes", "slice_seconds", "candidates": [{candidate, family,
//   estimable, log10_tree_nodes, nodes, seconds, nodes_per_cpu_second, log10_exhaust_cpu_hours,
//   found}]} (logarithms: the trees of large sets pass double's range). Nothing is stored.
// InputError for other requests.
nlohmann::json estimate_pack(const PackRequest& request, std::uint64_t probes, double slice_seconds);

}  // namespace tilekit
