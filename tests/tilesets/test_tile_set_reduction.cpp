#include <gtest/gtest.h>

#include <cmath>

#include "base/error.hpp"
#include "tilesets/tile_set_reduction.hpp"

using namespace tilekit;

TEST(Reduction, NkMatchesClosedFormInclusionExclusionAndBruteForceForEveryEntryOfTable2) {
  // Schloemer & Deussen 2010, Table 2: savings 1 - N_k / C^4 for k disjoint excluded pairs
  struct Entry {
    int k, c;
    double percent;
  };
  const Entry table2[] = {{1, 2, 87.5}, {1, 3, 61.7}, {1, 4, 43.0}, {1, 5, 31.0}, {1, 6, 23.3},
                          {1, 7, 18.1}, {1, 8, 14.4}, {1, 9, 11.7}, {2, 4, 76.6}, {2, 5, 58.2},
                          {2, 6, 44.8}, {2, 7, 35.2}, {2, 8, 28.2}, {2, 9, 23.1}, {3, 6, 64.4},
                          {3, 7, 51.2}, {3, 8, 41.5}, {3, 9, 34.1}, {4, 8, 54.1}, {4, 9, 44.7}};
  for (const Entry& e : table2) {
    const std::int64_t closed = reduced_size_closed_form(e.c, e.k);
    EXPECT_EQ(reduced_size_inclusion_exclusion(e.c, e.k), closed) << e.c << "," << e.k;
    EXPECT_EQ(reduced_size_brute_force(std::uint32_t(e.c), std::uint32_t(e.k)), closed) << e.c << "," << e.k;
    const double total = std::pow(e.c, 4);
    EXPECT_DOUBLE_EQ(std::round(1000.0 * (1.0 - closed / total)) / 10.0, e.percent) << e.c << "," << e.k;
  }
}

TEST(Reduction, SinglePairSavingsQuotedInTheText) {
  // "reductions of 61.7%, 43.0%, 31.0% and 23.3% for ... 3, 4, 5, and 6" colours
  const double quoted[] = {61.7, 43.0, 31.0, 23.3};
  for (int c = 3; c <= 6; ++c)
    EXPECT_DOUBLE_EQ(std::round(1000.0 * (1.0 - reduced_size_closed_form(c, 1) / std::pow(c, 4))) / 10.0,
                     quoted[c - 3]);
}

TEST(Reduction, KZeroKeepsTheCompleteSetAndKOutOfRangeIsAnInputError) {
  EXPECT_EQ(reduced_size_closed_form(5, 0), 625);
  EXPECT_EQ(reduced_size_inclusion_exclusion(5, 0), 625);
  EXPECT_EQ(reduced_size_brute_force(5, 0), 625);
  EXPECT_THROW(reduced_size_closed_form(5, 3), InputError);
  EXPECT_THROW(reduced_size_closed_form(0, 0), InputError);
  EXPECT_THROW(reduced_size_brute_force(3, 2), InputError);
}

TEST(Reduction, ReducedSetDropsExactlyTheTilesHoldingAnExcludedPair) {
  const TileSet s = reduced_corner_set(3, {{0, 2}});
  EXPECT_EQ(s.size(), std::size_t(reduced_size_closed_form(3, 1)));
  for (const CornerTile& t : s.corner_tiles()) {
    const bool has0 = t.ne == 0 || t.se == 0 || t.sw == 0 || t.nw == 0;
    const bool has2 = t.ne == 2 || t.se == 2 || t.sw == 2 || t.nw == 2;
    EXPECT_FALSE(has0 && has2);
  }
  EXPECT_EQ(excluded_pairs(3, {{0, 1}, {2, 1}}), (std::vector<ColourPair>{{0, 2}}));
}
