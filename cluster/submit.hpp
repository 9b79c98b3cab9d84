#pragma once
// Queueing a planned run: the run directory written (or resumed) and the shard array and its
// merge job handed to sbatch.
#include <cstddef>
#include <string>
#include <vector>

#include "cluster/plan.hpp"

namespace tilekit::cluster {

struct Submission {
  std::string array_job, merge_job;  // Slurm job ids; an MPI run's job is array_job, merge_job ""
  std::size_t submissions = 0;       // submissions of this run so far, this one included
};

// Writes the run directory of `plan` (the job scripts, run.json, shards/, logs/) and queues the
// array and the merge job (afterok) with `sbatch_command`. A run directory holds one run:
// submitting the same run again resumes it, another is refused (InputError). Throws NotFound
// when `sbatch_command` cannot be run (exit 127), InputError when it fails or prints no job id.
Submission submit_run(const ClusterPlan& plan, const std::string& sbatch_command);

// `sbatch_command --parsable ARGS...` run through the shell; the job id it prints.
std::string sbatch(const std::string& sbatch_command, const std::vector<std::string>& args);

}  // namespace tilekit::cluster
