#include "cli/run_options.hpp"

#include <fmt/format.h>

#include <cmath>
#include <utility>

#include "base/error.hpp"
#include "base/parse.hpp"
#include "cli/numeric_flags.hpp"

namespace tilekit::cli {

ShardSpec RunOptions::shard_spec() const {
  return parse_shard(shard);
}

void RunOptions::check_seconds() const {
  for (auto [value, flag] : {std::pair{time_limit, "--time-limit"}, std::pair{checkpoint_every, "--checkpoint-every"}})
    if (!(value >= 0) || !std::isfinite(value))
      throw InputError(fmt::format("{} must be a number of seconds >= 0, got {}", flag, value));
}

void RunOptions::apply(RunSettings& run, const CLI::App& cmd) const {
  check_seconds();
  run.threads = resolved_threads();
  run.seed = seed;
  run.time_limit = time_limit;
  run.shard = shard_spec();
  run.checkpoint_path = checkpoint;
  run.resume_path = resume;
  if (cmd.count("--checkpoint-every")) run.checkpoint_every = checkpoint_every;
}

void add_run_options(CLI::App* cmd, RunOptionFlags which, RunOptions& o) {
  using F = RunOptionFlags;
  if (has(which, F::Threads))
    cmd->add_option("--threads", o.threads, "Worker threads; 0 = every core (OMP_NUM_THREADS when set)")
        ->capture_default_str();
  if (has(which, F::Seed))
    cmd->add_option("--seed", o.seed, "Seed: the same seed gives the same result on any thread count")
        ->capture_default_str();
  if (has(which, F::TimeLimit))
    cmd->add_option("--time-limit", o.time_limit, "Stop after this many seconds (0 = none)")
        ->check(non_negative_seconds())
        ->capture_default_str();
  if (has(which, F::Checkpoint)) {
    cmd->add_option("--checkpoint", o.checkpoint,
                    "Write checkpoints to this file (atomically: every --checkpoint-every s, at the end, and on "
                    "SIGTERM/SIGINT/SIGUSR1, which then exit 3)");
    cmd->add_option("--checkpoint-every", o.checkpoint_every, "Seconds between checkpoints")
        ->check(non_negative_seconds())
        ->capture_default_str();
    cmd->add_option("--resume", o.resume, "Continue the run this checkpoint holds");
  }
  if (has(which, F::Shard))
    cmd->add_option("--shard", o.shard, "Run shard I of N (I/N, 0-based)")->capture_default_str();
}

}  // namespace tilekit::cli
