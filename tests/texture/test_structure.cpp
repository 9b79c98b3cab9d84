// Structured exemplars whose lines must continue across tile borders: a painted tile floor whose
// grout wanders by a pixel or two, planks whose edges are the strongest of two lines per period,
// and courses of bricks. The lattice's phase puts the strongest line on the borders, every sample
// of an exemplar that repeats exactly keeps that phase, and the render's line continuity
// (texture_analysis.hpp) stays within 20 % of the exemplar's own on the same lattice at that phase.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>

#include "base/random.hpp"
#include "texture/exemplar.hpp"
#include "texture/seam_metrics.hpp"
#include "texture/texture_analysis.hpp"
#include "texture/tile_synthesis.hpp"
#include "texture_fixtures.hpp"
#include "tiling/direct_tiling.hpp"

namespace tilekit {
namespace {

// A tileable 256x256 floor of 64-px cells (as ufo-tile's): dark grout 6 px wide whose every
// segment (between two cells) lies up to 2 px off the lattice, as painted by hand; faces of a grey
// that differs per cell, with noise.
Image tile_floor() {
  const int side = 256, cell = 64, cells = side / cell;
  SplitMix64 rng(11);
  std::int32_t off_x[4][4], off_y[4][4], grey[4][4];  // the segment left of / above cell [row][col]
  for (auto* table : {&off_x, &off_y})
    for (auto& row : *table)
      for (auto& v : row) v = std::int32_t(rng.uniform() * 5) - 2;
  for (auto& row : grey)
    for (auto& v : row) v = 120 + std::int32_t(rng.uniform() * 60);
  Image img(side, side);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const int row = y / cell, col = x / cell;
      bool grout = false;
      for (int k = 0; k <= cells; ++k) {  // segments of the vertical line k in this row, horizontal in this column
        const int vx = k * cell + off_x[row][k % cells], hy = k * cell + off_y[k % cells][col];
        grout = grout || std::abs(x - vx + 0.5) < 3 || std::abs(y - hy + 0.5) < 3 ||
                std::abs(x + side - vx + 0.5) < 3 || std::abs(y + side - hy + 0.5) < 3;
      }
      const int v = (grout ? 40 : grey[row][col]) + int(rng.uniform() * 30) - 15;
      img.set(x, y, {std::uint8_t(v), std::uint8_t(v), std::uint8_t(std::min(255, v + 10))});
    }
  return img;
}

// A tileable 256x256 wall of courses 16 px high: mortar 3 px high whose line wanders up to 1 px
// along the wall (laid by hand), head joints at random along each course (no period across), bricks
// of a colour each, with noise.
Image courses() {
  const int side = 256, course = 16;
  SplitMix64 rng(13);
  std::int32_t joints[16][3], shade[16][4];
  for (auto& row : joints)
    for (auto& v : row) v = std::int32_t(rng.uniform() * side);
  for (auto& row : shade)
    for (auto& v : row) v = std::int32_t(rng.uniform() * 50);
  Image img(side, side);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const int wobble = int(std::lround(std::sin(2 * std::numbers::pi * x / side * 3 + y / course)));
      const int yy = (y - wobble + side) % side, row = yy / course;
      bool mortar = yy % course < 3;
      int brick = 0;
      for (int j = 0; j < 3; ++j) {
        const int d = (x - joints[row][j] + side) % side;
        mortar = mortar || d < 3;
        brick += x >= joints[row][j];
      }
      const int noise = int(rng.uniform() * 24) - 12;
      const int v = mortar ? 200 + noise : 110 + shade[row][brick] + noise;
      img.set(x, y, {std::uint8_t(std::clamp(v, 0, 255)), std::uint8_t(std::clamp(v * 3 / 5, 0, 255)), 50});
    }
  return img;
}

// Tileable 256x256 planks 32 px wide: a dark edge at x = 32k + 23 and, halfway between, a fainter
// line of the grain at x = 32k + 7, on wood with vertical streaks and noise.
Image planks() {
  const int side = 256;
  SplitMix64 rng(12);
  std::int32_t streak[256];
  for (auto& v : streak) v = std::int32_t(rng.uniform() * 24);
  Image img(side, side);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const int r = x % 32;
      int v = 150 + streak[x] + int(rng.uniform() * 16);
      if (r == 23) v = 50;
      if (r == 7) v -= 45;
      img.set(x, y, {std::uint8_t(std::clamp(v, 0, 255)), std::uint8_t(std::clamp(v * 2 / 3, 0, 255)), 60});
    }
  return img;
}

