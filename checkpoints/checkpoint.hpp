#pragma once
// Checkpoint files: the on-disk form of a SearchState (solver/search_state.hpp).
//
//   TILEKIT-CHECKPOINT 1\n            magic and format version
//   bytes <n> fnv1a64 <16 hex>\n      length and checksum of the body
//   <body: n bytes of JSON>           fingerprint, subproblems, finished bitmap, counters,
//                                     in-flight decision paths
//
// Written atomically (temp file, fsync, rename), so a kill at any moment leaves either the
// previous checkpoint or the new one. Reading checks magic, version, length and checksum;
// any mismatch is an InputError (exit 2), never a wrong count.
#include <string>
#include <string_view>

#include "solver/search_state.hpp"
#include "solver/solve.hpp"

namespace tilekit {

inline constexpr int kCheckpointVersion = 1;

// The envelope every Tilekit checkpoint file shares (above, with its own magic and version):
// seal_checkpoint() wraps a body; open_checkpoint() returns the body after checking magic,
// version, length and checksum, or throws InputError naming `origin` and the problem.
std::string seal_checkpoint(std::string_view magic, int version, std::string_view body);
std::string_view open_checkpoint(std::string_view text, std::string_view magic, int version, const std::string& origin);

std::string encode_checkpoint(const SearchState& state);
// `origin` names the file in error messages.
SearchState decode_checkpoint(std::string_view text, const std::string& origin);

void write_checkpoint(const std::string& path, const SearchState& state);
SearchState read_checkpoint(const std::string& path);

// The differences between two search fingerprints, e.g. "mode: count here, all in the
// checkpoint"; empty when equal.
std::string fingerprint_difference(const std::string& here, const std::string& checkpoint);

// solve() with checkpoint files: reads options.resume_path (checking that it belongs to this
// search: InputError naming what differs), and writes options.checkpoint_path every
// options.checkpoint_every seconds, on a signal (with catch_signals) and at the end.
SearchResult solve_checkpointed(const TilingProblem& problem, SearchOptions options);

}  // namespace tilekit
