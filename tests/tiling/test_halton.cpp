#include <gtest/gtest.h>

#include <set>

#include "base/error.hpp"
#include "tiling/halton_tiling.hpp"
#include "tiling/neighbour_statistics.hpp"
#include "base/random.hpp"

using namespace tilekit;

TEST(Halton, FirstTenCellsOfThe8x9GridMatchThePaper) {
  // Schloemer & Deussen 2010, Fig. 2: the first 72 scaled points induce an 8 x 9 grid
  const std::pair<std::uint64_t, std::uint64_t> expected[] = {{0, 0}, {4, 3}, {2, 6}, {6, 1}, {1, 4},
                                                              {5, 7}, {3, 2}, {7, 5}, {0, 8}, {4, 0}};
  const HaltonColouring h(2, 8, 9);
  EXPECT_EQ(h.p1(), 8u);
  EXPECT_EQ(h.p2(), 9u);
  for (std::uint64_t i = 0; i < 10; ++i) {
    EXPECT_EQ(HaltonColouring::cell_of_point(i, 3, 2), expected[i]) << i;
    EXPECT_EQ(h.index(std::int64_t(expected[i].first), std::int64_t(expected[i].second)), i);  // eq. (6)
  }
}

TEST(Halton, Eq6InvertsTheForwardEnumerationOnEveryCellOfThe8x9Grid) {
  const HaltonColouring h(2, 8, 9);
  std::set<std::uint64_t> seen;
  for (std::uint64_t i = 0; i < 72; ++i) {
    auto [x, y] = HaltonColouring::cell_of_point(i, 3, 2);
    EXPECT_EQ(h.index(std::int64_t(x), std::int64_t(y)), i);
    seen.insert(i);
  }
  EXPECT_EQ(seen.size(), 72u);
  // eq. (4), C = 2: the first 36 cells get colour 0, the other 36 colour 1
  int zeros = 0;
  for (int x = 0; x < 8; ++x)
    for (int y = 0; y < 9; ++y) {
      EXPECT_EQ(h.colour(x, y), h.index(x, y) < 36 ? 0u : 1u);
      zeros += h.colour(x, y) == 0;
    }
  EXPECT_EQ(zeros, 36);
}

TEST(Halton, SixtyFourBitArithmeticWorksFarBeyondThePapers46000Limit) {
  // a 10^6 x 10^6 tiling: p1 = 2^20, p2 = 3^13, p1 p2 > 2^40 -- eq. (5) would overflow 32 bits
  const HaltonColouring h(5, 1000001, 1000001);
  EXPECT_EQ(h.p1(), 1u << 20);
  EXPECT_EQ(h.p2(), 1594323u);
  SplitMix64 rng(3);
  for (int k = 0; k < 20000; ++k) {
    const std::int64_t x = std::int64_t(rng.below(h.p1())), y = std::int64_t(rng.below(h.p2()));
    const std::uint64_t i = h.index(x, y);
    ASSERT_LT(i, h.p1() * h.p2());
    auto [fx, fy] = HaltonColouring::cell_of_point(i, h.n1(), h.n2());
    ASSERT_EQ(fx, std::uint64_t(x));
    ASSERT_EQ(fy, std::uint64_t(y));
    ASSERT_EQ(h.colour(x, y), std::uint32_t((unsigned __int128)i * 5 / (h.p1() * h.p2())));  // eq. (4)
  }
  // the largest lattice: 2^31 x 2^31 points
  const HaltonColouring big(8, 1ull << 31, 1ull << 31);
  const std::int64_t x = (1ll << 31) - 1, y = 1234567891;
  auto [fx, fy] = HaltonColouring::cell_of_point(big.index(x, y), big.n1(), big.n2());
  EXPECT_EQ(fx, std::uint64_t(x));
  EXPECT_EQ(fy, std::uint64_t(y));
}

TEST(Halton, ExponentsAreTheSmallestThatCoverTheLattice) {
  const HaltonColouring h(3, 4097, 4097);  // a 4096 x 4096 tiling
  EXPECT_EQ(h.n1(), 13);                   // 2^12 = 4096 < 4097 <= 8192
  EXPECT_EQ(h.n2(), 8);                    // 3^7 = 2187 < 4097 <= 6561
  EXPECT_THROW(HaltonColouring(3, 0, 5), InputError);
  EXPECT_THROW(HaltonColouring(0, 5, 5), InputError);
}

TEST(Halton, Table1IsReproducedWithin002ForTwoToEightColours) {
  // The paper's protocol (100 tilings, resolutions uniform up to 4096 x 4096, all corners
  // pooled) estimated from 300,000 corners drawn uniformly from those tilings; the full count
  // is `tilekit analyze neighbors --algo halton` (BENCHMARKS.md, within 0.005).
  for (std::uint32_t c = 2; c <= 8; ++c) {
    const NeighbourAnalysis r =
        analyze_neighbours(c, NeighbourAlgo::Halton, 100, 4096, 1, HashKind::LongPeriod, {}, 300000);
    const PaperTable1Row paper = *paper_table1(c);
    EXPECT_NEAR(r.stats.mean(), paper.halton_mean, 0.02) << c;
    EXPECT_NEAR(r.stats.deviation(), paper.halton_deviation, 0.02) << c;
    // and it is clearly better than the stochastic method
    EXPECT_LT(r.stats.mean(), 8.0 / c - 0.3) << c;
  }
}
