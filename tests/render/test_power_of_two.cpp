// Atlases resampled to a power of two (texture_atlas.hpp's resample_to_power_of_two, `texture
// atlas --power-of-two`): C = 3's 9 x 9 tiles of 16 px (144 texels) become 128 x 128, tiles of
// 14.2 texels; the files read back; the CPU reference and the GLSL sampler (level of detail from
// atlas_texels_per_tile) agree within 2/255 on a tilted view with 16 anisotropic taps; and the
// render stays close to the render of the atlas as laid out.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "../cli_runner.hpp"
#include "../texture/texture_fixtures.hpp"
#include "atlas/lookup.hpp"
#include "gl_test.hpp"
#include "render/cpu_renderer.hpp"
#include "render/gl_renderer.hpp"
#include "texture/texture_atlas.hpp"

namespace tilekit {
namespace {

TextureAtlas c3_atlas() {
  const AtlasLookup lookup = atlas_lookup(TileKind::Corner, 3);
  std::vector<Image> tiles;
  for (std::size_t i = 0; i < lookup.cells.size(); ++i) tiles.push_back(test::synthetic_image(16, 16, i + 7));
  return build_texture_atlas(lookup, tiles);
}

int largest_difference(const Image& a, const Image& b) {
  int worst = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    worst = std::max(worst, std::abs(int(a.pixels[i]) - int(b.pixels[i])));
  return worst;
}

TEST(PowerOfTwoAtlas, ResampledToTheNearestPowerOfTwoAndReadBack) {
  const TextureAtlas laid_out = c3_atlas();
  ASSERT_EQ(laid_out.levels[0].width, 144);
  const TextureAtlas a = resample_to_power_of_two(laid_out);
  EXPECT_EQ(a.levels[0].width, 128);
  EXPECT_EQ(a.levels[0].height, 128);
  EXPECT_EQ(a.levels.size(), 8u);  // 128 .. 1
  EXPECT_EQ(a.tile_px, 16);        // the views' unit
  EXPECT_FLOAT_EQ(atlas_texels_per_tile(a), 128.0f / 9.0f);
  EXPECT_FLOAT_EQ(atlas_texels_per_tile(laid_out), 16.0f);
  // A constant atlas stays constant (the weights of every output texel sum to one).
  TextureAtlas flat = laid_out;
  for (std::size_t i = 0; i < flat.levels[0].pixels.size(); ++i) flat.levels[0].pixels[i] = std::uint8_t(90 + i % 4);
  const TextureAtlas flat2 = resample_to_power_of_two(flat);
  for (std::size_t i = 0; i < flat2.levels[0].pixels.size(); ++i) ASSERT_EQ(flat2.levels[0].pixels[i], 90 + i % 4);
  test::TempDir d;
  write_texture_atlas(a, d / "atlas.png", "// glsl\n");
  const TextureAtlas back = read_texture_atlas(d / "atlas.png");
  EXPECT_EQ(back.levels[0].width, 128);
  EXPECT_EQ(back.tile_px, 16);
  EXPECT_EQ(back.levels.back().pixels, a.levels.back().pixels);
  EXPECT_EQ(resample_to_power_of_two(a).levels[0].pixels, a.levels[0].pixels);  // already a power of two: as is
}

TEST(PowerOfTwoAtlas, CpuAndGlslAgreeAndTheRenderStaysCloseToTheLaidOutAtlas) {
  const TextureAtlas laid_out = c3_atlas(), a = resample_to_power_of_two(laid_out);
  const View tilted{160, 96, 0.8, 21.5, -13, 2.5};
  const RenderOptions o{HashKind::LongPeriod, 3, 2, false, 16};
  const Image cpu = render_cpu(a, tilted, o);
  Image gl;
  SKIP_WITHOUT_EGL(gl = render_glsl(a, tilted, o));
  EXPECT_LE(largest_difference(cpu, gl), 2);
  // The same flat view of both atlases: resampling blurs a little, it moves nothing.
  const View flat{96, 96, 1.0, 40, 24, 0};
  const Image x = render_cpu(a, flat, o), y = render_cpu(laid_out, flat, o);
  double sum = 0;
  for (std::size_t i = 0; i < x.pixels.size(); ++i) sum += std::abs(int(x.pixels[i]) - int(y.pixels[i]));
  EXPECT_LT(sum / double(x.pixels.size()), 12.0);
}

}  // namespace
}  // namespace tilekit
