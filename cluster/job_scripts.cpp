#include "cluster/job_scripts.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "base/version.hpp"

namespace tilekit::cluster {
namespace {

// One #SBATCH directive and what it is for: an sbatch option, written without its leading
// "--" (sbatch's options, not Tilekit's: "job-name=tk-wang2").
struct Directive {
  std::string option, comment;
};

std::string directives_block(const std::vector<Directive>& ds) {
  std::size_t width = 0;
  for (const auto& d : ds) width = std::max(width, d.option.size());
  std::string out;
  for (const auto& d : ds) out += fmt::format("#SBATCH --{:<{}}  # {}\n", d.option, width, d.comment);
  return out;
}

std::string variable(const std::string& name, const std::string& value) {
  return fmt::format("{}={}\n", name, shell_quote(value));
}

std::string bash_array(const std::string& name, const std::vector<std::string>& values) {
  std::string out = name + "=(";
  for (std::size_t i = 0; i < values.size(); ++i) out += (i ? " " : "") + shell_quote(values[i]);
  return out + ")\n";
}

std::string body(std::string_view name) {
  std::string_view b = slurm_script_body(name);
  if (b.empty()) throw std::logic_error(fmt::format("job-script body '{}' was not embedded", name));
  return std::string(b);
}

void common_directives(const ClusterPlan& p, std::vector<Directive>& ds) {
  if (!p.partition.empty()) ds.push_back({"partition=" + p.partition, "the partition (queue) to run in"});
  // check_plan(): each starts with "--"
  for (const auto& a : p.sbatch_args) ds.push_back({a.substr(2), "passed through from cluster submit"});
}

// What both sbatch scripts start with: the shebang, their header comment, the #SBATCH block
// (with the common directives) and the run's variables that the body reads.
std::string script_head(const ClusterPlan& p, std::vector<Directive> ds, const std::string& header) {
  common_directives(p, ds);
  std::string s = "#!/bin/bash\n" + header + directives_block(ds);
  s += "\n# The run (written by tilekit cluster submit; the body below reads these).\n";
  s += variable("TILEKIT", p.tilekit);
  s += variable("RUN_DIR", p.run_dir);
  s += variable("SHARDS", std::to_string(p.shards));
  return s;
}

}  // namespace

std::string_view slurm_script_body(std::string_view name) {
  for (const EmbeddedFile& f : slurm_script_bodies())
    if (f.name == name) return f.text;
  return {};
}

std::string shell_quote(std::string_view text) {
  static const std::string safe = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-+=./,:@%";
  if (!text.empty() && text.find_first_not_of(safe) == std::string_view::npos) return std::string(text);
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string pack_array_script(const ClusterPlan& p) {
  std::vector<Directive> ds = {
      {"job-name=" + p.job_name, "the name squeue shows"},
      {fmt::format("array=0-{}", p.shards - 1),
       fmt::format("one array task per shard: shard I of {} runs as task I", p.shards)},
      {"ntasks=1", "one tilekit process per shard..."},
      {fmt::format("cpus-per-task={}", p.cpus_per_task),
       "...with this many cores (OMP_NUM_THREADS = SLURM_CPUS_PER_TASK)"},
      {"time=" + p.time, "wall time of one attempt; a requeued attempt gets it anew"},
      {fmt::format("signal=B:USR1@{}", p.signal_seconds),
       fmt::format("USR1 to this script {} s (to 60 s more) before the limit: checkpoint, exit 3", p.signal_seconds)},
      {"requeue", "let the task requeue itself after exit 3 and resume"},
      {"open-mode=append", "every attempt of a shard appends to the same log"},
      {"chdir=" + p.run_dir, "working directory, on the shared filesystem"},
      {"output=" + p.run_dir + "/logs/pack-%A_%a.out", "log of array job %A, shard %a"},
  };
  std::string s = script_head(
      p, std::move(ds),
      fmt::format("# Tilekit shard array, written by `tilekit cluster submit` (tilekit {}).\n", version_line()) +
          "# Queue it with submit.sh (it also queues the merge job), or: sbatch pack-array.sbatch\n");
  s += variable("MAX_REQUEUES", std::to_string(p.max_requeues));
  s += variable("CHECKPOINT_EVERY", fmt::format("{}", p.checkpoint_every));
  s += variable("SPLIT_AFTER", fmt::format("{}", p.split_after));
  s += bash_array("COMMAND", p.command);
  s += bash_array("PACK_ARGS", p.pack_args);
  s += "\n" + body("pack-common") + "\n" + body("pack-array");
  return s;
}

std::string pack_mpi_script(const ClusterPlan& p) {
  const bool srun = p.launcher == "srun";
  std::vector<Directive> ds = {
      {"job-name=" + p.job_name, "the name squeue shows"},
      {fmt::format("nodes={}", p.nodes), "one allocation of this many nodes..."},
      {fmt::format("ntasks={}", p.ntasks), "...for this many MPI ranks of one tilekit pack run"},
      {fmt::format("cpus-per-task={}", p.cpus_per_task),
       "threads per rank (OMP_NUM_THREADS = SLURM_CPUS_PER_TASK)"},
      {"time=" + p.time, "wall time of one attempt; a requeued attempt gets it anew"},
      {fmt::format("signal=B:USR1@{}", p.signal_seconds),
       fmt::format("USR1 to this script {} s (to 60 s more) before the limit: every rank checkpoints, exit 3",
                   p.signal_seconds)},
      {"requeue", "let the job requeue itself after exit 3 and resume"},
      {"open-mode=append", "every attempt appends to the same log"},
      {"chdir=" + p.run_dir, "working directory, on the shared filesystem"},
      {"output=" + p.run_dir + "/logs/pack-mpi-%j.out", "log of job %j"},
  };
  std::string s = script_head(
      p, std::move(ds),
      fmt::format("# Tilekit MPI run, written by `tilekit cluster submit` (tilekit {}).\n", version_line()) +
          "# Queue it with submit.sh, or: sbatch pack-mpi.sbatch\n");
  s += variable("MAX_REQUEUES", std::to_string(p.max_requeues));
  s += variable("CHECKPOINT_EVERY", fmt::format("{}", p.checkpoint_every));
  s += variable("LAUNCHER", p.launcher);
  s += "# How the ranks start: " +
       std::string(srun ? "srun with Slurm's MPI plugin below (Open MPI built with PMIx: pmix)"
                        : "Open MPI's mpirun, which reads the allocation from Slurm") +
       "\n";
  s += variable("SRUN_MPI", p.srun_mpi);
  s += bash_array("COMMAND", p.command);
  s += bash_array("PACK_ARGS", p.pack_args);
  s += "\n" + body("pack-common") + "\n" + body("pack-mpi");
  return s;
}

std::string merge_script(const ClusterPlan& p) {
  std::vector<Directive> ds = {
      {"job-name=" + p.job_name + "-merge", "the name squeue shows"},
      {"ntasks=1", "merging is one process..."},
      {"cpus-per-task=1", "...writing one SQLite file"},
      {"time=" + p.merge_time, "wall time of the merge"},
      {"chdir=" + p.run_dir, "working directory, on the shared filesystem"},
      {"output=" + p.run_dir + "/logs/merge-%j.out", "log of merge job %j"},
  };
  std::string s = script_head(
      p, std::move(ds),
      fmt::format("# Tilekit merge job, written by `tilekit cluster submit` (tilekit {}).\n", version_line()) +
          "# Queued after the shard array: sbatch "
          "--dependency=afterok:ARRAY_JOB_ID merge.sbatch\n" +  // not a tilekit flag
          "# (afterok: it starts only when every shard task ended with exit code 0).\n");
  s += variable("SPLIT_AFTER", fmt::format("{}", p.split_after));
  s += "\n" + body("merge");
  return s;
}

std::string submit_script(const ClusterPlan& p) {
  std::string s = "#!/bin/bash\n";
  s += fmt::format("# Queues the Tilekit run in {}: the shard array, then the merge job.\n", p.run_dir);
  s += "# Run it again to resume the whole run: finished shards exit at once, the others\n";
  s += "# resume from their checkpoints, and the merge runs when all of them are done.\n";
  s += "set -euo pipefail\n";
  s += "cd " + shell_quote(p.run_dir) + "\n";
  // sbatch's options below: not a tilekit flag
  s += "array=$(sbatch --parsable pack-array.sbatch)\n";                             // not a tilekit flag
  s += "array=${array%%;*}  # --parsable prints ID or ID;CLUSTER\n";                 // not a tilekit flag
  s += "merge=$(sbatch --parsable --dependency=afterok:\"$array\" merge.sbatch)\n";  // not a tilekit flag
  s += "merge=${merge%%;*}\n";
  s += "echo \"tilekit: shard array job $array, merge job $merge (afterok:$array)\"\n";
  return s;
}

std::string mpi_submit_script(const ClusterPlan& p) {
  std::string s = "#!/bin/bash\n";
  s += fmt::format("# Queues the Tilekit MPI run in {}: one job of {} ranks on {} nodes.\n", p.run_dir, p.ntasks,
                   p.nodes);
  s += "# Run it again to resume the run from its checkpoints (any number of ranks).\n";
  s += "set -euo pipefail\n";
  s += "cd " + shell_quote(p.run_dir) + "\n";
  s += "job=$(sbatch --parsable pack-mpi.sbatch)\n";  // not a tilekit flag
  s += "job=${job%%;*}  # --parsable prints ID or ID;CLUSTER\n";  // not a tilekit flag
  s += "echo \"tilekit: MPI job $job\"\n";
  return s;
}

std::vector<JobScript> job_scripts(const ClusterPlan& p) {
  if (p.mpi) return {{"pack-mpi.sbatch", pack_mpi_script(p)}, {"submit.sh", mpi_submit_script(p)}};
  return {
      {"pack-array.sbatch", pack_array_script(p)}, {"merge.sbatch", merge_script(p)}, {"submit.sh", submit_script(p)}};
}

}  // namespace tilekit::cluster
