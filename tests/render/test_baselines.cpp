// The baselines of render/baseline_samplers.hpp and what they sample (render/exemplar_surface.hpp):
// half floats, the histogram transformation of Heitz & Neyret 2018 and its inverse, and the
// properties the papers claim for the blends.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "../texture/texture_fixtures.hpp"
#include "base/error.hpp"
#include "render/cpu_renderer.hpp"
#include "render/exemplar_surface.hpp"

namespace tilekit {
namespace {

TEST(HalfFloat, RoundsToNearestEvenAndReadsBack) {
  for (float v : {0.0f, 1.0f, -2.5f, 0.5f, 65504.0f, 6.103515625e-05f /* smallest normal */, 5.9604645e-08f})
    EXPECT_EQ(half_to_float(float_to_half(v)), v) << v;
  EXPECT_EQ(half_to_float(float_to_half(5e-08f)), 5.9604645e-08f);  // the smallest subnormal, 2^-24
  EXPECT_EQ(float_to_half(1.0f), 0x3c00);
  EXPECT_EQ(float_to_half(1.0f + 1.0f / 2048), 0x3c00);  // a tie: to even
  EXPECT_EQ(float_to_half(1.0f + 3.0f / 2048), 0x3c02);  // a tie: to even, upwards
  EXPECT_EQ(float_to_half(1.0f + 1.5f / 2048), 0x3c01);  // above the tie
  EXPECT_EQ(float_to_half(2047.9f), 0x6800);             // the carry moves into the exponent (2048)
  EXPECT_EQ(float_to_half(1e6f), 0x7c00);                // overflow: infinity
  for (float v = -3; v < 3; v += 0.0137f) EXPECT_NEAR(half_to_float(float_to_half(v)), v, std::abs(v) / 2048 + 1e-7);
}

// Heitz & Neyret's transformation of a real texture: every decorrelated channel is Gaussian (mean
// 1/2, deviation 1/6), the basis is orthonormal, and the level-0 look-up table takes every texel's
// Gaussian value back to (almost) its colour.
TEST(ExemplarSurface, GaussianizedChannelsAreGaussianAndTheLookUpTableTakesThemBack) {
  const Image img = test::real_exemplar("gravel").image;
  const ExemplarSurface s = make_exemplar_surface(img, "gravel");
  const FloatImage& g = s.gaussian[0];
  const std::size_t n = std::size_t(g.width) * std::size_t(g.height);
  for (int k = 0; k < 3; ++k) {
    double sum = 0, sq = 0;
    for (std::size_t i = 0; i < n; ++i) sum += g.texels[4 * i + std::size_t(k)];
    for (std::size_t i = 0; i < n; ++i) sq += std::pow(g.texels[4 * i + std::size_t(k)] - sum / double(n), 2);
    EXPECT_NEAR(sum / double(n), 0.5, 1e-3) << k;
    EXPECT_NEAR(std::sqrt(sq / double(n)), 1.0 / 6, 2e-3) << k;
  }
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      double dot = 0;
      for (int c = 0; c < 3; ++c) dot += double(s.basis[std::size_t(3 * a + c)]) * s.basis[std::size_t(3 * b + c)];
      EXPECT_NEAR(dot, a == b ? 1 : 0, 1e-5);
    }
  std::size_t close = 0;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      float v[3];
      for (int k = 0; k < 3; ++k) {  // the level-0 row of the table, linear between entries
        const float u = std::clamp(g.at(x, y)[k] * kLutWidth - 0.5f, 0.0f, float(kLutWidth - 1));
        const int i = std::min(int(u), kLutWidth - 2);
        v[k] = (1 - (u - i)) * s.lut.at(i, 0)[k] + (u - i) * s.lut.at(i + 1, 0)[k];
      }
      bool ok = true;
      for (int c = 0; c < 3; ++c) {
        const float back = 255 * (s.mean[std::size_t(c)] + s.basis[std::size_t(c)] * v[0] +
                                  s.basis[std::size_t(3 + c)] * v[1] + s.basis[std::size_t(6 + c)] * v[2]);
        ok = ok && std::abs(back - img.at(x, y)[c]) <= 4;
      }
      close += ok;
    }
  EXPECT_GT(double(close), 0.97 * double(n));
  // Coarser levels' tables are flatter: prefiltering pulls them towards the mean.
  const int last = s.lut.height - 1;
  EXPECT_LT(std::abs(s.lut.at(kLutWidth - 1, last)[0] - s.lut.at(0, last)[0]),
            std::abs(s.lut.at(kLutWidth - 1, 0)[0] - s.lut.at(0, 0)[0]));
}

std::pair<double, double> mean_and_deviation(const Image& img) {
  double sum = 0, sq = 0;
  const std::size_t n = std::size_t(img.width) * std::size_t(img.height);
  for (std::size_t i = 0; i < n; ++i) sum += img.pixels[4 * i];
  for (std::size_t i = 0; i < n; ++i) sq += std::pow(img.pixels[4 * i] - sum / double(n), 2);
  return {sum / double(n), std::sqrt(sq / double(n))};
}

// The claim of Heitz & Neyret 2018: blending preserves the histogram, here its mean and contrast,
// on a flat render at the exemplar's scale; hex tiling's sharp blend keeps most of the contrast too.
TEST(Baselines, HistogramPreservingBlendingKeepsTheExemplarsMeanAndContrast) {
  const Image img = test::real_exemplar("grass").image;
  const ExemplarSurface s = make_exemplar_surface(img, "grass");
  const auto [mean, deviation] = mean_and_deviation(img);
  const View view{512, 512, 1, 1000, -3000, 0};
  const auto [hpn_mean, hpn_dev] =
      mean_and_deviation(render_cpu({RenderMethod::Hpn, nullptr, &s}, view, {HashKind::LongPeriod, 2, 2}));
  const auto [hex_mean, hex_dev] =
      mean_and_deviation(render_cpu({RenderMethod::Hex, nullptr, &s}, view, {HashKind::LongPeriod, 2, 2}));
  EXPECT_NEAR(hpn_mean, mean, 3);
  EXPECT_NEAR(hpn_dev / deviation, 1.0, 0.08);
  EXPECT_NEAR(hex_mean, mean, 6);
  EXPECT_GT(hex_dev / deviation, 0.8);
  RecordProperty("hpn_deviation_ratio", std::to_string(hpn_dev / deviation));
  RecordProperty("hex_deviation_ratio", std::to_string(hex_dev / deviation));
}

TEST(Baselines, AnExemplarTooSmallForItsCellsIsAnInputError) {
  const Image img = test::synthetic_image(40, 40);
  EXPECT_NO_THROW(make_exemplar_surface(img, "small"));  // cell 11, patches of radius 15 fit
  EXPECT_THROW(make_exemplar_surface(img, "small", 17), InputError);
  EXPECT_THROW(make_exemplar_surface(test::synthetic_image(12, 12), "tiny"), InputError);
}

}  // namespace
}  // namespace tilekit
