#include <gtest/gtest.h>

#include "aperiodic/convert.hpp"
#include "aperiodic/prune.hpp"
#include "base/error.hpp"
#include "tilesets/tile_set_io.hpp"

using namespace tilekit;

TEST(Pruning, RemovesATileThatCannotBeSurrounded) {
  // The blank tile tiles the plane; T needs a north neighbour with s = 1, which no tile has.
  std::vector<WangTile> w = {{0, 0, 0, 0}, {1, 0, 0, 0}};
  EXPECT_EQ(surroundable(w), (std::vector<std::size_t>{0}));
  PruneReport r = prune_wang(w, 1);
  EXPECT_EQ(r.before, 2u);
  EXPECT_EQ(r.after, 1u);
  EXPECT_EQ(r.removed_by_surround, 1u);
}

TEST(Pruning, RemovesATransientTransducerEdgeThatSurroundingKeeps) {
  // Rows: loop at state 0, loop at state 1, and t: 0 -> 1 (n=1, s=0). t can be surrounded
  // (a staircase tiling uses it once per row) but lies in no strongly connected component.
  std::vector<WangTile> w = {{0, 0, 0, 0}, {1, 1, 1, 1}, {1, 1, 0, 0}};
  EXPECT_EQ(surroundable(w).size(), 3u);
  EXPECT_EQ(in_transducer_scc(w, true), (std::vector<std::size_t>{0, 1}));
  PruneReport r = prune_wang(w, 2);
  EXPECT_EQ(r.after, 2u);
  EXPECT_EQ(r.removed_by_scc, 1u);
  EXPECT_EQ(r.removed_by_surround, 0u);
}

TEST(Pruning, KeepsEveryTileOfThePublishedAperiodicSets) {
  // Each tile of a minimal aperiodic set occurs in its tilings.
  for (const char* name : {"culik-13", "kari-14", "ammann-gs-16", "jeandel-rao-11"}) {
    PruneReport r;
    TileSet s = prune(resolve_tile_set(name), 3, &r);
    EXPECT_EQ(r.after, r.before) << name;
  }
}

TEST(Pruning, ShrinksTheDiagonalCornerSetsAndIsIdempotent) {
  TileSet src = resolve_tile_set("ammann-gs-16");
  Conversion c = diagonal_translation(src.wang_tiles());
  TileSet corner = conversion_tile_set(c, "d", "");
  PruneReport r;
  TileSet p = prune(corner, 2, &r);
  EXPECT_EQ(r.before, 87u);
  EXPECT_LT(r.after, 87u);
  PruneReport again;
  prune(p, 2, &again);
  EXPECT_EQ(again.after, again.before);
}

TEST(Pruning, RejectsANegativeRadius) { EXPECT_THROW(prune_wang({{0, 0, 0, 0}}, -1), InputError); }
