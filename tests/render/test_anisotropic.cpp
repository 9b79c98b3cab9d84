// Anisotropic filtering (render/anisotropic.hpp): the footprint rule, the CPU and GLSL renders of
// every method equal within 2/255 on tilted views, and what it changes (detail along the short
// axis of a tilted view; nothing on a flat one).
#include <gtest/gtest.h>

#include <cmath>

#include "../texture/texture_fixtures.hpp"
#include "gl_test.hpp"
#include "render/anisotropic.hpp"
#include "render/cpu_renderer.hpp"

namespace tilekit {
namespace {

TEST(Anisotropic, FootprintTakesCeilOfTheAxisRatioTapsAtTheLevelOfTheMajorAxisOverTheTaps) {
  Footprint f = anisotropic_footprint(0.01f, 0, 0, 0.01f, 64, 16);  // isotropic: one tap, OpenGL's lambda
  EXPECT_EQ(f.taps, 1);
  EXPECT_FLOAT_EQ(f.lod, std::log2(0.64f));
  f = anisotropic_footprint(0.01f, 0, 0.002f, 0.037f, 64, 16);  // ratio 3.76 along y
  EXPECT_EQ(f.taps, 4);
  EXPECT_NEAR(f.lod, std::log2(64 * std::hypot(0.002, 0.037) / 4), 1e-5);
  EXPECT_EQ(f.axis_u, std::lround(0.002 * 65536));
  EXPECT_EQ(f.axis_v, std::lround(0.037 * 65536));
  EXPECT_EQ(anisotropic_footprint(0.001f, 0, 0, 0.1f, 64, 16).taps, 16);  // ratio 100: capped
  EXPECT_EQ(anisotropic_footprint(0.001f, 0, 0, 0.1f, 64, 4).taps, 4);
  f = anisotropic_footprint(0.001f, 0, 0, 0.1f, 64, 1);  // trilinear: the major axis's level
  EXPECT_EQ(f.taps, 1);
  EXPECT_FLOAT_EQ(f.lod, std::log2(6.4f));
  EXPECT_EQ(anisotropic_footprint(0.02f, 0, 0, 0, 64, 16).taps, 16);  // a degenerate footprint
}

TEST(Anisotropic, TapsAreEvenlySpacedAndSymmetricAboutThePixel) {
  for (std::int32_t a : {0, 1, -7, 65536, -123457, 1 << 24})
    for (int n = 1; n <= 16; ++n) {
      std::int64_t sum = 0;
      for (int i = 0; i < n; ++i) {
        EXPECT_EQ(tap_offset(a, i, n), -tap_offset(a, n - 1 - i, n)) << a << " " << i << "/" << n;
        EXPECT_LE(std::abs(tap_offset(a, i, n) - double(a) * (2 * i + 1 - n) / (2 * n)), 0.5);
        sum += tap_offset(a, i, n);
      }
      EXPECT_EQ(sum, 0);
    }
}

double mean_horizontal_step(const Image& img, int y0, int y1) {
  double sum = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = 1; x < img.width; ++x) sum += std::abs(int(img.at(x, y)[0]) - int(img.at(x - 1, y)[0]));
  return sum / double((y1 - y0) * (img.width - 1));
}

TEST(Anisotropic, KeepsDetailAcrossATiltedViewAndChangesNothingOnAFlatOne) {
  const TextureAtlas& atlas = test::grass_atlas(TileKind::Corner);
  const View flat{256, 128, 1.7, 30, 40, 0}, tilted{256, 256, 0.5, 0, 0, 6};
  EXPECT_EQ(render_cpu(atlas, flat, {HashKind::LongPeriod, 3, 2, false, 16}).pixels,
            render_cpu(atlas, flat, {HashKind::LongPeriod, 3, 2, false, 1}).pixels);
  const Image aniso = render_cpu(atlas, tilted, {HashKind::LongPeriod, 3, 2, false, 16});
  const Image tri = render_cpu(atlas, tilted, {HashKind::LongPeriod, 3, 2, false, 1});
  // Far rows (the top quarter): trilinear filtering blurs across the row to the level of the long
  // axis; anisotropic taps keep the texture's steps.
  const double a = mean_horizontal_step(aniso, 0, 64), t = mean_horizontal_step(tri, 0, 64);
  EXPECT_GT(a, 1.5 * t) << "anisotropic " << a << ", trilinear " << t;
  RecordProperty("top_rows_step_aniso", std::to_string(a));
  RecordProperty("top_rows_step_trilinear", std::to_string(t));
}

// The CPU renderer and the GLSL sampler with 16x anisotropy on a steep tilted view, for the tiles
// of both kinds and both baselines: within 2/255 at every pixel.
TEST(Anisotropic, GlslEqualsTheCpuWithinTwoForEveryMethodOnATiltedView) {
  const ExemplarSurface ex = make_exemplar_surface(test::real_exemplar("grass").image, "grass");
  const View view{256, 160, 0.6, -300, 200, 6};
  struct Case {
    std::string name;
    RenderSource source;
  };
  const std::vector<Case> cases = {
      {"tiles corner", {RenderMethod::Tiles, &test::grass_atlas(TileKind::Corner), nullptr}},
      {"tiles wang", {RenderMethod::Tiles, &test::grass_atlas(TileKind::Wang), nullptr}},
      {"hex", {RenderMethod::Hex, nullptr, &ex}},
      {"hpn", {RenderMethod::Hpn, nullptr, &ex}}};
  for (const Case& c : cases) {
    const RenderOptions o{HashKind::LongPeriod, 4, 2, false, 16};
    EXPECT_GT(mean_fetches(c.source, view, 16), 2.0 * c.source.fetches(1)) << c.name << ": the view is anisotropic";
    Image gl;
    SKIP_WITHOUT_EGL(gl = render_glsl(c.source, view, o));
    const Image cpu = render_cpu(c.source, view, o);
    int worst = 0;
    for (std::size_t i = 0; i < cpu.pixels.size(); ++i)
      worst = std::max(worst, std::abs(int(cpu.pixels[i]) - int(gl.pixels[i])));
    EXPECT_LE(worst, 2) << c.name;
    RecordProperty(c.name + "_max", worst);
  }
}

}  // namespace
}  // namespace tilekit

