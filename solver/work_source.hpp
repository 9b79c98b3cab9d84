#pragma once
// Where the subproblems of a search come from when several processes share one run (an MPI job,
// cluster/mpi_work.hpp): instead of the fixed list of its shard, each worker thread of the
// parallel driver asks the source for its next job. The driver does everything else as for one
// process (its threads, checkpoints of what it ran, the trace); the source hands each job out
// once and, at the end, sums every process's counters on the root.
//
// Work stealing: when the pool runs dry while jobs are still running, the source raises a
// process's split_flag(); the first of its workers to see it gives away the untried alternatives
// of its shallowest open level (solver/dfs.hpp) through give(), and those child subtrees become
// jobs of their own (pieces). A subproblem that gave pieces away is *split*: no process marks it
// finished in its checkpoint; its jobs report their counts through done() and the root marks it
// finished, with the sum, once every piece is done (completed_splits()). A split subproblem's
// in-flight snapshot stays a valid checkpoint record of the whole subproblem (its pieces lie after
// the snapshot's path, and their counts are kept nowhere until the subproblem completes); a
// piece's is never recorded.
#include <atomic>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "solver/search_state.hpp"

namespace tilekit {

// One subproblem to run: its index, and for a resumed one the path to continue at and what the
// part before that path counted; or a piece of subproblem `index` given away by a split: the
// child subtree at `piece` (its whole decision path).
struct WorkItem {
  std::uint64_t index = 0;
  std::vector<Decision> resume;
  SearchCounters counted;
  std::vector<Decision> piece;
};

// What the root's source did for the run (pack --json's "mpi").
struct WorkStats {
  int ranks = 1;
  std::uint64_t jobs = 0;      // handed out (subproblems and pieces)
  std::uint64_t steals = 0;    // splits that gave work away
  std::uint64_t pieces = 0;    // child subtrees they gave
  std::uint64_t declined = 0;  // split requests answered with nothing (no open alternative in time)
  std::uint64_t splits_completed = 0;  // split subproblems whose every piece was done
};

class WorkSource {
 public:
  virtual ~WorkSource() = default;
  virtual int rank() const = 0;   // this process, 0 = the root
  virtual int ranks() const = 0;  // processes in the run
  // Called once per search after the split, with the subproblem list's size and hash (every
  // process checks that its list is the root's: InputError otherwise) and, on the root, the jobs
  // of the run (unfinished subproblems; resumed ones with their paths). Other processes' `jobs`
  // are ignored. `stopping` says when this process stops (next() then gives up waiting).
  virtual void start(std::uint64_t subproblems, std::uint64_t hash, std::vector<WorkItem> jobs,
                     std::function<bool()> stopping) = 0;
  // The next job for a worker thread of this process; false when there is none left (every job
  // of the run done, or the run stopped). May wait while other jobs run (they may be split).
  virtual bool next(WorkItem& job) = 0;
  // A job of this process is done: `split` when it is a piece or gave pieces away (its counts
  // then go to the root's sum of the subproblem), else it is finished here.
  virtual void done(std::uint64_t index, bool split, const SearchCounters& counted) = 0;
  // Raised when this process should give work away; a worker that can takes it (exchange to
  // false) and calls give(). Null: never.
  virtual std::atomic<bool>* split_flag() = 0;
  // Child subtrees of subproblem `index` (their whole paths) for other workers.
  virtual void give(std::uint64_t index, std::vector<std::vector<Decision>> pieces) = 0;
  // On the root: every split subproblem whose jobs are all done, with their summed counts (all
  // so far, each once per run). Empty elsewhere.
  virtual std::vector<std::pair<std::uint64_t, SearchCounters>> completed_splits() = 0;
  virtual WorkStats stats() = 0;
  // The root's jobs with a resume path not yet handed out (a checkpoint keeps them in flight).
  virtual std::vector<WorkItem> queued_resumed() = 0;
  // Called once per search when this process's workers are done: `mine` is what it counted,
  // `stopped` whether it stopped early (signal, time limit). Returns, on the root, the sum over
  // every process and sets `complete` when every job was handed out and no process stopped; on
  // the others, `mine` and `complete` = !stopped.
  virtual SearchCounters finish(const SearchCounters& mine, bool stopped, bool& complete) = 0;
};

}  // namespace tilekit
