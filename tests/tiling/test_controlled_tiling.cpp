#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <set>

#include "tiling/controlled_tiling.hpp"
#include "base/error.hpp"
#include "base/random.hpp"
#include "tilesets/tile_set_reduction.hpp"
#include "tilesets/validator.hpp"

using namespace tilekit;

TEST(AliasTable, RealisesTheDistributionExactlyOverAFineGridOfUniforms) {
  const double p[] = {0.5, 0.0, 0.125, 0.3, 0.075};
  const AliasTable t(p, 5);
  std::vector<double> freq(5, 0);
  const int n = 1000000;
  for (int k = 0; k < n; ++k) ++freq[t.sample((k + 0.5) / n)];
  for (int c = 0; c < 5; ++c) EXPECT_NEAR(freq[std::size_t(c)] / n, p[c], 1e-5) << c;
  EXPECT_EQ(freq[1], 0);  // a colour without mass never appears
}

TEST(AliasTable, DegenerateDistributionsAlwaysGiveTheirColour) {
  const double one[] = {0, 0, 1, 0};
  const AliasTable t(one, 4);
  for (double u : {0.0, 0.1, 0.49, 0.5, 0.74, 0.99, 0.999999}) EXPECT_EQ(t.sample(u), 2u);
}

TEST(PositionRandom, IsUniformAndPerPosition) {
  for (HashKind kind : {HashKind::LongPeriod, HashKind::Permutation}) {
    const PositionRandom r(kind, 5);
    std::vector<int> bins(10, 0);
    for (int x = 0; x < 200; ++x)
      for (int y = 0; y < 200; ++y) {
        const double u = r(x, y);
        ASSERT_GE(u, 0.0);
        ASSERT_LT(u, 1.0);
        ASSERT_EQ(u, r(x, y));
        ++bins[std::size_t(u * 10)];
      }
    for (int b : bins) EXPECT_NEAR(b / 40000.0, 0.1, 0.01) << hash_kind_name(kind);
  }
}

TEST(PositionRandom, DigitsAreTheThreeDimensionalHashOfEq37) {
  const PositionRandom r(HashKind::LongPeriod, 9);
  const LongPeriodHash h = LongPeriodHash::thesis_tiling_hash(derive_seed(9, 12));
  EXPECT_EQ(r.digits(), 7);  // 24^7 >= 2^32 > 24^6
  for (std::int64_t x : {-7ll, 0ll, 3ll, 1ll << 40})
    for (std::int64_t y : {-1ll, 0ll, 12345ll}) {
      double u = 0, scale = 1.0 / 24;
      for (int k = 0; k < 7; ++k, scale /= 24) u += h(x, y, k) * scale;
      EXPECT_DOUBLE_EQ(r(x, y), u);
    }
  const PositionRandom p(HashKind::Permutation, 9);
  const PermutationHash t(256, derive_seed(9, 11));
  EXPECT_EQ(p.digits(), 4);
  double u = 0, scale = 1.0 / 256;
  for (int k = 0; k < 4; ++k, scale /= 256) u += t(5, 6, k) * scale;
  EXPECT_DOUBLE_EQ(p(5, 6), u);
}

TEST(ControlledTiling, ColourFrequenciesFollowTheMap) {
  // two halves: left pixel (0.7, 0.2, 0.1), right pixel (0, 0, 1)
  ProbabilityMap m{3, 1, 2, {0.7, 0.2, 0.1, 0.0, 0.0, 1.0}};
  const ControlledColouring h(m, 300, 301, HashKind::LongPeriod, 1);
  std::vector<double> left(3, 0);
  double n = 0;
  for (int y = 0; y <= 300; ++y)
    for (int x = 0; x <= 301; ++x) {
      if (h.pixel_of(x, y).second == 0) {
        ++left[h.colour(x, y)];
        ++n;
      } else {
        ASSERT_EQ(h.colour(x, y), 2u);
      }
    }
  EXPECT_NEAR(left[0] / n, 0.7, 0.01);
  EXPECT_NEAR(left[1] / n, 0.2, 0.01);
  EXPECT_NEAR(left[2] / n, 0.1, 0.01);
}

TEST(ControlledTiling, LatticePointsMapToTheNearestPixelOfRhoXOverTx) {
  ProbabilityMap m = ProbabilityMap::ramp(2, 3, 5);
  const ControlledColouring h(m, 10, 8, HashKind::LongPeriod, 1);
  EXPECT_EQ(h.pixel_of(0, 0), std::make_pair(0, 0));
  EXPECT_EQ(h.pixel_of(8, 10), std::make_pair(2, 4));   // (1, 1) -> last pixel
  EXPECT_EQ(h.pixel_of(4, 5), std::make_pair(1, 2));    // (1/2, 1/2) -> middle pixel
  EXPECT_EQ(h.pixel_of(-3, 99), std::make_pair(2, 0));  // clamped outside the tiling
}

TEST(ControlledTiling, TilesStayInsideTheReducedSetOfTheMap) {
  // a ramp through 5 colours: each lattice point mixes two neighbouring colours only
  const ProbabilityMap m = ProbabilityMap::ramp(5, 1, 9);
  const ControlledColouring h(m, 120, 120, HashKind::LongPeriod, 3);
  const auto compatible = h.compatible_pairs();
  const auto excluded = excluded_pairs(5, compatible);
  EXPECT_FALSE(excluded.empty());
  for (auto [a, b] : excluded) EXPECT_GE(b - a, 2u);  // neighbouring colours of the ramp do meet
  const TileSet reduced = reduced_corner_set(5, excluded);
  EXPECT_LT(reduced.size(), 625u);
  const Tiling t = controlled_corner_tiling(m, 120, 120, HashKind::LongPeriod, 3);
  const ValidationReport rep = validate(t, &reduced);
  EXPECT_TRUE(rep.valid) << (rep.errors.empty() ? "" : rep.errors[0]);
}

TEST(ProbabilityMap, MalformedMapsAreInputErrorsNamingTheProblem) {
  auto message = [](const std::string& text) {
    try {
      probability_map_from_json(nlohmann::json::parse(text), "map.json");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(R"({"colors":2,"rows":1,"cols":1,"p":[[[0.5,0.6]]]})"),
            "map.json: p[0][0]: probabilities sum to 1.1, not 1");
  EXPECT_EQ(message(R"({"colors":2,"rows":1,"cols":1,"p":[[[1.5,-0.5]]]})"),
            "map.json: p[0][0][0]: expected a number between 0 and 1, got 1.5");
  EXPECT_EQ(message(R"({"colors":2,"rows":1,"cols":2,"p":[[[1,0]]]})"), "map.json: p[0]: expected an array of 2 elements, got 1");
  EXPECT_EQ(message(R"({"colors":0,"rows":1,"cols":1,"p":[]})"),
            "map.json: colors: expected an integer between 1 and 255, got 0");
  EXPECT_EQ(message(R"([1,2])"), "map.json: expected a JSON object, got [1,2]");
  // a header promising 4096x4096x255 probabilities is refused by the rows it lacks, not by an allocation
  EXPECT_EQ(message(R"({"colors":255,"rows":4096,"cols":4096,"p":[]})"),
            "map.json: p: expected an array of 4096 elements, got 0");
  const ProbabilityMap ok = probability_map_from_json(
      nlohmann::json::parse(R"({"colors":2,"rows":1,"cols":1,"p":[[[0.25,0.75]]]})"), "ok.json");
  EXPECT_DOUBLE_EQ(ok.at(0, 0)[1], 0.75);
  EXPECT_EQ(probability_map_to_json(ok)["p"][0][0][1], 0.75);
}
