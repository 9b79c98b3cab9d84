#pragma once
// `pack --shard I/N --part J/K`: one task of a follow-up array of an adaptively split run
// (cluster/split.hpp). A WorkSource (solver/work_source.hpp) for one process that keeps, of the
// jobs the engine makes for shard I/N (its unfinished subproblems, resumed ones at their paths),
// those of part J/K (ShardPart::owns, base/run_control.hpp) and hands them out to the threads.
// Being a work source, the resume of shard I's checkpoint F merges every F.rank-* beside it: the
// parts write their checkpoints there (cluster/split.hpp names them), so each part starts from
// all that the shard and its other parts have finished. The search's fingerprint stays the
// shard's; "complete" in the result means this part is done, not the shard.
#include <memory>

#include "base/run_control.hpp"
#include "solver/work_source.hpp"

namespace tilekit::cluster {

std::shared_ptr<WorkSource> part_work(const ShardSpec& shard, const ShardPart& part);

}  // namespace tilekit::cluster
