#pragma once
// The engine's resumable state (Gecode's recomputation idea): a search is a list of
// subproblems, each a prefix of decisions; a running subproblem is fully described by its
// path of decisions from the root. That is all a checkpoint or a shard needs to hold.
// The on-disk format lives in checkpoints/checkpoint.hpp; this is the in-memory value.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace tilekit {

// One decision: variable `var` takes value `value` (model-specific numbering).
struct Decision {
  int var = 0, value = 0;
  bool operator==(const Decision&) const = default;
};

struct SearchCounters {
  std::uint64_t solutions = 0;  // leaves times their multiplicity (e.g. torus translations)
  std::uint64_t orbits = 0;     // leaves that are the canonical member of their orbit
  std::uint64_t nodes = 0;
  SearchCounters& operator+=(const SearchCounters& o) {
    solutions += o.solutions;
    orbits += o.orbits;
    nodes += o.nodes;
    return *this;
  }
  bool operator==(const SearchCounters&) const = default;
};

// A subproblem stopped part-way: the node to explore next (its whole decision path from the
// root, prefix included) and what was counted in it before that node.
struct InFlightSubproblem {
  std::uint64_t index = 0;
  std::vector<Decision> path;
  SearchCounters counted;
};

struct SearchState {
  // Identity of the run: everything that must match for a resume to give the uninterrupted
  // result (problem, mode, formulation, ordering, seed, shard). Compared as text.
  std::string fingerprint;
  std::uint64_t subproblem_count = 0;  // over all shards
  std::uint64_t subproblem_hash = 0;   // hash of every subproblem prefix
  std::vector<bool> finished;          // per subproblem
  SearchCounters finished_counts;      // sum over finished subproblems
  // What each finished subproblem counted, in index order (one entry per set bit of
  // `finished`): the sum must equal finished_counts, so a state whose finished marks and
  // counts disagree (a subproblem counted but unmarked, to be counted again) is refused.
  std::vector<SearchCounters> finished_each;
  std::vector<InFlightSubproblem> in_flight;
  std::uint64_t restarts = 0;       // first mode with restarts: restarts done so far
  std::uint64_t restart_nodes = 0;  // nodes spent in those restarts
  double seconds = 0;               // wall time spent by earlier runs of this search
};

// Bounds of a resumable state (README, "Bad input"): the engine splits a search into about a
// thousand subproblems (2^24 is far beyond any split), a decision path is at most one decision
// per variable (2^24 variables is far beyond any model that fits in memory), and 2^40 restarts
// of at least one node each would take years; a larger count would only make the Luby
// schedule overflow.
inline constexpr std::uint64_t kMaxSubproblems = std::uint64_t(1) << 24;
// The most subproblems a search splits into by itself (64 per shard up to 1024 shards): the
// split replays every prefix, and beyond this it took longer than whole searches (a corner
// C=3 count split for --shard 77/100000 ran past the count itself).
inline constexpr std::size_t kMaxSplitSubproblems = std::size_t(1) << 16;
inline constexpr std::size_t kMaxDecisionPath = std::size_t(1) << 24;
inline constexpr std::uint64_t kMaxRestarts = std::uint64_t(1) << 40;

// Structural validation of a state read from a checkpoint, as data: the finished bitmap has
// one bit per subproblem; every in-flight subproblem is in range, unfinished and listed once;
// counters are consistent (orbits <= solutions; one count per finished subproblem, summing to
// the finished total); restarts and seconds bounded. (Restart nodes without a finished restart are
// normal: a checkpoint resumes at the lowest dive cut short, whose nodes are already counted.)
// With `subproblems` > 0 it also checks the state against the search resuming it (its
// subproblem count, and that every finished and in-flight subproblem belongs to shard I of N). A
// checksum only proves the file is as written; this proves it can be resumed to the
// uninterrupted result. Throws InputError naming the first problem found.
void check_search_state(const SearchState& state, std::uint64_t subproblems = 0, int shard_index = 0,
                        int shard_count = 1);
// The nodes a state has counted (restarts, finished subproblems and those in flight): what a
// search resumed from it reports on top of its own work.
std::uint64_t counted_nodes(const SearchState& state);
// Adds `from` (another process's state of the same search: an MPI rank's checkpoint) to `into`:
// a subproblem finished in either is finished, with its own counts; one in flight in either and
// finished in neither stays in flight at the snapshot that counted more nodes. Idempotent, so
// merging stale or repeated files never counts a subproblem twice. InputError unless both have
// the same fingerprint and subproblem list.
void merge_search_states(SearchState& into, const SearchState& from);

// The portfolio's resumable state (solver/portfolio.hpp): where the schedule stands and, per
// candidate, what it used and its own engine state.
struct PortfolioCandidateState {
  std::string name;    // "plain", a group spec, "sat:SPEC", ...
  bool empty = false;  // its subspace was exhausted without a solution
  std::uint64_t slices = 0, nodes = 0;
  double seconds = 0;                 // budget used so far (wall seconds of its slices)
  std::optional<SearchState> engine;  // its engine checkpoint (none before its first slice)
};

struct PortfolioState {
  std::string fingerprint;                          // problem, seed, shard, the set of candidates, the first slice
  std::uint64_t round = 0;                          // slices of this round last first_slice * 2^round seconds
  std::uint64_t next = 0;                           // the next candidate to run in this round (index into candidates)
  std::uint64_t side_round = 0, side_next = 0;      // the same for the side lane of restarting candidates
  std::vector<PortfolioCandidateState> candidates;  // in schedule order
  double seconds = 0;                               // wall time spent by earlier runs of this portfolio
};

}  // namespace tilekit
