#pragma once
// Checkpoints of `tilekit aperiodic verify` (aperiodic/decide.hpp): the transducer chains built
// so far, so a long run (large k) survives a kill or a wall-time limit and resumes where it was.
//
//   TILEKIT-DECIDE 1\n                the envelope of checkpoints/checkpoint.hpp: magic, version,
//   bytes <n> fnv1a64 <16 hex>\n      length and checksum of the body
//   <body: n bytes, little-endian>    fingerprint, seconds so far, the levels built (statistics),
//                                     and per chain its direction and every level's transducer,
//                                     product states and classes
//
// Written atomically (base/atomic_file.hpp). Reading checks the envelope and then the structure
// of every level (ranges, order, the first level against the tile set): anything wrong is an
// InputError (exit 2), never a wrong verdict.
#include <string>
#include <string_view>
#include <vector>

#include "aperiodic/chain.hpp"
#include "aperiodic/decide.hpp"

namespace tilekit {

inline constexpr int kDecideCheckpointVersion = 1;

struct DecideCheckpoint {
  std::string fingerprint;         // the tile set and the options that shape the chains
  double seconds = 0;              // time spent by the runs so far
  std::vector<DecideLevel> levels;  // statistics of the levels built so far
  std::vector<TransducerChain> chains;
};

// What a checkpoint must match to be resumed: the decision tiles, merge, and the directions.
std::string decide_fingerprint(const std::vector<WangTile>& tiles, const DecideOptions& opts);

std::string encode_decide_checkpoint(const DecideCheckpoint& c);
// `tiles` are the decision tiles the chains are restored on; `origin` names the file in errors.
DecideCheckpoint decode_decide_checkpoint(std::string_view text, const std::vector<WangTile>& tiles,
                                          const std::string& origin);

void write_decide_checkpoint(const std::string& path, const DecideCheckpoint& c);
DecideCheckpoint read_decide_checkpoint(const std::string& path, const std::vector<WangTile>& tiles);

}  // namespace tilekit
