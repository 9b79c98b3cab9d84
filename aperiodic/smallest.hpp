#pragma once
// The smallest corner set that is *really* aperiodic: one whose aperiodicity follows from
// a chain of sound steps back to a published aperiodic Wang set. Steps: a ch. 8
// construction labelled `conjugate` or `lifts` (aperiodic/convert.hpp), then optionally
// pruning (aperiodic/prune.hpp: keeps every tiling, or at least tileability and every
// periodic tiling). Every candidate chain is tried; the least tile count wins (then the
// least colour count). The thesis claims 44 (Fig. 8.6); Nurmi (Bridges 2016) gives 30.
#include <string>
#include <vector>

#include "aperiodic/convert.hpp"
#include "tilesets/tile_set.hpp"

namespace tilekit {

struct ChainStep {
  std::string step;  // e.g. "labbe-19", "vertical translation (thesis 8.3.2)", "prune R=3"
  std::size_t tiles = 0;
  std::uint32_t colours = 0;
  std::string kind;      // "wang" or "corner"
  std::string label;     // "published", soundness name, "prune"
  std::string argument;  // why the step keeps aperiodicity
  std::string check;     // a command that re-checks this link (its label, its tile count)
};

// One aperiodic corner set a chain of conversions yields, with its provenance.
struct CornerSetCandidate {
  std::string source, method;
  int prune_radius = -1;  // -1: not pruned
  std::size_t tiles = 0;
  std::uint32_t colours = 0;
  Soundness soundness = Soundness::Unverified;
  std::vector<ChainStep> chain;
  TileSet set;
};

// Published aperiodic Wang sets the chains start from (built-in names).
const std::vector<std::string>& published_aperiodic_sets();

// Every chain source -> method [-> prune R], sorted by (tiles, colours); sound ones first.
std::vector<CornerSetCandidate> aperiodic_corner_candidates(int prune_radius = 3);

// The least sound candidate (InputError if none, which cannot happen with the built-ins).
CornerSetCandidate smallest_aperiodic_corner_set(int prune_radius = 3);

}  // namespace tilekit
