// Generation through the direct stochastic tiling: the distance holds everywhere (an
// independent brute-force check on the float output, not the construction's bookkeeping),
// windows are random access, the density is right and threads do not change the output.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "base/random.hpp"
#include "points/generator.hpp"

using namespace tilekit;
using namespace tilekit::points;

namespace {

const PoissonTileSet& tiles() {
  static const PoissonTileSet set = [] {
    PoissonTileParams p;
    p.colours = 3;
    p.points = 32;
    p.rho = 0.75;
    p.seed = 11;
    p.threads = 2;
    return build_poisson_tiles(p);
  }();
  return set;
}

// Smallest distance between two of the points, by a sweep over x (independent of PointGrid).
double sweep_min_distance(const std::vector<double>& xy) {
  std::vector<std::pair<double, double>> p;
  for (std::size_t i = 0; i + 1 < xy.size(); i += 2) p.emplace_back(xy[i], xy[i + 1]);
  std::sort(p.begin(), p.end());
  double best = 1e300;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size() && p[j].first - p[i].first < best; ++j)
      best = std::min(best, std::hypot(p[j].first - p[i].first, p[j].second - p[i].second));
  return best;
}

std::set<std::pair<float, float>> as_set(const std::vector<double>& xy) {
  std::set<std::pair<float, float>> s;
  for (std::size_t i = 0; i + 1 < xy.size(); i += 2) s.emplace(xy[i], xy[i + 1]);
  return s;
}

}  // namespace

TEST(PoissonTileGenerator, NoTwoPointsCloserThanTwoRInRandomWindows) {
  const PoissonTileGenerator gen(tiles(), HashKind::LongPeriod, 7);
  SplitMix64 rng(42);
  const double density = 1000;  // tile side sqrt(32 / 1000) = 0.179
  const double s = gen.tile_size(density);
  const double d = 2 * tiles().radius * s;  // the distance asked for, in window units
  for (int k = 0; k < 8; ++k) {
    const double x0 = (rng.uniform() - 0.5) * 2000, y0 = (rng.uniform() - 0.5) * 2000;
    const Window w{x0, y0, x0 + 3 + rng.uniform(), y0 + 3 + rng.uniform()};
    const auto pts = gen.generate(w, density);
    ASSERT_GT(pts.size(), 2 * 8000u);
    // float32 coordinates near 1000 carry about 6e-5 of rounding.
    EXPECT_GE(sweep_min_distance(pts), d - 2e-4) << "window " << k;
    for (std::size_t i = 0; i < pts.size(); i += 2) {
      ASSERT_GE(pts[i], float(w.x0) - 1e-3f);
      ASSERT_LE(pts[i], float(w.x1) + 1e-3f);
    }
  }
}

TEST(PoissonTileGenerator, OverlappingWindowsAgreeOnTheirOverlap) {
  const PoissonTileGenerator gen(tiles(), HashKind::LongPeriod, 3);
  const double density = 400;
  const Window a{-1.3, 2.05, 2.2, 4.4}, b{0.7, 3.1, 3.9, 6.0}, both{0.7, 3.1, 2.2, 4.4};
  const auto in_overlap = [&](const std::vector<double>& xy) {
    std::vector<double> out;
    for (std::size_t i = 0; i < xy.size(); i += 2)
      if (xy[i] >= both.x0 && xy[i] < both.x1 && xy[i + 1] >= both.y0 && xy[i + 1] < both.y1)
        out.insert(out.end(), {xy[i], xy[i + 1]});
    return out;
  };
  const auto from_a = in_overlap(gen.generate(a, density)), from_b = in_overlap(gen.generate(b, density));
  const auto direct = gen.generate(both, density);
  EXPECT_GT(direct.size(), 2 * 600u);  // 1.5 x 1.3 at density 400
  EXPECT_EQ(as_set(from_a), as_set(direct));
  EXPECT_EQ(as_set(from_b), as_set(direct));
}

TEST(PoissonTileGenerator, ThreadsDoNotChangeTheOutput) {
  const PoissonTileGenerator gen(tiles(), HashKind::Permutation, 9);
  const Window w{-5, -5, 5, 5};
  EXPECT_EQ(gen.generate(w, 200, 1), gen.generate(w, 200, 2));
}

