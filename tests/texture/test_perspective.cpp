// Perspective rectification of a photographed wall (texture/perspective.hpp) and the phase of its
// lines in the synthesis (SynthesisExemplar): a wall of vertical columns drawn through a known
// homography, as a camera tilted towards the ground would see it.
#include <gtest/gtest.h>

#include <cmath>

#include "texture/perspective.hpp"
#include "texture/tile_synthesis.hpp"
#include "texture_fixtures.hpp"

namespace tilekit {
namespace {

// Columns 24 px wide between bright mortar lines 4 px wide, alternate columns darker (the period
// across is two columns, the lines' spacing one); in each column a joint every 60 px, the
// columns' joints 23 px apart (a raking bond). `tilt` sets the
// picture's denominator D = 1 + 0.0004 x tilt_x + tilt y (wall X = x / D, Y = y / D): 0 is a wall
// seen square on. Each pixel averages 3 x 3 points, so lines fall between pixels.
Image wall_picture(int w, int h, double tilt, double tilt_x = 0) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double sum = 0;
      for (int sy = 0; sy < 3; ++sy)
        for (int sx = 0; sx < 3; ++sx) {
          const double px = x + (sx + 0.5) / 3, py = y + (sy + 0.5) / 3;
          const double d = 1 + tilt_x * px + tilt * py, X = px / d + 7, Y = py / d;
          const int column = int(std::floor(X / 24));
          const bool mortar = std::fmod(X, 24) < 4 || std::fmod(Y + 23.0 * column + 6000, 60) < 4;
          sum += mortar ? 210 : 80 + 24 * ((column % 2 + 2) % 2) + (unsigned(column) * 2654435761u >> 29);
        }
      const auto v = std::uint8_t(std::lround(sum / 9));
      img.set(x, y, {v, v, v});
    }
  return img;
}

// The centres of the bright vertical lines of rows y0..y1 of an image, to a fraction of a pixel.
std::vector<double> line_centres(const Image& img, int y0, int y1) {
  std::vector<double> p(std::size_t(img.width), 0);
  for (int y = y0; y < y1; ++y)
    for (int x = 0; x < img.width; ++x) p[std::size_t(x)] += luma(img.at(x, y)) / (y1 - y0);
  std::vector<double> out;
  for (int x = 0; x < img.width;) {
    if (p[std::size_t(x)] <= 150) {
      ++x;
      continue;
    }
    int end = x;  // a run above the faces' level, widened by 2 px: its centroid
    while (end < img.width && p[std::size_t(end)] > 150) ++end;
    double s = 0, ws = 0;
    for (int k = std::max(0, x - 2); k < std::min(img.width, end + 2); ++k) {
      const double v = std::max(0.0, p[std::size_t(k)] - 110);
      s += v * (k + 0.5), ws += v;
    }
    if (x > 2 && end + 2 < img.width) out.push_back(s / ws);  // whole lines only
    x = end;
  }
  return out;
}

double mean_spacing(const std::vector<double>& c) {
  return c.size() < 2 ? 0 : (c.back() - c.front()) / double(c.size() - 1);
}

TEST(Perspective, ConvergingLinesAreFittedAndTheRectifiedWallHasOneSpacingEverywhere) {
  const Exemplar photo = exemplar_from_image(wall_picture(320, 320, 0.0015, 0.0003), "wall");
  // in the picture the columns are 24 px wide at the top and half as wide again at the bottom
  const double top = mean_spacing(line_centres(photo.image, 0, 24)),
               bottom = mean_spacing(line_centres(photo.image, 296, 320));
  EXPECT_GT(bottom / top, 1.3);
  const PerspectiveFit fit = fit_perspective(photo);
  ASSERT_TRUE(fit.applied);
  EXPECT_EQ(fit.axis, 0);
  EXPECT_LE(fit.rms, 0.03);
  EXPECT_GE(fit.lines, 10);
  EXPECT_GT(fit.spread, 1.3);
  const Exemplar flat = rectify_exemplar(photo, fit);
  EXPECT_GE(flat.width(), 160);
  EXPECT_GE(flat.height(), 200);
  // rectified: the same spacing at the top, in the middle and at the bottom, and the lines
  // vertical (the same centres in every band of rows)
  const int h = flat.height();
  const std::vector<double> a = line_centres(flat.image, 0, 24), b = line_centres(flat.image, h / 2 - 12, h / 2 + 12),
                            c = line_centres(flat.image, h - 24, h);
  ASSERT_GE(a.size(), 5u);
  ASSERT_EQ(a.size(), c.size());
  EXPECT_NEAR(mean_spacing(a) / mean_spacing(c), 1.0, 0.02);
  EXPECT_NEAR(mean_spacing(b) / mean_spacing(c), 1.0, 0.02);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], c[i], 1.0) << i;
}