// A 16x16-tile stitched render of corner tiles (C = 2, 64 px) over the exemplar's own continuity
// on the same lattice with a corner where the synthesis puts one.
double continuity_vs_exemplar(const Exemplar& e, const TextureTileSet& s) {
  const Tiling t = DirectCornerTiling(2, HashKind::LongPeriod, 1).generate(16, 16);
  const LineContinuity render = line_continuity(stitch_tiles(s, t), s.tile_px);
  const Image& own = s.sampled.width ? s.sampled : e.image;
  const LineContinuity exemplar =
      line_continuity(own, s.tile_px, int(std::lround(s.phase[0])), int(std::lround(s.phase[1])));
  EXPECT_GT(exemplar.ratio, 0.0);
  return render.ratio / exemplar.ratio;
}

TEST(Structure, GroutThatWandersAPixelOrTwoStaysOnTheBordersWithEverySampleInPhase) {
  const Exemplar e = exemplar_from_image(tile_floor(), "tile-floor", true);
  SynthesisOptions o = test::small_options(TileKind::Corner, 2, 64, 2);
  o.period_override = {64, 64};  // as --period 64,64 (the detector sees the grout's width, 6 px, first)
  const TextureTileSet s = synthesize_corner_tiles(e, o);
  // the grout (x, y = 64k - 3 .. 64k + 2, segments moved by up to 2) on the borders
  for (int k = 0; k < 2; ++k) EXPECT_LE(std::abs(std::remainder(s.phase[std::size_t(k)] + 0.5, 64.0)), 2.0) << k;
  // An exemplar that repeats exactly keeps every sample a whole number of periods from the
  // others: moving each to its own estimate of where its grout lies (as for a rectified wall)
  // broke the grout at the tile corners by the pixel or two the painter's lines wander.
  // (The centre patches are all shown at the same place in their tiles.)
  for (const std::array<int, 2>& q : s.centres)
    for (int k = 0; k < 2; ++k)
      EXPECT_LE(std::abs(std::remainder(q[std::size_t(k)] - s.centres[0][std::size_t(k)], 64.0)), 0.5)
          << q[0] << "," << q[1];
}

// --tile-px auto (choose_tile_size): the least multiple of the larger period of at least 64 px.
// A tile of one 64-px cell keeps the floor's grout on the borders only; tiles of two (the
// multiple nearest 128 px, before) put grout halfway between the borders too, where the cuts
// break it (ufo-tile: line continuity 1.26 times the exemplar's; BENCHMARKS.md, "Texture
// structure and tile size").
TEST(Structure, TheDefaultTileSizeIsTheLeastWholeNumberOfPeriodsOfAtLeast64Px) {
  const Exemplar e = exemplar_from_image(tile_floor(), "tile-floor", true);
  const auto size = [&](double px, double py) {
    ExemplarPeriod p;
    p.x = px, p.y = py;
    return choose_tile_size(e, p);
  };
  const TileSizeChoice floor = size(64, 64);
  EXPECT_EQ(floor.tile_px, 64);
  EXPECT_EQ(floor.period, 64);
  EXPECT_NE(floor.reason.find("1 whole period"), std::string::npos) << floor.reason;
  EXPECT_EQ(size(32, 0).tile_px, 64);    // two periods of the planks above
  EXPECT_EQ(size(0, 34.6).tile_px, 68);  // two periods of skimage's brick as `tiles` sees it (69.2, even)
  EXPECT_EQ(size(24, 30).tile_px, 90);   // the larger period: three of 30
  EXPECT_EQ(size(100, 0).tile_px, 100);  // one period of 64 px or more
  // 50 px: two periods, not one stretched to the 64-px floor (the synthesis keeps a period only
  // within 25 % of stretch)
  EXPECT_EQ(size(50, 0).tile_px, 100);
  // at most 512 px and what the exemplar allows (tile_px + 16 within it)
  EXPECT_EQ(size(600, 0).tile_px, std::min({512, e.width() - 16, e.height() - 16}));
  // the synthesis at the size chosen keeps both periods unstretched: one cell a tile
  SynthesisOptions o = test::small_options(TileKind::Corner, 2, floor.tile_px, 2);
  o.period_override = {64, 64};
  const SynthesisExemplar x(e, o);
  EXPECT_TRUE(x.periodic());
  EXPECT_EQ(x.scale()[0], 1.0);
  EXPECT_EQ(x.scale()[1], 1.0);
}

