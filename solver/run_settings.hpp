#pragma once
// RunSettings: how a search runs, as opposed to what it searches (solver/problem.hpp).
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "base/parse.hpp"
#include "solver/run_trace.hpp"
#include "solver/work_source.hpp"

namespace tilekit {

// How a search runs, as opposed to what it searches. One value goes from the command line
// (PackRequest::run, packing/request.hpp) through SearchOptions::run to the parallel driver
// (ParallelConfig::run, solver/parallel_search.hpp) and is never copied field by field: a new
// run setting is a field here, its flag and the code that uses it.
struct RunSettings {
  int threads = 1;
  std::uint64_t seed = 0;  // value orders and restart dives (part of a search's identity)
  double time_limit = 0;   // seconds; 0 = none. Hitting it leaves `complete` false.
  ShardSpec shard;         // run shard `index` of `count` (part of a search's identity)
  // ---- checkpoints ----
  std::string checkpoint_path;  // write checkpoints here ("" = none)
  double checkpoint_every = 0;  // seconds between checkpoints (0 = only on signals and at the end)
  std::string resume_path;      // resume from this checkpoint ("" = fresh start)
  // ---- reporting and signals ----
  bool progress = false;       // progress bar / log lines on stderr
  bool catch_signals = false;  // SIGTERM/SIGINT/SIGUSR1 stop the search (result.interrupted)
  // Another lane of the same run (solver/portfolio.hpp) found what was sought: when this becomes
  // true the search stops as soon as it looks, neither complete nor timed out nor interrupted.
  const std::atomic<bool>* cancel = nullptr;
  bool cancelled() const { return cancel && cancel->load(std::memory_order_relaxed); }
  // ---- scale-out ----
  // Record every subproblem (dive) this process runs, with its nodes and seconds (run_trace.hpp);
  // shared by the searches of one run (the portfolio's slices). Null: no trace.
  std::shared_ptr<RunTrace> trace;
  // Take subproblems from this source instead of the shard's fixed list (an MPI job,
  // work_source.hpp); count mode only. Null: the shard's list.
  std::shared_ptr<WorkSource> work;
};

}  // namespace tilekit