TEST(Perspective, AWallSeenSquareOnNoiseAndTileablePatternsAreLeftAsTheyAre) {
  const Exemplar square_on = exemplar_from_image(wall_picture(320, 320, 0), "wall");
  const PerspectiveFit fit = fit_perspective(square_on);
  EXPECT_EQ(fit.axis, 0);  // the lines are found...
  EXPECT_LT(fit.drift, kPerspectiveMinDrift);
  EXPECT_FALSE(fit.applied);  // ...and one period fits them
  EXPECT_EQ(rectify_exemplar(square_on, fit).image.pixels, square_on.image.pixels);
  EXPECT_FALSE(fit_perspective(test::synthetic_exemplar(256)).applied);
  EXPECT_FALSE(fit_perspective(exemplar_from_image(wall_picture(320, 320, 0.0015), "wall", true)).applied);
}

TEST(Perspective, HomographyInverseTakesPointsBack) {
  Homography h;
  h.m = {1.1, 0.2, -3, -0.1, 0.9, 5, 0.0004, 0.0011, 1};
  const Homography g = h.inverse();
  for (const auto& [x, y] : std::vector<std::array<double, 2>>{{0, 0}, {100, 40}, {-20, 300}}) {
    const auto p = h.apply(x, y), q = g.apply(p[0], p[1]);
    EXPECT_NEAR(q[0], x, 1e-9);
    EXPECT_NEAR(q[1], y, 1e-9);
  }
}

// Synthesis of the photographed wall: rectified, resampled so that a 64-pixel tile holds whole
// periods, and every sample in phase with its lines on the tile borders. The found period along
// x may be two columns (their joints differ); the samples' lines must still sit at the lattice's
// multiples of one column, not anywhere within the two-column period.
TEST(Perspective, SamplesOfAPhotographedWallKeepItsLinesOnTheLattice) {
  const Exemplar photo = exemplar_from_image(wall_picture(480, 480, 0.0012), "wall");
  SynthesisOptions o = test::small_options(TileKind::Corner, 2, 64);
  const SynthesisExemplar x(photo, o);
  ASSERT_TRUE(x.perspective().applied);
  ASSERT_GT(x.period().x, 0);
  const Exemplar& e = x.exemplar();
  // the lines of the samples, shown at lattice u = 0: every centre within 1.5 px of a multiple
  // of the column width (the tile holds whole columns)
  const double column = 64.0 / std::round(64.0 / mean_spacing(line_centres(e.image, 0, e.height())));
  EXPECT_NEAR(mean_spacing(line_centres(e.image, 0, e.height())), column, 0.5);
  int checked = 0;
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    const auto q = x.in_phase(random_sample_position(e, 64, seed), 0, 0, 64, 64);
    Image window(64, 64);
    for (int yy = 0; yy < 64; ++yy)
      for (int xx = 0; xx < 64; ++xx) std::copy_n(e.at(q[0] + xx, q[1] + yy), 4, window.at(xx, yy));
    for (double c : line_centres(window, 0, 64)) {
      EXPECT_LE(std::abs(std::remainder(c, column)), 1.5) << "seed " << seed << " line at " << c;
      ++checked;
    }
  }
  EXPECT_GE(checked, 40);
}

}  // namespace
}  // namespace tilekit
