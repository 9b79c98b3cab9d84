#pragma once
// The Slurm job scripts of `tilekit cluster submit`: a job array with one task per
// shard of `tilekit pack`, a merge job that runs after it (afterok), and submit.sh that queues
// both. Each script is a header of commented #SBATCH directives and variables written here,
// followed by a body kept in scripts/slurm/*.body.sh and embedded in the binary at build time.
#include <string>
#include <string_view>
#include <vector>

#include "tilesets/reference_data.hpp"

namespace tilekit::cli {

struct ClusterPlan {
  std::string tilekit;                 // absolute path of the binary the jobs run (default_job_binary)
  std::string run_dir;                 // absolute; on the filesystem shared by the nodes
  std::string job_name;                // squeue's name; the merge job adds "-merge"
  std::vector<std::string> command{"pack"};  // the shard command: pack, or aperiodic enumerate
  std::vector<std::string> pack_args;  // the shard command's arguments common to every shard
  int shards = 1;
  int cpus_per_task = 1;
  std::string time = "1:00:00";        // Slurm time of one attempt, as the user wrote it
  std::string merge_time = "1:00:00";
  int signal_seconds = 120;            // USR1 this long before the wall-time limit
  std::string partition;               // "" = the cluster's default partition
  int max_requeues = 10;
  double checkpoint_every = 300;       // seconds between periodic checkpoints
  std::vector<std::string> sbatch_args;  // extra directives, e.g. "--account=proj"
};

// Seconds in a Slurm time string: M, M:S, H:M:S, D-H, D-H:M, D-H:M:S (sbatch --time).
// Throws InputError for anything else (including UNLIMITED: a signal needs a finite limit).
long parse_slurm_time(std::string_view text);

// The default signal lead for a wall time of `seconds`: 120 s, at most half the limit.
int default_signal_seconds(long seconds);

// `text` quoted for bash (single quotes), unchanged when it needs no quoting.
std::string shell_quote(std::string_view text);

// The binary the jobs run when `cluster submit` has no --tilekit: the first executable file named
// tilekit in the directories of `path_env` (PATH: an installed binary, which a rebuild of a
// checkout does not replace under a running array), else `self` (the binary running submit, e.g.
// a build tree's build/tilekit). The result is absolute, with links resolved.
std::string default_job_binary(std::string_view path_env, const std::string& self);

// Throws InputError when the plan cannot make working scripts (bad counts, odd paths).
void check_plan(const ClusterPlan& plan);

std::string pack_array_script(const ClusterPlan& plan);
std::string merge_script(const ClusterPlan& plan);
std::string submit_script(const ClusterPlan& plan);

// The embedded bodies scripts/slurm/NAME.body.sh, named NAME ("pack-array", "merge"). Defined in
// the build's generated slurm_script_bodies.cpp (cmake/embed_files.cmake).
const std::vector<EmbeddedFile>& slurm_script_bodies();

// The body named `name`; empty if unknown.
std::string_view slurm_script_body(std::string_view name);

}  // namespace tilekit::cli
