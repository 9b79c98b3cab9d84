#pragma once
// When is a translation construction (thesis 8.3.2) sound? Horizontal translation keeps
// only the N/S colours of each Wang tile: a row of Wang tiles is a path in the row
// transducer graph (states = E/W colours, one edge w -> e per tile, labelled (n, s)), and
// the corner tiling keeps only the labels, constrained pairwise by the corner tiles.
// Rows are independent (the N/S pegs are shared between rows), so two 1-D questions decide
// the construction for tilings of the plane:
//   lifts:     every bi-infinite label sequence allowed pairwise (the corner set's rows)
//              is the label of a bi-infinite path (a subset construction over the labels);
//   injective: no two different bi-infinite paths carry the same labels (the label
//              product graph has no bi-infinite path through an off-diagonal edge).
// Vertical translation is the same with rows and columns exchanged.
#include <cstddef>
#include <string>
#include <vector>

#include "tilesets/tile.hpp"

namespace tilekit {

struct LiftReport {
  bool decided = true;   // false when the subset construction hit its state limit
  bool lifts = false;    // every tiling of the corner set lifts to a Wang tiling
  bool injective = false;
  std::size_t states = 0;  // subset states explored
  std::string detail;      // one line for the user
};

// horizontal = true: horizontal translation (rows, labels (n,s)); false: vertical
// translation (columns, labels (w,e)).
LiftReport translation_lift(const std::vector<WangTile>& tiles, bool horizontal, std::size_t max_states = 200000);

// The same check for a subset of the corner set (e.g. after pruning, which keeps the
// aperiodicity of the corner set): `corner` holds corner tiles in the Wang set's own
// colours, nw/ne/sw/se = (a.n, b.n, a.s, b.s) (horizontal) or (a.w, a.e, c.w, c.e)
// (vertical). Rows of such corner tilings are checked to lift, as above.
LiftReport translation_lift(const std::vector<WangTile>& tiles, bool horizontal,
                            const std::vector<CornerTile>& corner, std::size_t max_states = 200000);

}  // namespace tilekit
