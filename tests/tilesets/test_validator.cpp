#include <gtest/gtest.h>

#include "tilesets/tile_set.hpp"
#include "tilesets/validator.hpp"

using namespace tilekit;

// The 4x4 corner packing from pegs: peg(r,c) for a binary de Bruijn torus (Fig. 5.x of
// the thesis is one of the 32); built here by brute force from a known peg pattern.
static Tiling corner_from_pegs(const std::vector<std::vector<Colour>>& peg, std::uint32_t c) {
  int n = int(peg.size());
  Tiling t(TileKind::Corner, c, n, n, true);
  for (int r = 0; r < n; ++r)
    for (int k = 0; k < n; ++k) {
      CornerTile ct{peg[r][(k + 1) % n], peg[(r + 1) % n][(k + 1) % n], peg[(r + 1) % n][k], peg[r][k]};
      t.at(r, k) = corner_index(ct, c);
    }
  return t;
}

TEST(Validator, AcceptsABinaryDeBruijnTorusAsCornerPacking) {
  // A (4,4;2,2)_2 de Bruijn torus: every 2x2 binary window once.
  std::vector<std::vector<Colour>> peg = {{0, 0, 0, 1}, {0, 0, 1, 0}, {1, 0, 1, 1}, {0, 1, 1, 1}};
  ValidationReport rep = validate(corner_from_pegs(peg, 2));
  EXPECT_TRUE(rep.valid);
  EXPECT_TRUE(rep.packing) << (rep.errors.empty() ? "" : rep.errors[0]);
}

TEST(Validator, RejectsMismatchedNeighbours) {
  Tiling t(TileKind::Wang, 2, 1, 2, false);
  t.at(0, 0) = wang_index({0, 1, 0, 0}, 2);  // E = 1
  t.at(0, 1) = wang_index({0, 0, 0, 0}, 2);  // W = 0
  ValidationReport rep = validate(t);
  EXPECT_FALSE(rep.valid);
  ASSERT_FALSE(rep.errors.empty());
  EXPECT_EQ(rep.errors[0], "cells (0,0) and (0,1) do not match horizontally");
}

TEST(Validator, TorusWrapAroundIsChecked) {
  Tiling t(TileKind::Wang, 2, 1, 2, false);
  t.at(0, 0) = wang_index({0, 1, 0, 0}, 2);
  t.at(0, 1) = wang_index({0, 1, 0, 1}, 2);
  EXPECT_TRUE(validate(t).valid);
  t.torus = true;  // now W of (0,0) = 0 must equal E of (0,1) = 1, and N/S wrap too
  EXPECT_FALSE(validate(t).valid);
}

TEST(Validator, RepeatedTileIsNotAPacking) {
  Tiling t(TileKind::Corner, 2, 4, 4, true);  // all-zero tiles: valid tiling, not a packing
  ValidationReport rep = validate(t);
  EXPECT_TRUE(rep.valid);
  EXPECT_FALSE(rep.packing);
}

TEST(Validator, TileOutsideTheSetIsReported) {
  TileSet s = TileSet::wang({{0, 0, 0, 0}}, "zero");
  Tiling t(TileKind::Wang, 2, 1, 1, true);
  t.at(0, 0) = wang_index({1, 1, 1, 1}, 2);
  ValidationReport rep = validate(t, &s);
  EXPECT_FALSE(rep.valid);
  EXPECT_EQ(rep.errors[0], "cell (0,0): tile 15 is not in tile set 'zero'");
}
