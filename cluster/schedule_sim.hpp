#pragma once
// Replays the trace of a run (solver/run_trace.hpp) under a scheduling policy on P workers and
// reports the makespan against the ideal (total work / P): what `tilekit cluster simulate` does.
//
// What a trace lets us model, and what not:
//  - The work of a subproblem is what the traced run spent on it (nodes, or seconds); a
//    subproblem splits only into its pieces (the subtrees kTracePieceDepth levels below its
//    prefix, in DFS order), and a piece is never split: every policy's makespan is at least the
//    largest piece (`bound` reports max(ideal, largest piece)).
//  - Communication, job start and steal latencies are 0: the figures are upper bounds on the
//    efficiency of each policy (the `split` policy also counts its follow-up rounds).
//  - A first-mode trace (restart dives or subproblems until the first solution) is a list of
//    units in the order run; the run ends when the unit that found the solution ends, and every
//    policy hands out whole units (a dive is not split). More workers would start dives the trace
//    does not hold, so only the traced dives are replayed.
//
// Policies:
//  - static: unit i on worker i mod P (a Slurm job array of P shards, `--shard I/P`);
//  - pool: workers take whole units in index order as they become free (the MPI job's dynamic
//    pool, cluster/mpi_work.hpp);
//  - split: rounds of `static`, each cut at the round's fair share (outstanding work / P); the
//    subproblems a shard did not start stay whole, the one it was running leaves its unstarted
//    pieces (and the rest of the running piece) as new units, which the next round's array
//    spreads i mod P; the last round runs to the end (adaptive splitting for job arrays);
//  - steal: `pool`, and once the pool is empty an idle worker takes the later half of the
//    unstarted pieces of the worker with the most unstarted work (the oldest open subtrees; an
//    oracle victim, where a real thief tries random victims).
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace tilekit::cluster {

enum class SchedulePolicy { Static, Pool, Split, Steal };
const char* policy_name(SchedulePolicy p);
// "static", "pool", "split" or "steal"; InputError otherwise.
SchedulePolicy policy_from_name(const std::string& word);

// One unit of work of the traced run: a subproblem (with its pieces) or a dive.
struct TraceUnit {
  std::uint64_t index = 0;
  double cost = 0;            // nodes or seconds
  std::vector<double> pieces;  // in DFS order, summing to cost; empty: one piece
  bool found = false;          // first mode: this unit found the solution
};

struct Trace {
  std::string files;  // the files read, for reports
  bool first = false;  // a first-mode run: it ends when the found unit ends
  bool found = false;  // first mode: the last unit found the solution (else the run ran out of time)
  std::vector<TraceUnit> units;
  double work() const;  // the total cost (first mode: up to and including the found unit)
  double largest_piece() const;
};

// Reads trace files (the lines of solver/run_trace.hpp; several files: the ranks of an MPI job
// or the shards of a job array, merged by subproblem index) with the cost `nodes` or `seconds`.
// A subproblem traced twice (run again after a resume) counts once, as first traced. InputError
// naming the file and line on a malformed line; also on an unknown cost, no work at all, or two
// different exhaustive searches in one trace.
Trace read_trace(const std::vector<std::string>& files, const std::string& cost);

struct SimResult {
  SchedulePolicy policy = SchedulePolicy::Static;
  std::int64_t workers = 0;
  double makespan = 0, ideal = 0, bound = 0;
  double efficiency = 0;  // ideal / makespan
  int rounds = 1;          // split: the arrays run
  std::uint64_t steals = 0;
};

// `workers` >= 1 (InputError otherwise); `max_rounds` >= 1 is split's number of arrays.
SimResult simulate(const Trace& trace, SchedulePolicy policy, std::int64_t workers, int max_rounds = 4);

nlohmann::json to_json(const SimResult& r);

}  // namespace tilekit::cluster
