#pragma once
// `tilekit aperiodic enumerate`: a best-first search over chains of conversions
// (aperiodic/steps.hpp) from the published aperiodic Wang sets, every set deduplicated by its
// canonical form up to symmetry and colour names (aperiodic/canonical.hpp).
//
// The search. Sets reached by a chain of sound steps (published, conjugate, lifts, prune) of
// length d < max_depth with at most max_tiles tiles are expanded: every step in every symmetry
// that matters (steps.hpp) is applied and each result recorded as an edge. Expansion goes in
// batches of the smallest pending sets (tiles, then kind, then canonical hash); a set reached
// again by a shorter sound chain is expanded again with the shorter depth. The sets and edges at
// the end are therefore those of a fixed point that depends on the options only, not on the order,
// the thread count or on interruptions: a run killed and resumed stores exactly what an
// uninterrupted one stores. A result of an unverified step is a lead: the transducer decision
// (aperiodic/decide.hpp, bounded by k, so deterministic) labels it periodic or finite, or it stays a
// lead and is reported; leads are never expanded.
//
// Shards (--shard I/N): the published sets are expanded by every shard; a set one step from them
// belongs to shard (its hash mod N) and only its owner continues from it. The sets reachable
// within the depth are the union over those first steps of what each reaches, so the shards'
// edges and sets merge to those of the whole run.
//
// Checkpoints (TILEKIT-ENUMERATE envelope of checkpoints/checkpoint.hpp, JSON body): every set
// and edge so far, written between batches every checkpoint_every seconds, at the end, at the time
// limit and on SIGTERM/SIGINT/SIGUSR1 (then `interrupted`, the CLI exits 3). A corrupt, truncated
// or foreign checkpoint, or one of other options, is an InputError.
//
// Trace (`--trace FILE`, solver/run_trace.hpp): a "search" line, then one "subproblem" line per
// set expanded: index (batch * batch size + position), path "set HASH depth D", owner "I/N",
// nodes = the steps applied, seconds, solutions = the results kept or counted, batch, and a piece
// [1, seconds] per step. Batches run one after another (a batch's sets come from the one before),
// which a simulator replaying the lines as independent units does not model.
//
// Storage: every set as a tile set (name enum-HASH, content hash = the canonical hash, source
// "published: NAME" for the sources) and every edge as a conversion (method = the step, soundness =
// its label), written batch by batch; rows are keyed by content, so rewriting is harmless.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/run_control.hpp"
#include "tilesets/tile_set.hpp"

namespace tilekit {

class RunTrace;  // solver/run_trace.hpp

struct EnumerateOptions {
  std::vector<std::string> sources;  // built-in names; empty: every published aperiodic Wang set
  int max_depth = 3;                 // longest chain expanded (steps from a source)
  std::size_t max_tiles = 60;        // larger results are counted, not kept
  std::size_t batch = 8;             // sets expanded per batch (fixed: results never depend on threads)
  int threads = 0;                   // 0: every core (base/run_control.hpp resolve_threads)
  ShardSpec shard;                   // this run's shard (base/run_control.hpp)
  int lead_max_k = 6;                // the decision of a lead builds T_1..T_k per direction
  std::vector<std::string> operations;  // the step operations tried; empty: step_operations() (aperiodic/steps.hpp)
  double time_limit = 0;             // seconds for this run; 0: none (stops between batches)
  std::string checkpoint_path, resume_path;
  double checkpoint_every = 60;      // seconds; 0: after every batch
  std::string db;                    // results database; "" = none
  bool progress = false;
  bool catch_signals = false;
  // Record every set this run expands (solver/run_trace.hpp; written at every checkpoint and at the
  // end): a line per expansion, its steps as pieces [1, seconds]. Null: no trace.
  std::shared_ptr<RunTrace> trace;
};

struct EnumNode {
  std::string hash, text;  // canonical form (aperiodic/canonical.hpp)
  TileKind kind = TileKind::Wang;
  std::size_t tiles = 0;
  std::uint32_t colours = 0;
  int depth = -1;        // least length of a sound chain to it; -1: none (a lead only)
  int owned_depth = -1;  // the same over chains this shard continues from
  int expanded = -1;     // owned depth it was last expanded at; -1: never
  std::string parent, step, label, root;  // the first shortest sound link (root: the source's name)
  std::string lead;      // leads: what the decision said ("unknown at k=6", ...)
};

struct EnumEdge {
  std::string from, step, to, label, argument;
};

// What re-derives a link of a chain: its source and the steps from it (none: the source itself).
// The CLI words it as the command that checks the link (`aperiodic link`, `tileset show`).
struct LinkDerivation {
  std::string source;
  std::vector<std::string> steps;
};

struct ChainLink {
  std::string hash, step, label, argument;
  LinkDerivation derivation;
  std::size_t tiles = 0;
  std::uint32_t colours = 0;
  TileKind kind = TileKind::Wang;
};

struct EnumerateResult {
  bool complete = false;     // no set left to expand
  bool interrupted = false;  // a signal stopped it after its checkpoint
  bool timed_out = false;
  int signal = 0;
  bool resumed = false;
  std::size_t batches = 0, expanded = 0, checkpoints = 0;
  std::map<std::string, EnumNode> nodes;             // by hash
  std::map<std::pair<std::string, std::string>, EnumEdge> edges;  // by (from, step)
  std::map<std::string, std::size_t> over_limit;     // results over max_tiles, by operation
  std::string digest;  // FNV-1a 64 over the sorted sets and edges: equal runs, equal digests
  double seconds = 0, total_seconds = 0;
};

// The published Wang sets whose aperiodicity is proved (jeandel-rao-11 is Fig. 4 of Jeandel and Rao,
// jeandel-rao-11-variant-2 their Fig. 3; variant 3, Fig. 10, is not among them: tilesets/data/README.md).
const std::vector<std::string>& published_enumeration_sources();

EnumerateResult enumerate_conversions(const EnumerateOptions& options);

// The sound chain to `hash` the search recorded (parent links), source first.
std::vector<ChainLink> recorded_chain(const EnumerateResult& r, const std::string& hash);

// Applies steps one by one from a built-in source, each to the canonical form of the last result
// (aperiodic link). InputError for an unknown source or step, or a step that does not apply.
// With a deadline, the replay stops when it passes (checked between steps and inside the
// canonical forms, whose refinement of a set of thousands of tiles takes minutes): the links
// re-derived so far are returned and *timed_out is set (`last` is then the last one's set).
struct ReplayedLink {
  std::string step, label, argument, hash;
  std::size_t tiles = 0;
  std::uint32_t colours = 0;
  TileKind kind = TileKind::Wang;
};
std::vector<ReplayedLink> replay_chain(const std::string& source, const std::vector<std::string>& steps,
                                       TileSet* last = nullptr, const Deadline& deadline = {},
                                       bool* timed_out = nullptr);

}  // namespace tilekit
