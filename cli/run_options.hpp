#pragma once
// The run options of every long command (threads, seed, time limit, checkpoints, shard), added
// through one function so that their names, meanings and help text are the same everywhere:
// `--threads 0` is every core for each of them (base/run_control.hpp resolve_threads).
#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

#include "base/run_control.hpp"
#include "solver/run_settings.hpp"

namespace tilekit::cli {

enum class RunOptionFlags : unsigned { Threads = 1, Seed = 2, TimeLimit = 4, Checkpoint = 8, Shard = 16 };
constexpr RunOptionFlags operator|(RunOptionFlags a, RunOptionFlags b) {
  return RunOptionFlags(unsigned(a) | unsigned(b));
}
constexpr bool has(RunOptionFlags set, RunOptionFlags f) {
  return (unsigned(set) & unsigned(f)) != 0;
}

// The values of the run options. A command sets its own defaults (a seed of 1, a time limit of
// 10 s, a checkpoint every 60 s) before add_run_options(), which shows them in --help.
struct RunOptions {
  std::int64_t threads = 0;  // 0: every core
  std::uint64_t seed = 0;
  double time_limit = 0;  // seconds; 0: none
  std::string checkpoint, resume;
  double checkpoint_every = 0;  // seconds
  std::string shard = "0/1";

  int resolved_threads() const { return resolve_threads(threads); }
  // InputError naming the flag unless the time limit and the checkpoint interval are finite
  // numbers of seconds >= 0 (NaN, inf and negative values are refused, not read as "none").
  void check_seconds() const;
  ShardSpec shard_spec() const;
  // Threads (resolved), seed, time limit, shard and checkpoint paths into `run`, and the
  // checkpoint interval where `cmd` was given --checkpoint-every (else `run` keeps its default).
  void apply(RunSettings& run, const CLI::App& cmd) const;
};

// Adds the options of `which` to `cmd`, bound to `o`.
void add_run_options(CLI::App* cmd, RunOptionFlags which, RunOptions& o);

}  // namespace tilekit::cli
