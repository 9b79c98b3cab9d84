#pragma once
// The flags of `tilekit pack` that `cluster submit` gives the cluster plan (cluster/plan.hpp), so
// that the cluster library names no flag.
#include "cluster/plan.hpp"

namespace tilekit::cli {

// The shard command's flags that the plan writes into the job scripts, and those the job scripts
// set per shard (scripts/slurm/*.body.sh), which --pack-arg may not give.
cluster::ShardCommandWords pack_shard_words();

}  // namespace tilekit::cli
