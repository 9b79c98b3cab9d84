#pragma once
// The flags of `tilekit pack` that `cluster submit` gives the plan (cli/cmd_cluster.cpp), for tests
// that make plans without the CLI.
#include "cluster/plan.hpp"

namespace tilekit::test {

inline cluster::ShardCommandWords pack_shard_words() {
  return {.kind = "--kind",
          .colours = "--colors",
          .method = "--method",
          .mode = "--mode",
          .seed = "--seed",
          .window = "--window",
          .per_shard = {"--shard", "--checkpoint", "--checkpoint-every", "--resume", "--db", "--threads", "--json",
                        "--portfolio-stats"}};
}

}  // namespace tilekit::test