namespace tilekit {
namespace {

// The hardware filter's footprint (SwiftShader's rule, anisotropic.hpp): by area, N rounded, the
// minor axis' level through the bit-pattern log2.
TEST(HardwareFootprint, AreaRuleRoundedTapsAndTheMinorAxisLevel) {
  // isotropic, 2 texels a pixel: one tap at level 1 (exact: a power of two)
  Footprint f = hardware_footprint(2.0f / 64, 0, 0, 2.0f / 64, 64, 16);
  EXPECT_EQ(f.taps, 1);
  EXPECT_FLOAT_EQ(f.lod, 1.0f);
  // 8 texels along x, 2 along y: anisotropy 4, four taps along x at the level of 2 texels
  f = hardware_footprint(8.0f / 64, 0, 0, 2.0f / 64, 64, 16);
  EXPECT_EQ(f.taps, 4);
  EXPECT_FLOAT_EQ(f.lod, 1.0f);
  EXPECT_EQ(f.axis_u, std::int32_t(std::lround(8.0 / 64 * 65536)));
  EXPECT_EQ(f.axis_v, 0);
  // anisotropy 2.4 rounds to 2 taps (the tap rule, anisotropic_footprint, takes ceil: 3), and
  // the level stays that of the minor axis: log2(2.4 / 2.4) = 0 at 2.4 x 1 texels
  f = hardware_footprint(2.4f / 64, 0, 0, 1.0f / 64, 64, 16);
  EXPECT_EQ(f.taps, 2);
  EXPECT_NEAR(f.lod, 0.0f, 1e-6f);
  EXPECT_EQ(anisotropic_footprint(2.4f / 64, 0, 0, 1.0f / 64, 64, 16).taps, 3);
  // capped at the sampler's anisotropy; a degenerate footprint takes the most
  EXPECT_EQ(hardware_footprint(40.0f / 64, 0, 0, 1.0f / 64, 64, 16).taps, 16);
  EXPECT_EQ(hardware_footprint(4.0f / 64, 0, 4.0f / 64, 0, 64, 8).taps, 8);
  // the bit-pattern log2 is piecewise linear between powers of two: major^2 = 3, 3^2 = 9 reads
  // as 3 + 1/8, a quarter of it 0.78125 (log2 sqrt 3 = 0.7925)
  f = hardware_footprint(std::sqrt(3.0f) / 64, 0, 0, std::sqrt(3.0f) / 64, 64, 1);
  EXPECT_NEAR(f.lod, 0.78125f, 1e-5f);
}

}  // namespace
}  // namespace tilekit
