#pragma once
// A trace of a run's work: one JSON line per subproblem (or restart dive) this process ran, with
// its index, decision path, owner (shard or MPI rank), nodes, seconds and the cost of each piece
// below it (the subtrees `kTracePieceDepth` levels under the subproblem's prefix, in DFS order),
// so that a scheduling simulator (cluster/schedule_sim.hpp) can replay the run under another
// policy, including one that splits a subproblem. Written whole (temp file, fsync, rename) at
// every checkpoint and at the end of each search, so a killed run leaves the trace of its last
// checkpoint. Several searches of one process (the slices of a portfolio) append to one trace.
//
//   {"type":"search","title":...,"mode":"first"|"count","subproblems":N,"threads":T,"owner":"0/1","split_nodes":n,
//    "resumed":bool}
//   {"type":"subproblem","title":...,"index":i,"path":"var=value ...","owner":"I/N" or
//    "rank R","nodes":n,"seconds":s,"solutions":k,"resumed":bool,"pieces":[[nodes,seconds],...]}
//   {"type":"dive","title":...,"dive":r,"owner":...,"nodes":n,"seconds":s,"found":bool}
//   with work stealing (work_source.hpp), the same fields as a subproblem line for what was left of
//   a subproblem that gave work away ("type":"split") and for each stolen piece ("type":"piece",
//   "path" its own decision path); a simulator replaying whole subproblems skips them.
#include <cstdint>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace tilekit {

// Levels below a subproblem's prefix at which its pieces are cut: a subproblem of the trace is
// split into the subtrees rooted this many decisions deeper, in DFS order (an inner node above
// them is a piece of its own, of one node).
inline constexpr std::size_t kTracePieceDepth = 4;

class RunTrace {
 public:
  explicit RunTrace(std::string path) : path_(std::move(path)) {}
  const std::string& path() const { return path_; }
  // Appends one JSON line (without its newline); thread-safe.
  void add(std::string line);
  // Writes every line so far to path() atomically (InputError naming the path on failure).
  void write();
  std::size_t lines() const;

 private:
  std::string path_;
  mutable std::mutex mu_;
  std::vector<std::string> lines_;
};

}  // namespace tilekit