// A reused buffer (generate_into) holds exactly what a fresh one would, whatever it held before
// and whether it must grow, on one thread and on two.
TEST(PoissonTileGenerator, AReusedBufferHoldsExactlyTheFreshOutput) {
  const PoissonTileGenerator gen(tiles(), HashKind::LongPeriod, 4);
  const Window big{-9, -9, 9, 9}, small{2.5, -1, 4, 3};
  for (int threads : {1, 2}) {
    std::vector<double> buf{1, 2, 3};
    gen.generate_into(buf, small, 200, threads);
    EXPECT_EQ(buf, gen.generate(small, 200, threads));
    gen.generate_into(buf, big, 200, threads);  // grows
    EXPECT_EQ(buf, gen.generate(big, 200, threads));
    gen.generate_into(buf, small, 200, threads);  // shrinks, keeps its capacity
    EXPECT_EQ(buf, gen.generate(small, 200, threads));
  }
}

TEST(PoissonTileGenerator, TileAlignedWindowsHoldExactlyNPerTile) {
  const PoissonTileGenerator gen(tiles(), HashKind::LongPeriod, 1);
  const double s = gen.tile_size(32.0);  // tile side 1
  ASSERT_DOUBLE_EQ(s, 1.0);
  const auto pts = gen.generate({-7, 3, 13, 18}, 32.0);
  EXPECT_EQ(pts.size(), 2u * 20 * 15 * 32);
}

TEST(PoissonTileGenerator, PeriodicTilingRepeatsWithItsPeriod) {
  const PoissonTileGenerator gen(tiles(), HashKind::LongPeriod, 4, 5);
  const auto a = gen.generate({0, 0, 5, 5}, 32.0), b = gen.generate({5, 10, 10, 15}, 32.0);
  ASSERT_EQ(a.size(), b.size());
  std::vector<double> shifted;
  for (std::size_t i = 0; i < b.size(); i += 2) shifted.insert(shifted.end(), {b[i] - 5, b[i + 1] - 10});
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], shifted[i], 1e-5);
}

TEST(PoissonTileGenerator, EdgeBasedAndDualSetsGenerateValidWindowsToo) {
  for (auto method : {PoissonTileMethod::Wang, PoissonTileMethod::Dual}) {
    PoissonTileParams p;
    p.method = method;
    p.colours = 1;
    p.points = 32;
    p.threads = 2;
    const auto set = build_poisson_tiles(p);
    const PoissonTileGenerator gen(set, HashKind::LongPeriod, 5);
    const auto pts = gen.generate({0, 0, 12, 12}, 32.0);
    EXPECT_EQ(pts.size(), 2u * 144 * 32);
    EXPECT_GE(sweep_min_distance(pts), 2 * set.radius - 1e-5) << method_name(method);
  }
}

TEST(PoissonTileGenerator, EdgeColouredSetsPlaceTheTilesTheLatticeAndEdgeHashesName) {
  PoissonTileParams p;
  p.colours = 1;
  p.edge_colours = 2;
  p.points = 32;
  p.threads = 2;
  const auto set = build_poisson_tiles(p);
  // The row-wise fast path against the tile-by-tile index (tile side 1 at density 32).
  const PoissonTileGenerator gen(set, HashKind::LongPeriod, 5);
  const auto pts = gen.generate({-3, 2, 9, 10}, 32.0);
  std::vector<double> expected;
  std::set<std::uint64_t> used;
  for (std::int64_t ty = 2; ty < 10; ++ty)
    for (std::int64_t tx = -3; tx < 9; ++tx) {
      used.insert(gen.tile_index(tx, ty));
      for (const Point2& q : set.tiles[gen.tile_index(tx, ty)])
        expected.insert(expected.end(), {double(tx) + q.x, double(ty) + q.y});
    }
  EXPECT_EQ(pts, expected);
  EXPECT_GE(used.size(), 14u);  // of the 16 combinations of four edge colours
  EXPECT_GE(sweep_min_distance(pts), 2 * set.radius - 1e-5);
  // A periodic tiling repeats its edge colours too.
  const PoissonTileGenerator periodic(set, HashKind::LongPeriod, 5, 4);
  const auto a = periodic.generate({0, 0, 4, 4}, 32.0), b = periodic.generate({4, 8, 8, 12}, 32.0);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); i += 2) {
    EXPECT_NEAR(a[i], b[i] - 4, 1e-5);
    EXPECT_NEAR(a[i + 1], b[i + 1] - 8, 1e-5);
  }
}
