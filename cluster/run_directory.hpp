#pragma once
// The run directory of a cluster run and what it holds:
//   run.json                   the run file: the plan's identity and the submissions so far
//   pack-array.sbatch, merge.sbatch, submit.sh   the job scripts (job_scripts.hpp); an MPI run's
//                              pack-mpi.sbatch and submit.sh (its files are shard 0's)
//   shards/shard-I.{ckpt,sqlite,attempts,done.json,stats.json}   what shard I's task writes
//                              (scripts/slurm/pack-array.body.sh)
//   merged.sqlite, merged.json what the merge job writes
//   logs/                      the jobs' output
// Every file is read as a regular file with a size bound (base/input.hpp): a FIFO, a device or
// an oversized file is refused, never waited on.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cluster/plan.hpp"

namespace tilekit::cluster {

// Bounds of what is read: the run file (up to kMaxShardArgs arguments of kMaxShardArgBytes),
// and each file a job script writes (a result line, or one line of about 250 bytes per attempt).
inline constexpr std::uint64_t kMaxRunFileBytes = std::uint64_t(64) << 20;
inline constexpr std::uint64_t kMaxShardFileBytes = std::uint64_t(16) << 20;

// run.json as `cluster submit` wrote it: shards, pack_args and submissions checked.
struct RunFile {
  nlohmann::json doc;
  int shards = 0;
  std::vector<std::string> pack_args;
  nlohmann::json submissions = nlohmann::json::array();
  bool pack = true;  // the shards run `tilekit pack` (else `aperiodic enumerate`)
  int split_ways = 0;  // a split run's (`cluster submit --split-after`); 0 = not split
  int mpi_ranks = 0;  // an MPI run's ranks (`cluster submit --mpi`: one shard, shard 0); 0 = a job array
};

// The run file at `path`; nullopt when there is none. Throws InputError when it is not one.
std::optional<RunFile> read_run_file(const std::filesystem::path& path);

// The run file of a plan, with no submissions yet.
nlohmann::json run_record(const ClusterPlan& plan);

// A JSON object a job script writes (shard-I.done.json, merged.json); nullopt when it is absent
// or unreadable (a kill may cut one short: not written yet) or not an object.
std::optional<nlohmann::json> read_job_result(const std::filesystem::path& path);

// The file of shard `shard` with extension `ext` (".ckpt", ".attempts", ...) in run directory `dir`.
std::filesystem::path shard_file(const std::filesystem::path& dir, int shard, std::string_view ext);

}  // namespace tilekit::cluster
