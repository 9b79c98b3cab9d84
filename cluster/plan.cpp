#include "cluster/plan.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <utility>

#include "base/error.hpp"
#include "base/parse.hpp"
#include "cluster/slurm_time.hpp"

namespace tilekit::cluster {
namespace fs = std::filesystem;
namespace {

// A carriage return or another control character would split or hide a line of the scripts.
bool has_control_character(const std::string& s) {
  return std::any_of(s.begin(), s.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
}

bool enumerate_run(const SubmitRequest& r) {
  return r.command == "enumerate";
}

// The shard command and the arguments the request gives it (before --pack-arg).
void set_shard_command(const SubmitRequest& r, ClusterPlan& p) {
  if (enumerate_run(r)) {
    if (r.settings.mpi) throw InputError("`mpi` runs `pack` only (`command` enumerate has no MPI run)");
    if (r.settings.split_after > 0) throw InputError("`split_after` splits `pack` shards only (not `command` enumerate)");
    // `tilekit aperiodic enumerate` shards like pack (aperiodic/enumerate.hpp); its options come
    // with --pack-arg.
    if (!r.kind.empty() || r.colors != 0 || !r.method.empty() || !r.seed.empty())
      throw InputError("`command` enumerate takes no `kind`, `colors`, `method` or `seed` (use `shard_args`)");
    p.command = {"aperiodic", "enumerate"};
    p.pack_args.clear();
    return;
  }
  if (r.command != "pack") throw InputError(fmt::format("`command` must be pack or enumerate, got '{}'", r.command));
  if (r.kind != "wang" && r.kind != "corner" && r.kind != "window")
    throw InputError("`kind` must be wang, corner or window");
  const ShardCommandWords& w = r.words;
  const bool has_window = std::any_of(r.shard_args.begin(), r.shard_args.end(),
                                      [&](const std::string& a) { return a.rfind(w.window + "=", 0) == 0; });
  if (r.kind == "window" && !has_window)
    throw InputError(fmt::format("`kind` window needs `shard_args`={}=KxL and the torus size", w.window));
  if (r.colors < 1) throw InputError("`colors` must be at least 1");
  p.pack_args = {w.kind, r.kind, w.colours, std::to_string(r.colors)};
  if (!r.method.empty()) p.pack_args.insert(p.pack_args.end(), {w.method, r.method});
  if (r.settings.split_after > 0 && r.mode != "count" && r.mode != "all")
    throw InputError(fmt::format("`split_after`: a split run counts or lists all (`mode` count or all), got `mode` {}",
                                 r.mode));
  if (r.settings.mpi && r.mode != "count")
    throw InputError(fmt::format("`mpi` runs count only (`pack {}` counts), got `mode` {}", w.mpi, r.mode));
  p.pack_args.insert(p.pack_args.end(), {w.mode, r.mode});
  if (!r.seed.empty()) p.pack_args.insert(p.pack_args.end(), {w.seed, r.seed});
}

// The user's extra shard arguments; the ones the job script sets per shard are refused.
void append_shard_args(const SubmitRequest& r, ClusterPlan& p) {
  for (const auto& a : r.shard_args) {
    for (const std::string& own : r.words.per_shard)
      if (a == own || a.rfind(own + "=", 0) == 0)
        throw InputError(fmt::format("`shard_args` {}: the job script sets it per shard", a));
    p.pack_args.push_back(a);
  }
}

std::string absolute_run_dir(const SubmitRequest& r) {
  const std::string run_dir = !r.run_dir.empty() ? r.run_dir
                              : enumerate_run(r) ? std::string("tilekit-run-enumerate")
                                                 : fmt::format("tilekit-run-{}{}-{}", r.kind, r.colors, r.mode);
  std::string dir = fs::absolute(run_dir).lexically_normal().string();
  if (dir.size() > 1 && dir.back() == '/') dir.pop_back();
  return dir;
}

std::string job_binary(const SubmitRequest& r, const PlanEnvironment& env) {
  if (r.tilekit.empty()) return default_job_binary(env.path, env.self);
  std::string path = fs::absolute(r.tilekit).string();
  if (!fs::is_regular_file(path) || ::access(path.c_str(), X_OK) != 0)
    throw InputError(fmt::format("`tilekit` {}: not an executable file", r.tilekit));
  return path;
}

}  // namespace

PlanEnvironment current_environment() {
  const char* path = std::getenv("PATH");
  return {path ? path : "", "/proc/self/exe"};
}

std::string default_job_binary(std::string_view path_env, const std::string& self) {
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

ClusterPlan make_plan(const SubmitRequest& r, const PlanEnvironment& env) {
  ClusterPlan p = r.settings;
  set_shard_command(r, p);
  append_shard_args(r, p);
  p.run_dir = absolute_run_dir(r);
  p.tilekit = job_binary(r, env);
  p.job_name = !r.job_name.empty() ? r.job_name
               : enumerate_run(r)  ? std::string("tk-enumerate")
                                   : fmt::format("tk-{}{}", r.kind, r.colors);
  p.merge_time = r.merge_time.empty() ? p.time : r.merge_time;
  if (p.mpi && p.ntasks == 0) p.ntasks = p.nodes;
  p.signal_seconds = r.signal_seconds > 0 ? r.signal_seconds : default_signal_seconds(parse_slurm_time(p.time));
  check_plan(p);
  return p;
}

void check_plan(const ClusterPlan& p) {
  if (p.shards < 1 || p.shards > kMaxShards)
    throw InputError(fmt::format("`shards` must be between 1 and {}", kMaxShards));
  if (p.cpus_per_task < 1) throw InputError("`cpus_per_task` must be at least 1");
  if (p.mpi) {
    if (p.shards != 1) throw InputError("`mpi` runs one job: `shards` must be 1 (the ranks share the work)");
    if (p.nodes < 1 || p.nodes > kMaxShards) throw InputError(fmt::format("`nodes` must be between 1 and {}", kMaxShards));
    if (p.ntasks < p.nodes || p.ntasks > kMaxShards)
      throw InputError(fmt::format("`ntasks` must be between `nodes` ({}) and {}", p.nodes, kMaxShards));
    if (p.launcher != "srun" && p.launcher != "mpirun")
      throw InputError(fmt::format("`launcher` must be srun or mpirun, got '{}'", p.launcher));
    if (p.srun_mpi.empty() || p.srun_mpi.size() > 32 ||
        p.srun_mpi.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_") != std::string::npos)
      throw InputError(fmt::format("`srun_mpi` '{}': expected an MPI plugin name such as pmix or pmi2", p.srun_mpi));
  }
  if (!(p.split_after >= 0) || !(p.split_after <= kMaxCheckpointSeconds))
    throw InputError(fmt::format("`split_after` must be 0 (no splitting) or a number of seconds up to a year, got {}",
                                 p.split_after));
  if (p.split_ways < 2 || p.split_ways > 1000)
    throw InputError(fmt::format("`split_ways` must be between 2 and 1000, got {}", p.split_ways));
  if (p.split_after > 0 && p.mpi) throw InputError("`split_after` splits a job array; an `mpi` run shares its work");
  if (p.max_requeues < 0) throw InputError("`max_requeues` must not be negative");
  // NaN fails every comparison: !(x > 0) refuses it with the non-positive ones.
  if (!(p.checkpoint_every > 0) || !(p.checkpoint_every <= kMaxCheckpointSeconds))
    throw InputError(fmt::format("`checkpoint_every` must be a positive number of seconds, at most {} (a year), got {}",
                                 kMaxCheckpointSeconds, p.checkpoint_every));
  long limit = parse_slurm_time(p.time);
  parse_slurm_time(p.merge_time, "merge_time");
  if (p.signal_seconds < 1 || p.signal_seconds >= limit)
    throw InputError(
        fmt::format("`signal_seconds` {} must be between 1 and the wall time ({} s)", p.signal_seconds, limit));
  // #SBATCH lines are split at white space, and '%' starts a Slurm filename pattern.
  for (const auto& [what, value] : {std::pair<const char*, const std::string&>{"`run_dir`", p.run_dir},
                                    {"`partition`", p.partition},
                                    {"`job_name`", p.job_name}})
    if (value.find_first_of(" \t\n'\"#%\\") != std::string::npos || has_control_character(value))
      throw InputError(
          fmt::format("{} '{}': no spaces, quotes, '#', '%' or '\\' allowed in Slurm directives", what, value));
  for (const auto& a : p.sbatch_args)
    if (a.rfind("--", 0) != 0 || a.find_first_of(" \t\n") != std::string::npos || has_control_character(a))
      throw InputError(
          fmt::format("`sbatch_args` '{}': expected one sbatch option like "
                      "--account=NAME",  // not a tilekit flag
                      a));
  // What the run file may hold (run_directory.cpp reads it back with these bounds).
  if (p.pack_args.size() > kMaxShardArgs) throw InputError(fmt::format("at most {} `shard_args`", kMaxShardArgs));
  for (const auto& a : p.pack_args)
    if (a.size() > kMaxShardArgBytes)
      throw InputError(fmt::format("`shard_args`: an argument of {} bytes, more than {}", a.size(), kMaxShardArgBytes));
}

}  // namespace tilekit::cluster
