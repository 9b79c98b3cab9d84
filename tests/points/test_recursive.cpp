// Recursive Wang tiles (Kopf et al. 2006): progressive (the points at density d are a subset of
// those at any higher density, also for a varying density), density right on average, random
// access, base points on their subdivision, file round trip; the object distribution function
// and density functions.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "base/error.hpp"
#include "points/density.hpp"
#include "points/object_distribution.hpp"
#include "points/point_io.hpp"
#include "points/recursive_tiles.hpp"

using namespace tilekit;
using namespace tilekit::points;

namespace {

const RecursiveWangTiles& rtiles() {
  static const RecursiveWangTiles t = [] {
    RecursiveTileParams p;
    p.points = 128;
    p.threads = 2;
    p.seed = 3;
    return build_recursive_tiles(p);
  }();
  return t;
}

std::set<std::pair<float, float>> point_set(const std::vector<double>& xy) {
  std::set<std::pair<float, float>> s;
  for (std::size_t i = 0; i + 1 < xy.size(); i += 2) s.emplace(xy[i], xy[i + 1]);
  return s;
}

}  // namespace

TEST(RecursiveWangTiles, BasePointsLieOnTheirSubdivisionAndRanksArePermutations) {
  const auto& t = rtiles();
  ASSERT_EQ(t.types(), 8u);  // the compact Wang set over 2 colours
  EXPECT_LT(t.relax_residual, 0.05);
  const int n = t.n;
  for (std::size_t type = 0; type < t.types(); ++type) {
    ASSERT_EQ(t.base[type].size(), t.points);
    // Every base point coincides with a subdivision point ranked below N.
    for (std::uint32_t k = 0; k < t.points; ++k) {
      double best = 1;
      for (int j = 0; j < n * n; ++j)
        for (std::uint32_t i = 0; i < t.points; ++i) {
          if (t.rank[type][std::size_t(j) * t.points + i] != k) continue;
          const Point2 q = t.base[t.rule[type][std::size_t(j)]][i];
          best = std::hypot((j % n + q.x) / n - t.base[type][k].x, (j / n + q.y) / n - t.base[type][k].y);
        }
      EXPECT_LT(best, 2e-6) << type << " " << k;  // exact, except points kept 1e-6 inside the borders
    }
  }
}

TEST(RecursiveWangTiles, PointsAtALowerDensityAreASubsetOfThoseAtAHigherOne) {
  const RecursiveGenerator g(rtiles(), HashKind::LongPeriod, 5);
  const Window w{0.3, -1.7, 6.3, 4.3};
  std::set<std::pair<float, float>> previous;
  for (double d : {40.0, 120.0, 300.0, 700.0, 2500.0, 9000.0}) {
    const auto xy = g.generate(w, *constant_density(d), 1.0);
    const auto now = point_set(xy);
    EXPECT_EQ(now.size(), xy.size() / 2);  // no point twice
    for (const auto& p : previous) ASSERT_TRUE(now.count(p)) << "density " << d;
    EXPECT_NEAR(double(now.size()), d * w.area(), 0.06 * d * w.area());
    previous = now;
  }
}

TEST(RecursiveWangTiles, ProgressiveForAVaryingDensityToo) {
  const RecursiveGenerator g(rtiles(), HashKind::LongPeriod, 8);
  const Window w{0, 0, 4, 4};
  const auto low = expression_density("300 * (1 + x) * exp(-0.2 * y)");
  const auto high = expression_density("900 * (1 + x) * exp(-0.2 * y) + 50");
  const auto a = g.generate(w, *low, 1.0), b = g.generate(w, *high, 1.0);
  const auto sb = point_set(b);
  for (const auto& p : point_set(a)) ASSERT_TRUE(sb.count(p));
  EXPECT_GT(b.size(), 2 * a.size());
}

