#pragma once
// Which subproblems a shard of a search owns: the one definition that the engine
// (parallel_search.hpp), the checks of a resumed state (search_state.cpp) and the status of a
// cluster run (cluster/status.cpp) share.
#include <cstdint>

#include "base/parse.hpp"

namespace tilekit {

// Subproblem `k` (in the engine's deterministic split) belongs to shard I of N when k mod N = I:
// every N-th one, from I.
inline bool shard_owns(const ShardSpec& shard, std::uint64_t k) {
  return k % std::uint64_t(shard.count) == std::uint64_t(shard.index);
}

}  // namespace tilekit
