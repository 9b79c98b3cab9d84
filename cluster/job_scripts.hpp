#pragma once
// The Slurm job scripts of a cluster run: a job array with one task per shard of the shard
// command, a merge job that runs after it (afterok), and submit.sh that queues both. Each script
// is a header of commented #SBATCH directives and variables written here, followed by a body
// kept in scripts/slurm/*.body.sh and embedded in the library at build time.
#include <string>
#include <string_view>
#include <vector>

#include "cluster/plan.hpp"
#include "tilesets/reference_data.hpp"

namespace tilekit::cluster {

// `text` quoted for bash (single quotes), unchanged when it needs no quoting.
std::string shell_quote(std::string_view text);

std::string pack_array_script(const ClusterPlan& plan);
std::string merge_script(const ClusterPlan& plan);
std::string submit_script(const ClusterPlan& plan);
// An MPI plan's (plan.mpi): one job that starts `ntasks` ranks of `tilekit pack --mpi` with srun
// (or mpirun) inside its allocation, checkpointing and requeueing itself like an array task.
std::string pack_mpi_script(const ClusterPlan& plan);
std::string mpi_submit_script(const ClusterPlan& plan);

// One script of the run directory: its file name there and its text.
struct JobScript {
  std::string name;  // "pack-array.sbatch", "merge.sbatch", "submit.sh"
  std::string text;
};
// The three scripts, in that order; an MPI plan's two: "pack-mpi.sbatch", "submit.sh".
std::vector<JobScript> job_scripts(const ClusterPlan& plan);

// The embedded bodies scripts/slurm/NAME.body.sh, named NAME ("pack-array", "merge"). Defined in
// the build's generated slurm_script_bodies.cpp (cmake/embed_files.cmake).
const std::vector<EmbeddedFile>& slurm_script_bodies();

// The body named `name`; empty if unknown.
std::string_view slurm_script_body(std::string_view name);

}  // namespace tilekit::cluster