TEST(RecursiveWangTiles, OverlappingWindowsAgree) {
  const RecursiveGenerator g(rtiles(), HashKind::Permutation, 2);
  const auto d = constant_density(800);
  const auto a = g.generate({0, 0, 3, 3}, *d, 1.0), b = g.generate({1, 1, 4, 4}, *d, 1.0);
  std::set<std::pair<float, float>> sa, sb;
  for (const auto& p : point_set(a))
    if (p.first >= 1 && p.second >= 1) sa.insert(p);
  for (const auto& p : point_set(b))
    if (p.first < 3 && p.second < 3) sb.insert(p);
  EXPECT_EQ(sa, sb);
  EXPECT_GT(sa.size(), 3000u);
}

TEST(RecursiveWangTiles, FileRoundTripsAndRejectsDamage) {
  const std::string text = recursive_tiles_to_text(rtiles());
  const auto back = recursive_tiles_from_text(text, "t");
  EXPECT_EQ(back.base, rtiles().base);
  EXPECT_EQ(back.rank, rtiles().rank);
  EXPECT_EQ(back.rule, rtiles().rule);
  std::string bad = text;
  bad[text.size() / 2] = bad[text.size() / 2] == '1' ? '2' : '1';
  EXPECT_THROW(recursive_tiles_from_text(bad, "t"), InputError);
}

TEST(DensityFunctions, ExpressionsEvaluateAndReportSyntaxErrors) {
  const auto f = expression_density("2 * x + y^2 - min(x, 1) + clamp(r, 0, 10) + pi - pi");
  EXPECT_NEAR((*f)(3, 4), 6 + 16 - 1 + 5, 1e-12);
  EXPECT_EQ((*expression_density("-5"))(0, 0), 0);  // negative densities count as 0
  EXPECT_THROW(expression_density("2 * (x + 1"), InputError);
  EXPECT_THROW(expression_density("foo(x)"), InputError);
  EXPECT_THROW(expression_density("max(x)"), InputError);
  EXPECT_THROW(expression_density(""), InputError);
  // Every evaluation is checked: infinite or undefined values are bad input, not a silent 0.
  for (const char* e : {"exp(1000)", "0/0", "log(-1)", "sqrt(x - 10)"})
    EXPECT_THROW((*expression_density(e))(1, 1), InputError) << e;
  EXPECT_EQ((*expression_density("log(x)"))(0.5, 0), 0);  // finite and negative: 0
}

TEST(ObjectDistribution, ClassesFollowTheProbabilitiesAndEvaluationFindsTheClosestPoint) {
  PoissonTileParams p;
  p.colours = 2;
  p.points = 32;
  p.threads = 2;
  const auto set = build_poisson_tiles(p);
  const PoissonTileGenerator gen(set, HashKind::LongPeriod, 4);
  const ObjectDistribution pod(gen, 100.0, parse_object_classes("tree:2,rock:1,bush:1"), 9);
  const auto placed = pod.scatter({0, 0, 20, 20});
  std::vector<double> count(3, 0);
  for (const auto& o : placed) ++count[o.object];
  const double n = double(placed.size());
  EXPECT_NEAR(count[0] / n, 0.5, 0.02);
  EXPECT_NEAR(count[1] / n, 0.25, 0.02);
  // evaluate() agrees with a brute-force closest point and its class with scatter()'s.
  for (double x = 3.05; x < 6; x += 0.37)
    for (double y = 7.11; y < 10; y += 0.41) {
      const auto e = pod.evaluate(x, y);
      double best = 1e9;
      std::uint32_t cls = 0;
      for (const auto& o : placed)
        if (std::hypot(o.x - x, o.y - y) < best) best = std::hypot(o.x - x, o.y - y), cls = o.object;
      EXPECT_NEAR(e.distance, best, 1e-5);
      EXPECT_EQ(e.object, cls);
      EXPECT_EQ(e.inside, e.distance < pod.radius());
    }
  EXPECT_THROW(parse_object_classes("tree:0.5,rock"), InputError);
}
