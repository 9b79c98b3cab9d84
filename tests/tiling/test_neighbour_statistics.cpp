#include <gtest/gtest.h>

#include <cmath>

#include "base/error.hpp"
#include "tiling/neighbour_statistics.hpp"

using namespace tilekit;

TEST(NeighbourStatistics, CountsInLatticeNeighboursOnly) {
  // 3 x 3 lattice, all one colour: corners have 3 neighbours, edges 5, the centre 8
  std::vector<std::uint16_t> same(9, 1);
  NeighbourStatistics s;
  count_identical_neighbours(same.data(), 3, 3, s);
  EXPECT_EQ(s.corners, 9u);
  EXPECT_EQ(s.sum, 4u * 3 + 4u * 5 + 8u);
  EXPECT_EQ(s.interior_histogram[8], 1u);
  // a checkerboard: only the diagonal neighbours match
  std::vector<std::uint16_t> board = {0, 1, 0, 1, 0, 1, 0, 1, 0};
  NeighbourStatistics b;
  count_identical_neighbours(board.data(), 3, 3, b);
  EXPECT_EQ(b.sum, 4u * 1 + 4u * 2 + 4u);
  EXPECT_EQ(b.interior_histogram[4], 1u);
}

TEST(StochasticBaseline, InteriorCountsFollowBinomialEightOneOverC) {
  for (std::uint32_t c : {2u, 3u, 4u, 5u, 8u}) {
    // The paper's stochastic baseline is the long-period hash [LD06b]. (A single permutation
    // table is not i.i.d.: down a column it lists distinct table entries, and its mean falls
    // measurably below 8/C -- see PermutationHashIsMeasurablyBelowTheBinomialMean.)
    for (HashKind hash : {HashKind::LongPeriod}) {
      const NeighbourAnalysis r = analyze_neighbours(c, NeighbourAlgo::Direct, 3, 1200, c, hash);
      const auto& hist = r.stats.interior_histogram;
      double n = 0;
      for (auto v : hist) n += double(v);
      ASSERT_GT(n, 1e5);
      // chi-square against Binomial(8, 1/C) over the 9 outcomes (cells with expectation >= 5)
      const double p = 1.0 / c;
      double chi2 = 0;
      int dof = -1;
      for (int k = 0; k <= 8; ++k) {
        const double expect =
            n * std::tgamma(9) / (std::tgamma(k + 1) * std::tgamma(9 - k)) * std::pow(p, k) * std::pow(1 - p, 8 - k);
        if (expect < 5) continue;
        chi2 += (hist[std::size_t(k)] - expect) * (hist[std::size_t(k)] - expect) / expect;
        ++dof;
      }
      // the 0.999 quantile of chi-square with <= 8 degrees of freedom is below 26.2
      EXPECT_LT(chi2, 26.2) << "C=" << c << " " << hash_kind_name(hash) << " dof " << dof;
      EXPECT_NEAR(r.stats.mean(), 8.0 * p, 0.02) << c;
      EXPECT_NEAR(r.stats.deviation(), std::sqrt(8 * p * (1 - p)), 0.02) << c;
    }
  }
}

TEST(StochasticBaseline, PermutationHashIsMeasurablyBelowTheBinomialMean) {
  // 24 tilings below one period (258 for C = 3), fresh tables each: the short-period hash has
  // fewer identical neighbours than i.i.d. colours would give.
  const NeighbourAnalysis r = analyze_neighbours(3, NeighbourAlgo::Direct, 24, 250, 3, HashKind::Permutation);
  EXPECT_LT(r.stats.mean(), 8.0 / 3 - 0.02);
  EXPECT_GT(r.stats.mean(), 8.0 / 3 - 0.2);
}

TEST(StochasticBaseline, PaperStochasticColumnIsBinomial) {
  // Table 1's stochastic column agrees with Binomial(8, 1/C) to within 0.01
  for (std::uint32_t c = 2; c <= 8; ++c) {
    const PaperTable1Row row = *paper_table1(c);
    EXPECT_NEAR(row.stochastic_mean, 8.0 / c, 0.01);
    EXPECT_NEAR(row.stochastic_deviation, std::sqrt(8.0 / c * (1 - 1.0 / c)), 0.01);
  }
  EXPECT_FALSE(paper_table1(9).has_value());
}

TEST(NeighbourAnalysis, SampledEstimateAgreesWithTheFullCount) {
  const NeighbourAnalysis full = analyze_neighbours(4, NeighbourAlgo::Halton, 6, 600, 3, HashKind::LongPeriod);
  const NeighbourAnalysis sampled =
      analyze_neighbours(4, NeighbourAlgo::Halton, 6, 600, 3, HashKind::LongPeriod, {}, 200000);
  EXPECT_EQ(sampled.stats.corners, 200000u);
  EXPECT_NEAR(sampled.stats.mean(), full.stats.mean(), 0.01);
  EXPECT_NEAR(sampled.stats.deviation(), full.stats.deviation(), 0.01);
}

TEST(NeighbourAnalysis, BadParametersAreInputErrors) {
  EXPECT_THROW(analyze_neighbours(0, NeighbourAlgo::Halton, 1, 10, 1, HashKind::LongPeriod), InputError);
  EXPECT_THROW(analyze_neighbours(3, NeighbourAlgo::Halton, 0, 10, 1, HashKind::LongPeriod), InputError);
  EXPECT_THROW(analyze_neighbours(3, NeighbourAlgo::Halton, 1, 0, 1, HashKind::LongPeriod), InputError);
  EXPECT_THROW(parse_neighbour_algo("scanline"), InputError);
}
