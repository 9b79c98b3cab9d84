// The map filler's model and driver (solver/fill_model.hpp, solver/fill_search.hpp): fills of
// the complete corner set over two colours, checked here by decoding the corners of every cell
// (not through the rules the search used), fixed cells, refuted requests with their window,
// block fills across block borders and the torus' wrap, and a resume equal to the whole run.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "solver/fill_search.hpp"

namespace tilekit::test {
namespace {

// Corner tiles over C colours (index ((ne*C + se)*C + sw)*C + nw), neighbours where corners meet.
std::shared_ptr<FillRules> corner_rules(int colours, std::vector<double> weights = {}) {
  const int n = colours * colours * colours * colours;
  auto r = std::make_shared<FillRules>(n, std::move(weights));
  auto corner = [&](int t, int k) {  // k: 0 nw, 1 sw, 2 se, 3 ne
    for (int i = 0; i < k; ++i) t /= colours;
    return t % colours;
  };
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      if (corner(a, 3) == corner(b, 0) && corner(a, 2) == corner(b, 1)) r->allow(a, 1, b);  // b east of a
      if (corner(a, 1) == corner(b, 0) && corner(a, 2) == corner(b, 3)) r->allow(a, 2, b);  // b south of a
    }
  return r;
}

// Every neighbour pair of a corner map agrees on its shared corners (decoded here).
int corner_mismatches(const std::vector<int>& map, int rows, int cols, bool torus, int colours) {
  auto c = [&](int t, int k) {
    for (int i = 0; i < k; ++i) t /= colours;
    return t % colours;
  };
  int bad = 0;
  for (int r = 0; r < rows; ++r)
    for (int q = 0; q < cols; ++q) {
      const int a = map[std::size_t(r * cols + q)];
      if (q + 1 < cols || torus) {
        const int b = map[std::size_t(r * cols + (q + 1) % cols)];
        bad += c(a, 3) != c(b, 0) || c(a, 2) != c(b, 1);
      }
      if (r + 1 < rows || torus) {
        const int b = map[std::size_t(((r + 1) % rows) * cols + q)];
        bad += c(a, 1) != c(b, 0) || c(a, 2) != c(b, 3);
      }
    }
  return bad;
}

FillMapRequest request(int rows, int cols, bool torus, std::uint64_t seed = 1) {
  FillMapRequest req;
  req.rules = corner_rules(2);
  req.rows = rows, req.cols = cols, req.torus = torus;
  req.run.seed = seed;
  return req;
}

TEST(FillModel, FillsTheTorusAndTheBoundedMap) {
  for (const bool torus : {false, true}) {
    const FillMapOutcome o = fill_map(request(13, 17, torus));
    ASSERT_TRUE(o.found);
    EXPECT_EQ(corner_mismatches(o.map, 13, 17, torus, 2), 0) << torus;
  }
}

TEST(FillModel, FixedCellsStayWhereTheyAre) {
  FillMapRequest req = request(12, 12, true, 5);
  req.fixed.assign(144, -1);
  req.fixed[0] = 0;     // all colour 0
  req.fixed[77] = 15;   // all colour 1
  req.fixed[143] = 9;   // mixed; its south-east corner is the peg of cell 0 across the wrap
  const FillMapOutcome o = fill_map(req);
  ASSERT_TRUE(o.found);
  EXPECT_EQ(o.map[0], 0);
  EXPECT_EQ(o.map[77], 15);
  EXPECT_EQ(o.map[143], 9);
  EXPECT_EQ(corner_mismatches(o.map, 12, 12, true, 2), 0);
}

TEST(FillModel, ARefutedRequestNamesASmallWindow) {
  FillMapRequest req = request(20, 30, false);
  req.fixed.assign(600, -1);
  req.fixed[5 * 30 + 7] = 0;   // colour 0 everywhere
  req.fixed[5 * 30 + 8] = 15;  // colour 1 everywhere, east of it: the shared corners differ
  const FillMapOutcome o = fill_map(req);
  EXPECT_FALSE(o.found);
  EXPECT_TRUE(o.proved_impossible);
  EXPECT_LE(o.window.rows * o.window.cols, 2);
  EXPECT_EQ(o.window.row, 5);
  EXPECT_EQ(o.window.col, 7);
  // the proof is sound: the window alone, with nothing around it, has no fill
  EXPECT_EQ(fill_window_status(req.rules, req.fixed, 20, 30, false, o.window, 1000), 1);
  EXPECT_EQ(fill_window_status(req.rules, req.fixed, 20, 30, false, {0, 0, 3, 3}, 1000), 0);
}

TEST(FillModel, BlocksAgreeAcrossTheirBordersAndTheWrap) {
  FillMapRequest req = request(150, 170, true, 3);
  req.block = 32;
  const FillMapOutcome o = fill_map(req);
  ASSERT_TRUE(o.found);
  EXPECT_EQ(o.blocks, 5 * 6);
  EXPECT_EQ(corner_mismatches(o.map, 150, 170, true, 2), 0);
}

TEST(FillModel, WeightsSteerTheTileFrequencies) {
  FillMapRequest req = request(64, 64, true, 9);
  std::vector<double> w(16, 1.0);
  w[0] = 50;  // colour 0 everywhere
  req.rules = corner_rules(2, w);
  const FillMapOutcome o = fill_map(req);
  ASSERT_TRUE(o.found);
  int zeros = 0;
  for (int t : o.map) zeros += t == 0;
  EXPECT_GT(zeros, 64 * 64 / 4);  // uniform weights give about 1/16
}

// WFC's order (least entropy of the weights left, on the frontier, ties by seeded noise): valid
// maps, bounded, on the torus and in blocks, the same map for the same seed, weights followed.
TEST(FillModel, TheEntropyOrderFillsValidMapsAndFollowsTheWeights) {
  std::vector<double> w(16, 1.0);
  w[0] = 50;
  for (const bool torus : {false, true}) {
    FillMapRequest req = request(90, 70, torus, 4);
    req.rules = corner_rules(2, w);
    req.order = FillOrder::Entropy;
    req.block = 32;
    const FillMapOutcome o = fill_map(req);
    ASSERT_TRUE(o.found) << torus;
    EXPECT_EQ(corner_mismatches(o.map, 90, 70, torus, 2), 0) << torus;
    EXPECT_EQ(fill_map(req).map, o.map) << torus;
    int zeros = 0;
    for (int t : o.map) zeros += t == 0;
    EXPECT_GT(zeros, 90 * 70 / 4) << torus;
    req.order = FillOrder::Scanline;
    EXPECT_NE(fill_map(req).map, o.map) << "the order changes the dives";
  }
}

TEST(FillModel, AResumedFillEndsWithTheSameMap) {
  const std::string ck = (std::filesystem::temp_directory_path() / "tilekit-fill-model-test.ckpt").string();
  std::remove(ck.c_str());
  FillMapRequest req = request(160, 160, false, 7);
  req.block = 16;
  const FillMapOutcome whole = fill_map(req);
  ASSERT_TRUE(whole.found);
  FillMapRequest first = req;
  first.run.checkpoint_path = ck;
  first.run.time_limit = 0.02;  // stops part way, after a checkpoint
  const FillMapOutcome part = fill_map(first);
  FillMapRequest rest = req;
  rest.run.checkpoint_path = ck;
  rest.run.resume_path = ck;
  const FillMapOutcome resumed = fill_map(rest);
  ASSERT_TRUE(resumed.found);
  EXPECT_TRUE(resumed.resumed);
  EXPECT_EQ(resumed.map, whole.map);
  // a checkpoint of another request is refused
  FillMapRequest other = rest;
  other.run.seed = 8;
  EXPECT_THROW(fill_map(other), InputError);
  std::remove(ck.c_str());
  (void)part;
}

}  // namespace
}  // namespace tilekit::test
