// Poisson disk tile sets: construction facts (N points per tile, the radius inside and across
// tiles by an exhaustive neighbour check), the three methods, and the file format.
#include <gtest/gtest.h>

#include <cmath>

#include "base/error.hpp"
#include "points/poisson_tiles.hpp"
#include "points/sampler.hpp"
#include "points/tile_parts.hpp"
#include "points/tile_set_file.hpp"
#include "tests/build_paths.hpp"

using namespace tilekit;
using namespace tilekit::points;

namespace {

// Brute force over all pairs on a torus w x h.
double torus_min_distance(const std::vector<Point2>& p, double w, double h) {
  double best = 1e300;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double dx = wrap_centred(p[i].x - p[j].x, w), dy = wrap_centred(p[i].y - p[j].y, h);
      best = std::min(best, std::sqrt(dx * dx + dy * dy));
    }
  return best;
}

// C = 1, E = 2: 16 tiles, each lattice edge one of two edge colours.
const PoissonTileSet& edged_set() {
  static const PoissonTileSet set = [] {
    PoissonTileParams p;
    p.colours = 1;
    p.edge_colours = 2;
    p.points = 32;
    p.seed = 3;
    p.threads = 2;
    return build_poisson_tiles(p);
  }();
  return set;
}

const PoissonTileSet& corner_set() {
  static const PoissonTileSet set = [] {
    PoissonTileParams p;
    p.colours = 3;
    p.points = 32;
    p.rho = 0.75;
    p.seed = 5;
    p.threads = 2;
    return build_poisson_tiles(p);
  }();
  return set;
}

}  // namespace

TEST(Sampler, TorusSetReachesTheRelativeRadiusAskedFor) {
  SamplingProblem p;
  p.torus = true;
  p.count = 100;
  SamplingOptions o;
  o.min_distance = 2 * 0.8 * max_poisson_radius(100);
  const auto r = sample_poisson_disk(p, o, 3);
  ASSERT_EQ(r.points.size(), 100u);
  EXPECT_GE(torus_min_distance(r.points, 1, 1), o.min_distance);
  EXPECT_EQ(r.lloyd_iterations, 0);
}

TEST(Sampler, FixedPointsAndFreeRegionAreRespected) {
  SamplingProblem p;
  p.fixed = {{0.5, 0.5}, {0.2, 0.8}};
  p.free = [](Point2 q) { return q.x < 0.7; };
  p.count = 20;
  SamplingOptions o;
  o.min_distance = 0.1;
  const auto r = sample_poisson_disk(p, o, 1);
  ASSERT_EQ(r.points.size(), 20u);
  auto all = r.points;
  all.insert(all.end(), p.fixed.begin(), p.fixed.end());
  EXPECT_GE(min_distance(all), 0.1);
  for (const auto& q : r.points) EXPECT_LT(q.x, 0.7);
}

TEST(Sampler, QuarterTurnSymmetryGivesSymmetricSets) {
  SamplingProblem p;
  p.count = 24;
  p.symmetry_order = 4;
  p.centre = {0.5, 0.5};
  SamplingOptions o;
  o.min_distance = 0.12;
  const auto r = sample_poisson_disk(p, o, 9);
  ASSERT_EQ(r.points.size(), 24u);
  for (const auto& q : r.points) {
    const Point2 t = rotate_quarter(q, 1, {0.5, 0.5});
    double best = 1;
    for (const auto& s : r.points) best = std::min(best, std::sqrt(squared_distance(s, t)));
    EXPECT_LT(best, 1e-12);
  }
}

// New points next to fixed ones from another sample: the fraction of the expected count that
// lands within `band` distances of the border between them, over `runs` samples of 1,024 points.
double border_density(int sweeps, int runs, double band) {
  const std::uint32_t n = 1024;
  SamplingOptions o;
  o.min_distance = 2 * 0.75 * max_poisson_radius(n);
  o.hard_disk_sweeps = sweeps;
  double found = 0, expected = 0;
  for (int i = 0; i < runs; ++i) {
    SamplingProblem whole;
    whole.torus = true;
    whole.count = n;
    SamplingProblem p;
    p.torus = true;
    for (const auto& q : sample_poisson_disk(whole, o, 100 + std::uint64_t(i)).points)
      if (q.x < 0.5) p.fixed.push_back(q);
    p.free = [](Point2 q) { return q.x >= 0.5; };
    p.count = n - p.fixed.size();
    for (const auto& q : sample_poisson_disk(p, o, 200 + std::uint64_t(i)).points)
      if (q.x < 0.5 + band * o.min_distance || q.x >= 1 - band * o.min_distance) ++found;
    expected += double(p.count) * 2 * band * o.min_distance / 0.5;
  }
  return found / expected;
}

