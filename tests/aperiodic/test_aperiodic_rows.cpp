#include <gtest/gtest.h>

#include "aperiodic/rows.hpp"
#include "tilesets/tile_set_io.hpp"

using namespace tilekit;

namespace {
// Six tiles that tile only with period 2 (rows) x 3 (columns): tile (i,j) knows its position.
std::vector<WangTile> periodic_2x3() {
  std::vector<WangTile> w;
  for (Colour i = 0; i < 2; ++i)
    for (Colour j = 0; j < 3; ++j) w.push_back({i * 3 + j, i * 3 + (j + 1) % 3, ((i + 1) % 2) * 3 + j, i * 3 + j});
  return w;
}
}  // namespace

TEST(PeriodicRows, Culik13HasNoStackOfPeriodicRowsUpToEight) {
  auto w = resolve_tile_set("culik-13").wang_tiles();
  for (int q = 1; q <= 8; ++q) {
    PeriodicRows r = periodic_rows(w, q, true);
    EXPECT_TRUE(r.enumerated);
    EXPECT_EQ(r.recurrent, 0u) << "q = " << q;
  }
  EXPECT_GT(periodic_rows(w, 8, true).rows, 100u);  // many periodic rows, none stacks forever
}

TEST(PeriodicRows, APeriodicSetKeepsItsPeriodsAndLosesTheOthers) {
  auto w = periodic_2x3();
  EXPECT_EQ(periodic_rows(w, 1, true).recurrent, 0u);
  EXPECT_EQ(periodic_rows(w, 2, true).recurrent, 0u);
  EXPECT_GT(periodic_rows(w, 3, true).recurrent, 0u);
  EXPECT_GT(periodic_rows(w, 6, true).recurrent, 0u);
  EXPECT_EQ(periodic_rows(w, 3, false).recurrent, 0u);  // columns: vertical period 2 only
  EXPECT_GT(periodic_rows(w, 2, false).recurrent, 0u);
}

TEST(PeriodicRows, GivesUpBeyondTheRowLimit) {
  auto w = resolve_tile_set("complete-wang-2").wang_tiles();
  PeriodicRows r = periodic_rows(w, 8, true, 100);
  EXPECT_FALSE(r.enumerated);
}