TEST(Structure, ThePlanksEdgesNotTheirGrainGoOnTheBorders) {
  const Exemplar e = exemplar_from_image(planks(), "planks", true);
  ASSERT_NEAR(dominant_period(e).x, 32, 0.5);
  const SynthesisOptions o = test::small_options(TileKind::Corner, 2, 64, 2);
  // the edge's two sides (x = 23 and 24) on the border, not the grain's (7, 8): the lines at half
  // the period are the clearer component, and either of the two could go on the border
  EXPECT_LE(std::abs(std::remainder(SynthesisExemplar(e, o).phase()[0] - 23.5, 32.0)), 1.5);
  const TextureTileSet s = synthesize_corner_tiles(e, o);
  const double r = continuity_vs_exemplar(e, s);
  EXPECT_GE(r, 0.8);
  EXPECT_LE(r, 1.2);
}

TEST(Structure, BedJointsContinueAcrossTileBorders) {
  const Exemplar e = exemplar_from_image(courses(), "courses", true);
  const ExemplarPeriod p = dominant_period(e);
  ASSERT_TRUE(std::abs(p.y - 16) < 0.5 || std::abs(p.y - 32) < 0.5) << p.y;  // one course or two
  const SynthesisOptions o = test::small_options(TileKind::Corner, 2, 64, 2);
  const TextureTileSet s = synthesize_corner_tiles(e, o);
  const double r = continuity_vs_exemplar(e, s);
  EXPECT_GE(r, 0.8);
  EXPECT_LE(r, 1.2);
}

// A tileable 256x256 running bond of rough bricks: 64 x 32 px bricks, every other course shifted
// by half a brick (the bond repeats every 64 px along both axes), mortar 3 px wide and 30 levels
// darker, and faces grainy: every texel off by up to +-grain levels. At +-40 (and already at +-20)
// the first look at full resolution finds no period; smoothed by 2 px the bond shows.
Image rough_bricks(int grain, int side = 256) {
  SplitMix64 rng(5);
  Image img(side, side);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const int course = y / 32, shift = course % 2 ? 32 : 0;
      const bool mortar = y % 32 < 3 || (x + shift) % 64 < 3;
      const int v = std::clamp((mortar ? 100 : 130) + int((rng.uniform() * 2 - 1) * grain), 0, 255);
      img.set(x, y, Rgb{std::uint8_t(v), std::uint8_t(v), std::uint8_t(v)});
    }
  return img;
}

TEST(Structure, RoughBricksShowTheirBondOnceTheGrainIsSmoothedAway) {
  const Exemplar e = exemplar_from_image(rough_bricks(40), "rough bricks", true);
  // at its own resolution the grain's gradient hides the joints' (this is why the detector looks again)
  const ExemplarPeriod fine = period_at_scale(e, 0);
  ASSERT_TRUE(fine.x == 0 || fine.y == 0) << fine.x << "," << fine.y;
  const ExemplarPeriod p = dominant_period(e);
  EXPECT_NEAR(p.x, 64, 0.5);
  EXPECT_NEAR(p.y, 64, 0.5);
  // smooth bricks: the first look finds the bond, and the coarser ones are not asked
  const ExemplarPeriod smooth = period_at_scale(exemplar_from_image(rough_bricks(0), "bricks", true), 0);
  EXPECT_NEAR(smooth.x, 64, 0.5);
  EXPECT_NEAR(smooth.y, 64, 0.5);
}

// A 1088x1088 wall: its autocorrelations sum every third row (or column) only, and still find
// the bond, at the first look and at the second.
TEST(Structure, ALargeExemplarsBondIsFoundFromEveryThirdLine) {
  const Exemplar e = exemplar_from_image(rough_bricks(0, 1088), "large bricks", true);
  const ExemplarPeriod p = period_at_scale(e, 0);
  EXPECT_NEAR(p.x, 64, 0.5);
  EXPECT_NEAR(p.y, 64, 0.5);
  const ExemplarPeriod rough = dominant_period(exemplar_from_image(rough_bricks(40, 1088), "large rough bricks", true));
  EXPECT_NEAR(rough.x, 64, 0.5);
  EXPECT_NEAR(rough.y, 64, 0.5);
}

}  // namespace
}  // namespace tilekit
