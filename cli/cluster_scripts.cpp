#include "cli/cluster_scripts.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <regex>
#include <utility>

#include "base/error.hpp"
#include "base/version.hpp"

namespace tilekit::cli {
namespace {

// One #SBATCH directive and what it is for.
struct Directive {
  std::string option, comment;
};

std::string directives_block(const std::vector<Directive>& ds) {
  std::size_t width = 0;
  for (const auto& d : ds) width = std::max(width, d.option.size());
  std::string out;
  for (const auto& d : ds) out += fmt::format("#SBATCH {:<{}}  # {}\n", d.option, width, d.comment);
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

}  // namespace

std::string_view slurm_script_body(std::string_view name) {
  for (const EmbeddedFile& f : slurm_script_bodies())
    if (f.name == name) return f.text;
  return {};
}

namespace {

std::string body(std::string_view name) {
  std::string_view b = slurm_script_body(name);
  if (b.empty()) throw std::logic_error(fmt::format("job-script body '{}' was not embedded", name));
  return std::string(b);
}

void common_directives(const ClusterPlan& p, std::vector<Directive>& ds) {
  if (!p.partition.empty()) ds.push_back({"--partition=" + p.partition, "the partition (queue) to run in"});
  for (const auto& a : p.sbatch_args) ds.push_back({a, "passed through with --sbatch-arg"});
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

long parse_slurm_time(std::string_view text) {
  // sbatch --time formats: M, M:S, H:M:S, D-H, D-H:M, D-H:M:S.
  static const std::regex re(R"(^(?:(\d+)-(\d+)(?::(\d+)(?::(\d+))?)?|(\d+)(?::(\d+)(?::(\d+))?)?)$)");
  std::cmatch m;
  std::string s(text);
  if (!std::regex_match(s.c_str(), m, re))
    throw InputError(fmt::format("--time '{}': expected minutes, M:S, H:M:S, D-H, D-H:M or D-H:M:S", text));
  auto num = [&](int i) { return m[i].matched ? std::stol(m[i].str()) : 0L; };
  long secs = 0;
  if (m[1].matched) {
    secs = num(1) * 86400 + num(2) * 3600 + num(3) * 60 + num(4);
  } else if (m[7].matched) {
    secs = num(5) * 3600 + num(6) * 60 + num(7);
  } else if (m[6].matched) {
    secs = num(5) * 60 + num(6);
  } else {
    secs = num(5) * 60;
  }
  if (secs <= 0) throw InputError(fmt::format("--time '{}': the wall time must be positive", text));
  return secs;
}

int default_signal_seconds(long seconds) {
  return static_cast<int>(std::max(1L, std::min(120L, seconds / 2)));
}

std::string shell_quote(std::string_view text) {
  static const std::string safe = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-+=./,:@%";
  if (!text.empty() && text.find_first_not_of(safe) == std::string_view::npos) return std::string(text);
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string default_job_binary(std::string_view path_env, const std::string& self) {
  namespace fs = std::filesystem;
  for (std::size_t begin = 0; begin <= path_env.size();) {
    std::size_t end = std::min(path_env.find(':', begin), path_env.size());
    // An empty PATH entry means the current directory to a shell; a job must not depend on it.
    if (end > begin) {
      const fs::path candidate = fs::path(path_env.substr(begin, end - begin)) / "tilekit";
      std::error_code ec;
      if (fs::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0)
        return fs::canonical(fs::absolute(candidate)).string();
    }
    begin = end + 1;
  }
  return fs::canonical(self).string();
}

void check_plan(const ClusterPlan& p) {
  if (p.shards < 1) throw InputError("--shards must be at least 1");
  if (p.cpus_per_task < 1) throw InputError("--cpus-per-task must be at least 1");
  if (p.max_requeues < 0) throw InputError("--max-requeues must not be negative");
  if (p.checkpoint_every <= 0) throw InputError("--checkpoint-every must be positive");
  long limit = parse_slurm_time(p.time);
  parse_slurm_time(p.merge_time);
  if (p.signal_seconds < 1 || p.signal_seconds >= limit)
    throw InputError(
        fmt::format("--signal-seconds {} must be between 1 and the wall time ({} s)", p.signal_seconds, limit));
  // #SBATCH lines are split at white space, and '%' starts a Slurm filename pattern.
  for (const auto& [what, value] : {std::pair<const char*, const std::string&>{"--run-dir", p.run_dir},
                                    {"--partition", p.partition},
                                    {"--job-name", p.job_name}})
    if (value.find_first_of(" \t\n'\"#%\\") != std::string::npos)
      throw InputError(
          fmt::format("{} '{}': no spaces, quotes, '#', '%' or '\\' allowed in Slurm directives", what, value));
  for (const auto& a : p.sbatch_args)
    if (a.rfind("--", 0) != 0 || a.find_first_of(" \t\n") != std::string::npos)
      throw InputError(fmt::format("--sbatch-arg '{}': expected one sbatch option like --account=NAME", a));
}

std::string pack_array_script(const ClusterPlan& p) {
  std::vector<Directive> ds = {
      {"--job-name=" + p.job_name, "the name squeue shows"},
      {fmt::format("--array=0-{}", p.shards - 1),
       fmt::format("one array task per shard: shard I of {} runs as task I", p.shards)},
      {"--ntasks=1", "one tilekit process per shard..."},
      {fmt::format("--cpus-per-task={}", p.cpus_per_task),
       "...with this many cores (OMP_NUM_THREADS = SLURM_CPUS_PER_TASK)"},
      {"--time=" + p.time, "wall time of one attempt; a requeued attempt gets it anew"},
      {fmt::format("--signal=B:USR1@{}", p.signal_seconds),
       fmt::format("USR1 to this script {} s (to 60 s more) before the limit: checkpoint, exit 3", p.signal_seconds)},
      {"--requeue", "let the task requeue itself after exit 3 and resume"},
      {"--open-mode=append", "every attempt of a shard appends to the same log"},
      {"--chdir=" + p.run_dir, "working directory, on the shared filesystem"},
      {"--output=" + p.run_dir + "/logs/pack-%A_%a.out", "log of array job %A, shard %a"},
  };
  std::string s = script_head(
      p, std::move(ds),
      fmt::format("# Tilekit shard array, written by `tilekit cluster submit` (tilekit {}).\n", version_line()) +
          "# Queue it with submit.sh (it also queues the merge job), or: sbatch pack-array.sbatch\n");
  s += variable("MAX_REQUEUES", std::to_string(p.max_requeues));
  s += variable("CHECKPOINT_EVERY", fmt::format("{}", p.checkpoint_every));
  s += bash_array("COMMAND", p.command);
  s += bash_array("PACK_ARGS", p.pack_args);
  s += "\n" + body("pack-array");
  return s;
}

std::string merge_script(const ClusterPlan& p) {
  std::vector<Directive> ds = {
      {"--job-name=" + p.job_name + "-merge", "the name squeue shows"},
      {"--ntasks=1", "merging is one process..."},
      {"--cpus-per-task=1", "...writing one SQLite file"},
      {"--time=" + p.merge_time, "wall time of the merge"},
      {"--chdir=" + p.run_dir, "working directory, on the shared filesystem"},
      {"--output=" + p.run_dir + "/logs/merge-%j.out", "log of merge job %j"},
  };
  std::string s = script_head(
      p, std::move(ds),
      fmt::format("# Tilekit merge job, written by `tilekit cluster submit` (tilekit {}).\n", version_line()) +
          "# Queued after the shard array: sbatch --dependency=afterok:ARRAY_JOB_ID merge.sbatch\n" +
          "# (afterok: it starts only when every shard task ended with exit code 0).\n");
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
  s += "array=$(sbatch --parsable pack-array.sbatch)\n";
  s += "array=${array%%;*}  # --parsable prints ID or ID;CLUSTER\n";
  s += "merge=$(sbatch --parsable --dependency=afterok:\"$array\" merge.sbatch)\n";
  s += "merge=${merge%%;*}\n";
  s += "echo \"tilekit: shard array job $array, merge job $merge (afterok:$array)\"\n";
  return s;
}

}  // namespace tilekit::cli