TEST(Sampler, HardDiskSweepsFillTheBandThatDartsLeaveNextToFixedPoints) {
  // Darts alone leave the half-distance band along the fixed points about a fifth short (README,
  // "Why the tiles showed"); after the sweeps it holds its share.
  const double darts = border_density(0, 12, 0.5), swept = border_density(100, 12, 0.5);
  EXPECT_LT(darts, 0.9);
  EXPECT_GT(swept, 0.93);
}

TEST(Sampler, ImpossibleDensityIsABadInputError) {
  SamplingProblem p;
  p.torus = true;
  p.count = 50;
  SamplingOptions o;
  o.min_distance = 2 * 0.99 * max_poisson_radius(50);  // rho 0.99: hexagonal packing only
  o.tries = 2;
  o.repair = 10;
  EXPECT_THROW(sample_poisson_disk(p, o, 1), InputError);
}

TEST(CornerPoissonTiles, EveryTileHoldsNPointsAndTheRadiusHoldsAcrossEveryNeighbourPair) {
  const auto& set = corner_set();
  ASSERT_EQ(set.tiles.size(), 81u);  // the complete corner set over 3 colours
  for (const auto& t : set.tiles) ASSERT_EQ(t.size(), 32u);
  const auto check = check_poisson_tiles(set, 2);
  EXPECT_TRUE(check.exhaustive);
  EXPECT_EQ(check.points_off_count, 0u);
  EXPECT_GE(check.rho_within, 0.75);
  EXPECT_GE(check.rho_across, 0.75);
  EXPECT_EQ(check.pairs_checked, 2u * 729 + 2u * 2187);  // 2 L^6 + 2 L^7
}

TEST(CornerPoissonTiles, TilesSharingACornerColourShareTheCornerRegionPoints) {
  const auto& set = corner_set();
  const parts::Regions g(set.radius * (1 + kMargin));
  // Tiles 0 and 1 have different NW corners and the same NE, SE, SW corners (eq. 2.5).
  auto corner_pts = [&](std::size_t t) {
    std::vector<Point2> out;
    for (const auto& q : set.tiles[t])
      if (g.in_corner({q.x - 1, q.y - 1})) out.push_back(q);  // the SE corner region
    return out;
  };
  EXPECT_EQ(corner_pts(0), corner_pts(1));
  EXPECT_NE(corner_pts(0), corner_pts(9));  // tile 9: SE = 1 (((0 C + 1) C + 0) C + 0)
}

TEST(DualPoissonTiles, RotatedPartsFitTogetherAcrossEveryNeighbourPair) {
  PoissonTileParams p;
  p.method = PoissonTileMethod::Dual;
  p.colours = 1;
  p.points = 32;
  p.seed = 2;
  p.threads = 2;
  const auto set = build_poisson_tiles(p);
  EXPECT_EQ(set.tiles.size(), 256u);  // 4 states (orientations) per lattice point
  EXPECT_EQ(set.edge_regions, 10u);   // Li et al. Table I, C = 1: 10 edge tiles
  EXPECT_EQ(set.interiors, 70u);      // and 70 quad tiles
  const auto check = check_poisson_tiles(set, 2);
  EXPECT_EQ(check.points_off_count, 0u);
  EXPECT_GE(check.rho_across, 0.75);
}

TEST(WangPoissonTiles, OneColourSetKeepsTheRadiusInRandomTilings) {
  PoissonTileParams p;
  p.method = PoissonTileMethod::Wang;
  p.colours = 1;
  p.points = 32;
  const auto set = build_poisson_tiles(p);
  ASSERT_EQ(set.tiles.size(), 1u);
  const auto check = check_poisson_tiles(set, 1);
  EXPECT_FALSE(check.exhaustive);
  EXPECT_GE(check.rho_across, 0.75);
}

