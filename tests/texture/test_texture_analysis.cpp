// The measures of `tilekit texture analyze` (texture/texture_analysis.hpp) on images whose answer
// is known: a mosaic of random crops shows no lattice, one tile repeated shows nothing else.
#include <gtest/gtest.h>

#include <cmath>

#include "base/error.hpp"
#include "base/random.hpp"
#include "texture/seam_metrics.hpp"
#include "texture/texture_analysis.hpp"
#include "texture_fixtures.hpp"

namespace tilekit {
namespace {

// Smooth random texture: white noise blurred by a 5x5 box, on a torus of `side` pixels.
Image noise_texture(int side, std::uint64_t seed) {
  SplitMix64 rng(seed);
  std::vector<double> v(std::size_t(side) * std::size_t(side));
  for (double& x : v) x = rng.uniform();
  Image img(side, side);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      double s = 0;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx)
          s += v[std::size_t((y + dy + side) % side) * std::size_t(side) + std::size_t((x + dx + side) % side)];
      const auto g = std::uint8_t(std::clamp(std::lround(128 + (s / 25 - 0.5) * 600), 0l, 255l));
      img.set(x, y, {g, g, g});
    }
  return img;
}

// T x T crops of `src` at random places, abutted (the naive mosaic), or the same crop everywhere.
Image mosaic(const Image& src, int tile, int tiles, bool repeat, std::uint64_t seed) {
  SplitMix64 rng(seed);
  Image out(tile * tiles, tile * tiles);
  std::array<int, 2> p{0, 0};
  for (int r = 0; r < tiles; ++r)
    for (int c = 0; c < tiles; ++c) {
      if (!repeat || (r == 0 && c == 0))
        p = {int(rng.below(std::uint64_t(src.width - tile))), int(rng.below(std::uint64_t(src.height - tile)))};
      for (int y = 0; y < tile; ++y)
        for (int x = 0; x < tile; ++x) out.set(c * tile + x, r * tile + y, src.get(p[0] + x, p[1] + y));
    }
  return out;
}

TEST(TextureAnalysis, ReferenceLagsAreTheAxesAndDiagonalOffTheLattice) {
  const auto lags = reference_lags(Lattice::square(64));
  auto has = [&](int dx, int dy) {
    return std::find(lags.begin(), lags.end(), std::array<int, 2>{dx, dy}) != lags.end();
  };
  EXPECT_TRUE(has(32, 0));
  EXPECT_TRUE(has(0, 60));
  EXPECT_TRUE(has(67 + 1, 68));
  EXPECT_FALSE(has(61, 0));  // 3 px from 64
  EXPECT_FALSE(has(64, 64));
  EXPECT_FALSE(has(0, 125));
  EXPECT_FALSE(has(31, 0));
  // per direction 97 lags from 32 to 128, less 7 around 64 and 4 up to 128
  EXPECT_EQ(lags.size(), 3u * (97 - 7 - 4));
}

TEST(TextureAnalysis, RandomCropsShowNoLatticeAndOneRepeatedTileShowsOnlyIt) {
  const Image src = noise_texture(512, 3);
  const Image naive = mosaic(src, 64, 12, false, 1), repeated = mosaic(src, 64, 12, true, 1);
  const TextureAnalysis a = analyze_texture(naive, Lattice::square(64), &src);
  const TextureAnalysis b = analyze_texture(repeated, Lattice::square(64), &src, nullptr, 2);
  EXPECT_LT(std::abs(a.grid_repetition), 0.03) << a.grid_repetition;
  EXPECT_GT(b.grid_repetition, 0.9) << b.grid_repetition;
  EXPECT_NEAR(b.lattice_lags[0].r, 1.0, 1e-5);  // at (T, 0) the image is itself (float sums)
  EXPECT_LT(std::abs(a.spectrum.lattice_peak_db), 3.0) << a.spectrum.lattice_peak_db;
  EXPECT_GT(b.spectrum.lattice_peak_db, 10.0) << b.spectrum.lattice_peak_db;
  // abutted crops step across their borders; the seam ratio sees it
  EXPECT_GT(*a.seam_ratio, 1.5);
  EXPECT_NEAR(*a.histogram_distance, 0, 3.0);
  EXPECT_FALSE(a.cut_visibility);
  // the lattice frequencies marked: 1/64, sqrt(2)/64, ..., up to 8/64
  EXPECT_NEAR(a.spectrum.lattice_frequencies.front(), 1.0 / 64, 1e-9);
  EXPECT_NEAR(a.spectrum.max_frequency, 8.0 / 64, 1e-9);
}

