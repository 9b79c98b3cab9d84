#pragma once
// Where the subproblems of a search come from when several processes share one run (an MPI job,
// cluster/mpi_work.hpp): instead of the fixed list of its shard, each worker thread of the
// parallel driver asks the source for its next job. The driver does everything else as for one
// process (its threads, checkpoints of what it ran, the trace); the source hands each job out
// once and, at the end, sums every process's counters on the root.
#include <cstdint>
#include <vector>

#include "solver/search_state.hpp"

namespace tilekit {

// One subproblem to run: its index, and for a resumed one the path to continue at and what the
// part before that path counted.
struct WorkItem {
  std::uint64_t index = 0;
  std::vector<Decision> resume;
  SearchCounters counted;
};

class WorkSource {
 public:
  virtual ~WorkSource() = default;
  virtual int rank() const = 0;   // this process, 0 = the root
  virtual int ranks() const = 0;  // processes in the run
  // Called once per search after the split, with the subproblem list's size and hash (every
  // process checks that its list is the root's: InputError otherwise) and, on the root, the jobs
  // of the run (unfinished subproblems; resumed ones with their paths). Other processes' `jobs`
  // are ignored.
  virtual void start(std::uint64_t subproblems, std::uint64_t hash, std::vector<WorkItem> jobs) = 0;
  // The next job for a worker thread of this process; false when there is none left (or this
  // process stopped).
  virtual bool next(WorkItem& job) = 0;
  // The root's jobs with a resume path not yet handed out (a checkpoint keeps them in flight).
  virtual std::vector<WorkItem> queued_resumed() = 0;
  // Called once per search when this process's workers are done: `mine` is what it counted,
  // `stopped` whether it stopped early (signal, time limit). Returns, on the root, the sum over
  // every process and sets `complete` when every job was handed out and no process stopped; on
  // the others, `mine` and `complete` = !stopped.
  virtual SearchCounters finish(const SearchCounters& mine, bool stopped, bool& complete) = 0;
};

}  // namespace tilekit
