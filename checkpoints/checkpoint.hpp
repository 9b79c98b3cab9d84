#pragma once
// Checkpoint files: the on-disk form of a search's state (solver/search_state.hpp), or of a
// portfolio's (every candidate's engine state and the schedule), with the request of the run
// they belong to, so that `tilekit pack --resume FILE` alone continues it.
//
//   TILEKIT-CHECKPOINT 3\n            magic and format version
//   bytes <n> fnv1a64 <16 hex>\n      length and checksum of the body
//   <body: n bytes of JSON>           {"request": {...} or null,
//                                      "search": {fingerprint, subproblems, subproblem_hash,
//                                                 finished (hex bitmap), finished_counts,
//                                                 finished_each [[solutions, orbits, nodes] per
//                                                 finished subproblem, in index order],
//                                                 in_flight [{index, path, counted}], restarts,
//                                                 restart_nodes, seconds}}
//                                     or {"request": ..., "portfolio": {fingerprint, round,
//                                         next, seconds, candidates [{name, empty, slices,
//                                         nodes, seconds, engine: <search> or null}]}}
// Versions 1 and 2 lacked finished_each, without which a cleared finished mark cannot be told
// from an unfinished subproblem (it would be counted twice): they are refused, naming the
// version (finish such a run with the build that started it).
//
// Written atomically (temp file, fsync, rename), so a kill at any moment leaves either the
// previous checkpoint or the new one. Reading checks magic, version, length and checksum, then
// the structure (types, the bitmap's length, in-flight subproblems that are in range, distinct
// and unfinished, a schedule position inside the candidate list, ...); any mismatch is an
// InputError (exit 2), never a wrong count.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/checkpoint_envelope.hpp"
#include "solver/portfolio.hpp"
#include "solver/problem.hpp"
#include "solver/search_state.hpp"

namespace tilekit {

inline constexpr int kCheckpointVersion = 3;

// The envelope (seal_checkpoint, open_checkpoint) is base/checkpoint_envelope.hpp.

struct CheckpointFile {
  nlohmann::json request;             // the run's request (packing/request.hpp); null if unknown
  std::optional<SearchState> search;  // exactly one of search and portfolio
  std::optional<PortfolioState> portfolio;
};

std::string encode_checkpoint(const CheckpointFile& file);
// `origin` names the file in error messages.
CheckpointFile decode_checkpoint_file(std::string_view text, const std::string& origin);
void write_checkpoint(const std::string& path, const CheckpointFile& file);
CheckpointFile read_checkpoint_file(const std::string& path);

// A single search's state without a request (the state must be there: InputError otherwise).
std::string encode_checkpoint(const SearchState& state);
SearchState decode_checkpoint(std::string_view text, const std::string& origin);
void write_checkpoint(const std::string& path, const SearchState& state);
SearchState read_checkpoint(const std::string& path);

// The differences between two search fingerprints, e.g. "mode: count here, all in the
// checkpoint"; empty when equal.
std::string fingerprint_difference(const std::string& here, const std::string& checkpoint);

// The checkpoint at options.run.resume_path, checked to belong to this run: a single search
// (portfolio null) or this portfolio, with a matching fingerprint (InputError naming what
// differs). What solve_checkpointed() and run_portfolio_checkpointed() read; a command calls it
// first to refuse a foreign checkpoint before it writes anything.
CheckpointFile read_resume_file(const TilingProblem& problem, const SearchOptions& options,
                                const PortfolioOptions* portfolio);

// An MPI run's checkpoint files (cluster/mpi_work.hpp): rank 0 writes `path`, rank R > 0
// `path`.rank-R; rank_checkpoint_files() lists the `path`.rank-* files beside `path`.
std::string rank_checkpoint_path(const std::string& path, int rank);
std::vector<std::string> rank_checkpoint_files(const std::string& path);

// solve() with checkpoint files: reads options.run.resume_path (checking that it belongs to this
// search: InputError naming what differs), and writes options.run.checkpoint_path every
// options.run.checkpoint_every seconds, on a signal (with run.catch_signals) and at the end, with
// `request` in every file written. With options.run.work (an MPI job) rank R > 0 writes
// rank_checkpoint_path() and reads nothing; the root resumes from `resume_path` merged with every
// rank file beside it (merge_search_states), and a fresh root removes stale rank files.
SearchResult solve_checkpointed(const TilingProblem& problem, SearchOptions options,
                                const nlohmann::json& request = nullptr);

// run_portfolio() with checkpoint files, the same way: options.run.resume_path must hold a
// portfolio state of this portfolio, options.run.checkpoint_path receives it.
PortfolioResult run_portfolio_checkpointed(const TilingProblem& problem, const SearchOptions& options,
                                           PortfolioOptions portfolio, const nlohmann::json& request = nullptr);

}  // namespace tilekit