TEST(PoissonTileParams, TooFewPointsForTheRegionsIsRejected) {
  PoissonTileParams p;
  p.points = 4;
  EXPECT_THROW(check_poisson_tile_params(p), InputError);
  p.points = 64;
  p.rho = 1.2;
  EXPECT_THROW(check_poisson_tile_params(p), InputError);
}

TEST(PointTileFile, RoundTripsExactlyAndRejectsDamage) {
  const auto& set = corner_set();
  const std::string text = poisson_tiles_to_text(set);
  const auto back = poisson_tiles_from_text(text, "t");
  EXPECT_EQ(back.tiles, set.tiles);
  EXPECT_EQ(back.radius, set.radius);
  std::string bad = text;
  bad[bad.find("tile 5\n") + 8] ^= 1;  // one digit of a coordinate
  EXPECT_THROW(poisson_tiles_from_text(bad, "t"), InputError);
  EXPECT_THROW(poisson_tiles_from_text(text.substr(0, text.size() / 2), "t"), InputError);
}

TEST(PointTileFile, VersionOneFilesOfEarlierTilekitsStillRead) {
  // Written by tilekit before edge colours existed (points/data/README.md).
  const auto set = read_poisson_tiles(std::string(TILEKIT_SOURCE_DIR) + "/points/data/corner-c2-n32-v1.ptiles");
  EXPECT_EQ(set.method, PoissonTileMethod::Corner);
  EXPECT_EQ(set.colours, 2u);
  EXPECT_EQ(set.edge_colours, 1u);
  ASSERT_EQ(set.tiles.size(), 16u);
  const auto c = check_poisson_tiles(set, 2);
  EXPECT_TRUE(c.exhaustive);
  EXPECT_GE(c.rho_across, 0.75);
  EXPECT_EQ(c.points_off_count, 0u);
  // Sets without edge colours are still written as version 1.
  EXPECT_TRUE(poisson_tiles_to_text(set).starts_with("TILEKIT-POINT-TILES 1\n"));
}

TEST(PointTileFile, EdgeColoursNeedVersionTwoAndANewerVersionIsRefusedByNumber) {
  const std::string text = poisson_tiles_to_text(edged_set());
  ASSERT_TRUE(text.starts_with("TILEKIT-POINT-TILES 2\nmethod corner\ncolors 1\nedge_colors 2\n"));
  const auto back = poisson_tiles_from_text(text, "t");
  EXPECT_EQ(back.edge_colours, 2u);
  EXPECT_EQ(back.tiles, edged_set().tiles);
  std::string newer = text;
  newer.replace(0, std::string("TILEKIT-POINT-TILES 2").size(), "TILEKIT-POINT-TILES 3");
  try {
    poisson_tiles_from_text(newer, "n.ptiles");
    ADD_FAILURE() << "a version 3 file was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("n.ptiles:1: point tile-set format version 3 is newer"), std::string::npos)
        << e.what();
  }
}

TEST(CornerPoissonTiles, EdgeColoursVaryTheEdgeRegionAndKeepTheRadiusAcrossEveryNeighbourPair) {
  const auto& set = edged_set();
  ASSERT_EQ(set.tiles.size(), 16u);  // C^4 E^4
  EXPECT_EQ(set.edge_regions, 4u);   // 2 C^2 E
  const auto c = check_poisson_tiles(set, 2);
  EXPECT_TRUE(c.exhaustive);
  EXPECT_GE(c.rho_across, 0.75);
  EXPECT_GE(c.rho_within, 0.75);
  EXPECT_EQ(c.points_off_count, 0u);
  // Tiles whose north edges have the same colour share the points along it; another colour
  // gives other points there. Index: W + 2 (S + 2 (E + 2 N)).
  const auto north = [&](std::uint64_t t) {
    std::vector<Point2> v;
    for (const auto& q : set.tiles[t])
      if (q.y < 0.5 * set.radius && q.x > 0.3 && q.x < 0.7) v.push_back(q);
    std::sort(v.begin(), v.end(), [](Point2 a, Point2 b) { return a.x < b.x; });
    return v;
  };
  EXPECT_EQ(north(0), north(7));   // N = 0 in both
  EXPECT_EQ(north(8), north(15));  // N = 1 in both
  EXPECT_NE(north(0), north(8));
}