TEST(TextureAnalysis, AnyLatticeCanBeMeasuredSuchAsHexTilings) {
  // content that repeats on a triangular lattice of spacing 48 (a hex tiling's lattice)
  const Image src = noise_texture(128, 5);
  const double s = 48, h = s * std::sqrt(3.0) / 2;
  Image img(480, 480);
  for (int y = 0; y < 480; ++y)
    for (int x = 0; x < 480; ++x) {
      const double j = std::floor(y / h), xs = x - j * s / 2, i = std::floor(xs / s);
      img.set(x, y, src.get(int(xs - i * s), int(y - j * h)));
    }
  Lattice hex{{s, 0}, {s / 2, h}, {0, 0}};
  const TextureAnalysis a = analyze_texture(img, hex);
  EXPECT_GT(a.grid_repetition, 0.5) << a.grid_repetition;
  EXPECT_FALSE(a.seam_ratio);                                                 // no tile borders on pixel rows
  EXPECT_LT(analyze_texture(img, Lattice::square(41)).grid_repetition, 0.1);  // lags not on that lattice
}

TEST(TextureAnalysis, HistogramDistanceIsTheShiftOfTheGreyLevels) {
  const Image src = noise_texture(64, 7);
  Image brighter = src;
  for (std::size_t i = 0; i < brighter.pixels.size(); i += 4)
    for (int c = 0; c < 3; ++c)
      brighter.pixels[i + std::size_t(c)] = std::uint8_t(std::min(255, src.pixels[i + std::size_t(c)] + 10));
  const auto emd = histogram_emd(brighter, src);
  for (double v : emd) EXPECT_NEAR(v, 10, 0.6);  // a few pixels clip at 255
}

TEST(TextureAnalysis, CutVisibilityComparesStepsAcrossLabelBoundariesWithStepsInside) {
  const Image src = noise_texture(256, 9);
  Image labels(256, 256);
  std::vector<std::uint32_t> ids(256 * 256);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) {
      const std::uint8_t id = std::uint8_t((x / 40 + y / 30) % 3);
      labels.set(x, y, {0, 0, id});
      ids[std::size_t(y) * 256 + std::size_t(x)] = id;
    }
  const TextureAnalysis a = analyze_texture(src, Lattice::square(64), nullptr, &labels);
  EXPECT_DOUBLE_EQ(*a.cut_visibility, seam_statistics(src, 64, &ids).cut_ratio);
  EXPECT_NEAR(*a.cut_visibility, 1.0, 0.1);  // one continuous texture: the "cuts" do not show
}

TEST(TextureAnalysis, ImagesTooSmallForTheLatticeAndLabelsOfAnotherSizeAreInputErrors) {
  const Image src = noise_texture(200, 1);
  EXPECT_THROW(analyze_texture(src, Lattice::square(64)), InputError);  // needs 256 px
  EXPECT_NO_THROW(analyze_texture(src, Lattice::square(50)));
  const Image small = noise_texture(100, 1);
  EXPECT_THROW(analyze_texture(src, Lattice::square(50), nullptr, &small), InputError);
  EXPECT_THROW(analyze_texture(src, Lattice{{10, 0}, {20, 0}, {0, 0}}), InputError);  // degenerate
}

// Mortar-like lines every 8 rows with a little noise: continuous across the lattice's borders
// (ratio near 1), or shifted by 4 rows in every other 32-pixel tile column (broken at the borders).
TEST(LineContinuity, SeesLinesThatStopAtTileBorders) {
  const auto wall = [](bool broken) {
    Image img(256, 256);
    SplitMix64 rng(7);
    for (int y = 0; y < 256; ++y)
      for (int x = 0; x < 256; ++x) {
        const int shift = broken && (x / 32) % 2 ? 4 : 0;
        const int v = ((y + shift) % 8 == 0 ? 60 : 180) + int(rng.uniform() * 30) + int(20 * std::sin(x * 0.3));
        img.set(x, y, {std::uint8_t(v), std::uint8_t(v), std::uint8_t(v)});
      }
    return img;
  };
  const LineContinuity whole = line_continuity(wall(false), 32), broken = line_continuity(wall(true), 32);
  EXPECT_GT(whole.ratio, 0.9);
  EXPECT_LT(whole.ratio, 1.1);
  EXPECT_LT(broken.ratio, 0.7);
  EXPECT_NEAR(broken.interior, whole.interior, 0.05);  // inside the tiles the lines are the same
  const TextureAnalysis a = analyze_texture(wall(true), Lattice{{32, 0}, {0, 32}, {0, 0}});
  ASSERT_TRUE(a.line_continuity.has_value());
  EXPECT_DOUBLE_EQ(*a.line_continuity, broken.ratio);
}

}  // namespace
}  // namespace tilekit
