#pragma once
// Checkpoint files: the on-disk form of a search's state (solver/search_state.hpp), or of a
// portfolio's (every candidate's engine state and the schedule), with the request of the run
// they belong to, so that `tilekit pack --resume FILE` alone continues it.
//
//   TILEKIT-CHECKPOINT 2\n            magic and format version
//   bytes <n> fnv1a64 <16 hex>\n      length and checksum of the body
//   <body: n bytes of JSON>           {"request": {...} or null,
//                                      "search": {fingerprint, subproblems, subproblem_hash,
//                                                 finished (hex bitmap), finished_counts,
//                                                 in_flight [{index, path, counted}], restarts,
//                                                 restart_nodes, seconds}}
//                                     or {"request": ..., "portfolio": {fingerprint, round,
//                                         next, seconds, candidates [{name, empty, slices,
//                                         nodes, seconds, engine: <search> or null}]}}
// Version 1 files (the "search" object's fields at the top level, no request) are still read.
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

#include "solver/portfolio.hpp"
#include "solver/problem.hpp"
#include "solver/search_state.hpp"

namespace tilekit {

inline constexpr int kCheckpointVersion = 2;

// The envelope every Tilekit checkpoint file shares (above, with its own magic and version):
// seal_checkpoint() wraps a body; open_checkpoint() returns the body after checking magic, a
// version in [oldest, newest] (stored in *version_read), length and checksum, or throws
// InputError naming `origin` and the problem.
std::string seal_checkpoint(std::string_view magic, int version, std::string_view body);
std::string_view open_checkpoint(std::string_view text, std::string_view magic, int oldest, int newest,
                                 const std::string& origin, int* version_read = nullptr);

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

// solve() with checkpoint files: reads options.run.resume_path (checking that it belongs to this
// search: InputError naming what differs), and writes options.run.checkpoint_path every
// options.run.checkpoint_every seconds, on a signal (with run.catch_signals) and at the end, with
// `request` in every file written.
SearchResult solve_checkpointed(const TilingProblem& problem, SearchOptions options,
                                const nlohmann::json& request = nullptr);

// run_portfolio() with checkpoint files, the same way: options.run.resume_path must hold a
// portfolio state of this portfolio, options.run.checkpoint_path receives it.
PortfolioResult run_portfolio_checkpointed(const TilingProblem& problem, const SearchOptions& options,
                                           PortfolioOptions portfolio, const nlohmann::json& request = nullptr);

}  // namespace tilekit
