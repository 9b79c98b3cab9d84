#pragma once
// Pruning tiles that no tiling of the plane needs (`tilekit aperiodic ... --prune R`).
//
// Two filters, repeated until nothing changes:
//  - surround: a tile survives a round when it is the centre of a 3x3 patch of surviving
//    tiles; R rounds keep every tile that can be surrounded to radius R (a necessary
//    condition, exact for R = 1). A tile of a tiling of the plane is surrounded to every
//    radius, so this filter keeps every tiling of the plane.
//  - transducer SCC: a row of a tiling is a bi-infinite path in the row transducer graph
//    (states = E/W colours, one edge per tile; Kari/Culik); a tile whose edge lies in no
//    strongly connected component (Boost.Graph strong_components) can occur at most once
//    per row. The same with columns. This filter can remove tilings, but it keeps
//    tileability and aperiodicity exactly:
//      * a doubly periodic tiling has periodic rows and columns, i.e. cycles, so it uses
//        only SCC tiles: the pruned set tiles periodically iff the original does;
//      * a tiling uses at most K non-SCC tiles per row (K = their number), so a 2N x 2N
//        square holds at most 2NK of them and, for large N, contains an m x m square free
//        of them; by compactness the pruned set tiles the plane iff the original does.
// Corner sets are pruned through their equivalent Wang set (thesis 2.9), tile for tile.
#include <cstddef>
#include <functional>
#include <vector>

#include "aperiodic/convert.hpp"
#include "tilesets/tile_set.hpp"

namespace tilekit {

struct PruneReport {
  std::size_t before = 0, after = 0;
  std::size_t removed_by_surround = 0, removed_by_scc = 0;
  int passes = 0;
  std::vector<std::size_t> kept;  // positions (in the source) of the surviving tiles
};

// Tiles of `tiles` that are the centre of some 3x3 patch of `tiles` (positions).
std::vector<std::size_t> surroundable(const std::vector<WangTile>& tiles);
// ... of some (2R+1) x (2R+1) patch (R = patch_radius; a backtracking search per tile).
std::vector<std::size_t> surroundable(const std::vector<WangTile>& tiles, int patch_radius);
// Tiles whose edge lies in a strongly connected component of the row transducer graph
// (rows = true) or of the column transducer graph (rows = false).
std::vector<std::size_t> in_transducer_scc(const std::vector<WangTile>& tiles, bool rows);

// The label of a pruned conversion result: surround pruning keeps every tiling, so a
// conjugacy stays one; SCC pruning may drop tilings (never tileability or periodic ones),
// so a conjugate result becomes `lifts` (its tilings still lift to the source).
Soundness after_pruning(Soundness s, const PruneReport& r);

// patch_radius > 1: once the 3x3 rounds change nothing, tiles that are the centre of no
// (2 patch_radius + 1)-square patch of survivors go too, and everything repeats to a fixed point
// (the 92-tile set of the 25-set's chain loses 3 tiles at patch radius 2).
PruneReport prune_wang(const std::vector<WangTile>& tiles, int radius, int patch_radius = 1);

// Strip pruning (aperiodic/strip_prune.cpp), the transducer-SCC filter for strips of k rows: a
// tile survives when it lies in the top row (bottom row, leftmost or rightmost column) of a
// periodic strip of k rows (columns), i.e. on a cycle of T_{k-1} composed with the row transducer
// (aperiodic/chain.hpp). A periodic tiling is made of periodic strips, so it keeps every periodic
// tiling; and a strip of an arbitrary tiling is a path that leaves a strongly connected component
// of that product at most c - 1 times (c components), so each row holds at most c - 1 removed
// tiles and the compactness argument above keeps tileability. k = 1 is the SCC filter. Levels are
// built while their product has at most max_transitions transitions.
std::vector<std::size_t> in_periodic_strips(const std::vector<WangTile>& tiles, int k, bool columns, bool top,
                                            std::size_t max_transitions = 2000000);
// Repeats the strip filter for k = 1..max_k in all four directions until nothing changes.
PruneReport prune_strips_wang(const std::vector<WangTile>& tiles, int max_k, std::size_t max_transitions = 2000000);
TileSet prune_strips(const TileSet& set, int max_k, PruneReport* report = nullptr);
// Prunes a Wang or corner set; the result keeps the surviving tiles in their order.
TileSet prune(const TileSet& set, int radius, PruneReport* report = nullptr, int patch_radius = 1);
// Prunes a Wang set with `prune_wang_tiles`, a corner set through its equivalent Wang set (thesis
// 2.9: the same tilings, tile for tile); the result keeps the surviving tiles in their order.
TileSet prune_via_wang(const TileSet& set,
                       const std::function<PruneReport(const std::vector<WangTile>&)>& prune_wang_tiles,
                       PruneReport* report);

}  // namespace tilekit
