#pragma once
// Engine statistics (CaDiCaL's `stats`): what a search did, so that every run can explain
// itself. Each worker counts in its own plain integers (its SubtreeSearch and its copy of the
// model, whose counters join the worker's after each subproblem or dive) and a worker's counts
// join the run's total once, when it leaves: counting needs no atomics in the search loop.
//
// The counters:
//   nodes        search nodes entered (the engine's node count, the subproblem split included)
//   decisions    values tried at a node (a model assign() during the search)
//   conflicts    decisions the model refused (assign() returned false): one pruning rule each
//   backtracks   returns from a node to its parent (a leaf left, a subtree exhausted)
//   leaves       complete assignments reached (solutions = leaves x multiplicity)
//   propagations domains a model revised by forward checking after an assignment
//   prunes[rule] dead ends per rule (Prune below); the assign() rules sum to `conflicts`
// and the time per phase: setup (the plan and the model build), split (subproblems),
// estimate (Knuth probes), search (the workers, periodic checkpoints included), checkpoint
// writes (all of them). A subproblem's prefix (and a resumed path) is replayed by assign()
// alone: it adds propagations, but no nodes or decisions.
#include <array>
#include <cstddef>
#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <string>

namespace tilekit {

// Why a branch of the search died. Every model names the rule that refused an assignment.
enum class Prune : int {
  EmptyDomain,   // the variable chosen at a node had no candidate value (counted by the engine)
  ForwardCheck,  // a free neighbour (cell model) or a window/cell with one free variable lost its last option
  ClassCheck,    // lifts: a free cell of the placed tile's residue class lost its last option
  NoSuchTile,    // a completed cell's edges or corners form no tile of the set
  TileUsed,      // packings: a completed cell's tile (window tori: its window) is already placed
  OrbitUsed,     // under an imposed group: a completed cell's tile orbit is already placed
  PatternCount,  // under an imposed group: more partial cells need a pattern than unused orbits offer it
  Count_         // number of rules
};
inline constexpr std::size_t kPruneRules = std::size_t(Prune::Count_);

// The rule's name in tables and JSON ("empty-domain", ...).
const char* prune_name(Prune rule);

// What a model counts (each model holds one; the engine resets it on every copy it searches).
struct ModelStats {
  std::uint64_t propagations = 0;
  std::array<std::uint64_t, kPruneRules> prunes{};
  void prune(Prune rule) { ++prunes[std::size_t(rule)]; }
  ModelStats& operator+=(const ModelStats& o) {
    propagations += o.propagations;
    for (std::size_t i = 0; i < kPruneRules; ++i) prunes[i] += o.prunes[i];
    return *this;
  }
};

struct SearchStats {
  // ---- the tree (this run only; a resumed run counts from zero) ----
  std::uint64_t nodes = 0, decisions = 0, conflicts = 0, backtracks = 0, leaves = 0;
  std::uint64_t solutions = 0;  // leaves x multiplicity (First mode: the solutions reported)
  std::uint64_t restarts = 0;   // Luby restarts (first mode)
  ModelStats model;             // propagations and prunes per rule
  std::uint64_t searches = 0;   // solve() calls summed here (portfolio slices, torus shapes)
  // ---- time per phase, seconds ----
  double setup_seconds = 0, split_seconds = 0, estimate_seconds = 0, search_seconds = 0, checkpoint_seconds = 0;
  std::uint64_t checkpoints = 0;

  std::uint64_t prunes(Prune rule) const { return model.prunes[std::size_t(rule)]; }
  // Sums two runs (counters and times); used to merge workers, slices and shapes.
  SearchStats& operator+=(const SearchStats& o);
};

// {"nodes": ..., "prunes": {"empty-domain": ...}, "seconds": {"setup": ...}, ...}
void to_json(nlohmann::json& j, const SearchStats& s);
// A short table for humans (one counter per line), e.g. for `pack --stats` on stderr.
std::string stats_table(const SearchStats& s);

}  // namespace tilekit
