#pragma once
// The plan of a cluster run: what `tilekit cluster submit` is asked (SubmitRequest), checked and
// completed into the settings every job script is written from (ClusterPlan).
#include <string>
#include <string_view>
#include <vector>

namespace tilekit::cluster {

// Everything the job scripts are written from; the defaults are those of `cluster submit`.
struct ClusterPlan {
  std::string tilekit;                       // absolute path of the binary the jobs run (default_job_binary)
  std::string run_dir;                       // absolute; on the filesystem shared by the nodes
  std::string job_name;                      // squeue's name; the merge job adds "-merge"
  std::vector<std::string> command{"pack"};  // the shard command: pack, or aperiodic enumerate
  std::vector<std::string> pack_args;        // the shard command's arguments common to every shard
  int shards = 1;
  int cpus_per_task = 1;
  std::string time = "1:00:00";  // Slurm time of one attempt, as the user wrote it
  std::string merge_time = "1:00:00";
  int signal_seconds = 120;  // USR1 this long before the wall-time limit
  std::string partition;     // "" = the cluster's default partition
  int max_requeues = 10;
  double checkpoint_every = 300;         // seconds between periodic checkpoints
  std::vector<std::string> sbatch_args;  // extra directives, e.g. "--account=proj"
  // One MPI job (`pack --mpi`, cluster/mpi_work.hpp) instead of an array: `ntasks` ranks on
  // `nodes` nodes of one allocation, each rank with cpus_per_task threads, started by `launcher`:
  // "srun" (srun's `--mpi=` set to `srun_mpi`, PMIx by default) or "mpirun" (Open MPI's, inside
  // the allocation). `shards` is 1 then: the run's files are shard 0's.
  // Adaptive splitting (cluster/split.hpp): each shard (and each work unit of the follow-up
  // arrays) stops after `split_after` seconds (0 = never: a plain array) and the merge job splits
  // what it left into `split_ways` units per unfinished unit, as the next array.
  double split_after = 0;
  int split_ways = 4;
  bool mpi = false;
  int nodes = 1;
  int ntasks = 0;  // ranks; 0 = `nodes` (make_plan fills it in)
  std::string launcher = "srun";
  std::string srun_mpi = "pmix";
};

// The longest checkpoint interval a plan takes: a year (a longer one would never fire, and
// inf or 1e308 would reach the job scripts as text that the shard command refuses).
inline constexpr double kMaxCheckpointSeconds = 365.0 * 86400.0;
// The most arguments of the shard command, and the longest one (what a run file may hold).
inline constexpr std::size_t kMaxShardArgs = 4096, kMaxShardArgBytes = 4096;

// The flags of the shard command's command line. They are the caller's (the CLI's
// `pack_shard_words()`, cli/cmd_cluster.cpp), so that this library names no flag; the flags the job
// scripts set per shard are written in their bodies (scripts/slurm/).
struct ShardCommandWords {
  std::string kind, colours, method, mode, seed;  // the flag that sets each request field
  std::string window;                             // the flag a window run's shard_args must give
  std::string mpi;                                // the flag of an MPI run (`pack --mpi`)
  std::vector<std::string> per_shard;             // flags the job scripts set: refused in shard_args
};

// What `cluster submit` is asked. `settings` carries the scheduling fields as given (shards,
// cpus_per_task, time, partition, max_requeues, checkpoint_every, sbatch_args); make_plan()
// fills in the rest.
struct SubmitRequest {
  std::string command = "pack";                  // or "enumerate": tilekit aperiodic enumerate
  std::string kind, method, mode = "all", seed;  // pack's (empty: not given)
  int colors = 0;
  std::vector<std::string> shard_args;     // more arguments of the shard command (--pack-arg)
  std::string run_dir, tilekit, job_name;  // "" = the defaults
  int signal_seconds = 0;                  // 0 = default_signal_seconds(time)
  std::string merge_time;                  // "" = time
  ClusterPlan settings;
  ShardCommandWords words;
};

// Where make_plan() looks for the binary the jobs run: the PATH variable and this binary.
struct PlanEnvironment {
  std::string path;                     // $PATH
  std::string self = "/proc/self/exe";  // the binary running submit
};
// $PATH of this process, and /proc/self/exe.
PlanEnvironment current_environment();

// The binary the jobs run when `cluster submit` has no --tilekit: the first executable file named
// tilekit in the directories of `path_env` (PATH: an installed binary, which a rebuild of a
// checkout does not replace under a running array), else `self` (the binary running submit, e.g.
// a build tree's build/tilekit). The result is absolute, with links resolved.
std::string default_job_binary(std::string_view path_env, const std::string& self);

// Errors name the request's fields between backquotes, never flags ("`checkpoint_every` must be
// ...", "`shard_args` --db=x: the job script sets it per shard"; the field of a ClusterPlan
// setting is its member's name): the CLI words them as the flags that set them.

// The request checked and completed: the shard command and its arguments, the absolute run
// directory, the binary, the job name, the merge time and the signal lead. Throws InputError for
// anything the job scripts could not run with (check_plan()).
ClusterPlan make_plan(const SubmitRequest& request, const PlanEnvironment& env = current_environment());

// Throws InputError when the plan cannot make working scripts (bad counts, odd paths).
void check_plan(const ClusterPlan& plan);

}  // namespace tilekit::cluster
