#pragma once
// The steps of the search over conversions (aperiodic/enumerate.hpp): each maps a tile set to
// another and carries a label saying what it keeps.
//   conjugate   the tilings of both sets are in bijection by a local map that commutes with
//               translations (aperiodic/convert.hpp); aperiodicity is kept both ways;
//   lifts       every tiling of the result lifts to one of the source and a periodic one to a
//               periodic one, and the source's tilings map onto the result's: aperiodicity kept;
//   prune       tiles that no periodic tiling uses removed, keeping tileability (aperiodic/prune.hpp);
//   unverified  none of these is known (a translation whose rows do not all lift).
// A chain of steps labelled published, conjugate, lifts or prune from a published aperiodic set
// proves its last set aperiodic.
//
// A step is written "[SYMMETRY:]OPERATION": the operation applied to the set's image under the
// symmetry (aperiodic/canonical.hpp), e.g. "rot90:horizontal". Operations:
//   diagonal, horizontal, rotation, subdivision, subdivision+merge-centres (Wang -> corner,
//   thesis 8.3; `horizontal` of a set turned a quarter is the thesis' vertical translation),
//   horizontal+prune (the translation pruned, labelled by the lift check of the pruned rows),
//   to-wang (corner -> Wang, thesis 8.4), fuse (Wang: horizontal dominoes as tiles),
//   blocks (Wang -> corner: the Wang tiles as pegs, the matching 2x2 blocks as corner tiles),
//   prune (surround radius 3 and transducer SCCs), prune-strips (aperiodic/prune.hpp, k <= 3),
//   merge-colours and merge-colours-lifts (corner: the least set reached by colour merges checked
//   by a recovery map of radius 1 on patches with a margin of at most 1, aperiodic/colour_merge.hpp;
//   the first keeps only merges that prove a conjugacy, the second also those whose tilings only lift).
#include <optional>
#include <string>
#include <vector>

#include "tilesets/tile_set.hpp"

namespace tilekit {

struct StepResult {
  TileSet set;
  std::string label;     // conjugate, lifts, prune or unverified
  std::string argument;  // one line: why this label
};

// Every operation name, in the order the search tries them by default.
const std::vector<std::string>& step_operations();
// The stronger operations (issue 40), tried when a search names them (`enumerate --operations`)
// and by `aperiodic link`: prune5 and horizontal+prune5 prune to a fixed point with 5x5 patches
// too (prune_wang's patch radius 2); merge-colours2 checks each merge up to recovery radius 2.
const std::vector<std::string>& stronger_step_operations();
// step_operations() then stronger_step_operations(): every name apply_step knows.
const std::vector<std::string>& all_step_operations();

// The symmetries worth applying before an operation: the operations that commute with every
// symmetry of the square (diagonal, rotation, subdivision, to-wang, the prunes) need only the
// identity, since canonical forms are taken up to symmetry anyway; horizontal translation and
// fusion commute with the mirrors and the half turn, so the identity and a quarter turn cover
// all; subdivision+merge-centres merges greedily in tile order, so all eight are tried.
std::vector<std::string> symmetries_for(const std::string& operation);

// Applies "[SYMMETRY:]OPERATION". nullopt when the operation does not apply (wrong kind, a prune
// that removes nothing, a result over the tile-index limits). InputError for an unknown step.
std::optional<StepResult> apply_step(const TileSet& set, const std::string& step);

// Is a chain with this label still a proof of aperiodicity?
bool sound_label(const std::string& label);

}  // namespace tilekit
