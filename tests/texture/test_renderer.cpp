// The CPU reference renderer and the GLSL sampler through headless EGL (surfaceless Mesa,
// llvmpipe): the same hash bit for bit, the same tiles, the same pixels within 1/255 at mip 0
// and 2/255 over all levels.
#include <gtest/gtest.h>

#include "../cli_runner.hpp"
#include "texture/cpu_renderer.hpp"
#include "texture/gl_renderer.hpp"
#include "texture/glsl_sampler.hpp"
#include "texture/seam_metrics.hpp"
#include "texture_fixtures.hpp"

namespace tilekit {
namespace {

int sh(const std::string& cmd) {
  return std::system(cmd.c_str());
}

TEST(CpuRenderer, ScaleOneAtTexelCentresEqualsTheStitchedTiling) {
  const TextureAtlas& atlas = test::grass_atlas(TileKind::Corner);
  const View v{320, 192, 1.0, 128, 64, 0};  // origin at texel (128, 64): tile (2, 1)
  for (int threads : {1, 2}) {
    const RgbaImage img = render_cpu(atlas, v, {HashKind::LongPeriod, 9, threads, false});
    const Tiling t = DirectCornerTiling(2, HashKind::LongPeriod, 9).generate(3, 5, 2, 1);
    const RgbaImage truth = stitch_tiles(test::grass_tiles(TileKind::Corner), t);
    EXPECT_EQ(img.pixels, truth.pixels) << threads << " threads";
  }
}

TEST(CpuRenderer, BadViewsAreInputErrors) {
  const TextureAtlas& atlas = test::grass_atlas(TileKind::Corner);
  EXPECT_THROW(render_cpu(atlas, View{0, 10, 1, 0, 0, 0}, {}), InputError);
  EXPECT_THROW(render_cpu(atlas, View{10, 10, -1, 0, 0, 0}, {}), InputError);
  EXPECT_THROW(render_cpu(atlas, View{10, 10, 200, 0, 0, 0}, {}), InputError);  // 3 tiles per pixel
  EXPECT_THROW(render_cpu(atlas, View{10, 10, 1, 1e12, 0, 0}, {}), InputError);
}

TEST(GlslSampler, CompilesAsAnEs300FragmentShaderForEveryKindAndPosition) {
  ASSERT_EQ(sh("command -v glslangValidator >/dev/null"), 0) << "glslangValidator missing: run scripts/setup.sh";
  test::TempDir d;
  for (auto [kind, c] :
       {std::pair{TileKind::Corner, 2u}, std::pair{TileKind::Corner, 3u}, std::pair{TileKind::Wang, 2u}})
    for (HashKind h : {HashKind::Permutation, HashKind::LongPeriod})
      for (GlslMode mode : {GlslMode::Texture, GlslMode::LatticeColour, GlslMode::TileIndex}) {
        const AtlasLookup l = atlas_lookup(kind, c, {});
        test::write_text(d / "t.frag", glsl_fragment_shader(l, 64, VirtualTiling(kind, c, h, 3), mode));
        EXPECT_EQ(sh("glslangValidator " + (d / "t.frag") + " > " + (d / "log.txt") + " 2>&1"), 0)
            << test::slurp(d / "log.txt");
      }
}

// The tests below need an EGL display; where none can be made they are skipped with the reason.
#define SKIP_WITHOUT_EGL(statement)                 \
  try {                                             \
    statement;                                      \
  } catch (const GlUnavailable& e) {                \
    GTEST_SKIP() << "no EGL context: " << e.what(); \
  }

TEST(GlslSampler, LatticeHashIsBitIdenticalToTheCpp) {
  for (HashKind h : {HashKind::Permutation, HashKind::LongPeriod})
    for (TileKind kind : {TileKind::Corner, TileKind::Wang}) {
      const TextureAtlas& atlas = test::grass_atlas(kind);
      const RenderOptions o{h, 77, 1, false};
      std::unique_ptr<GlRenderer> r;
      SKIP_WITHOUT_EGL(r = std::make_unique<GlRenderer>(atlas, View{300, 80, 1, 0, 0, 0}, o, GlslMode::LatticeColour));
      const VirtualTiling tiling(kind, 2, h, 77);
      const ColourHash& hash = *tiling.hashes()[0];
      for (auto [ox, oy] : {std::pair{-150, -40}, std::pair{-1000003, 999979}, std::pair{2147400000, -2147400000}}) {
        r->set_origin(ox, oy);
        r->draw();
        const RgbaImage img = r->read();
        int wrong = 0;
        for (int y = 0; y < img.height; ++y)
          for (int x = 0; x < img.width; ++x)
            wrong += img.at(x, y)[0] != hash.colour(std::int64_t(x) + ox, std::int64_t(y) + oy);
        EXPECT_EQ(wrong, 0) << hash_kind_name(h) << " " << kind_name(kind) << " origin " << ox << "," << oy;
      }
    }
}

TEST(GlslSampler, VirtualTilesEqualTheCppDirectTiling) {
  for (TileKind kind : {TileKind::Corner, TileKind::Wang}) {
    const TextureAtlas& atlas = test::grass_atlas(kind);
    const RenderOptions o{HashKind::LongPeriod, 5, 1, false};
    std::unique_ptr<GlRenderer> r;
    SKIP_WITHOUT_EGL(r = std::make_unique<GlRenderer>(atlas, View{200, 100, 1, 0, 0, 0}, o, GlslMode::TileIndex));
    r->set_origin(-100, -37);
    r->draw();
    const RgbaImage img = r->read();
    const VirtualTiling tiling(kind, 2, HashKind::LongPeriod, 5);
    int wrong = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const std::uint8_t* p = img.at(x, y);
        wrong += TileIndex(p[0] | p[1] << 8 | p[2] << 16 | p[3] << 24) != tiling.tile(x - 100, y - 37);
      }
    EXPECT_EQ(wrong, 0) << kind_name(kind);
  }
}

struct Diff {
  int max = 0;
  double mean = 0;
};
Diff diff(const RgbaImage& a, const RgbaImage& b) {
  Diff d;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const int v = std::abs(int(a.pixels[i]) - int(b.pixels[i]));
    d.max = std::max(d.max, v);
    d.mean += v;
  }
  d.mean /= double(a.pixels.size());
  return d;
}

TEST(GlslSampler, A1024SquareRenderEqualsTheCpuReferenceWithinOneAtMipZeroAndTwoOverAllLevels) {
  for (TileKind kind : {TileKind::Corner, TileKind::Wang}) {
    const TextureAtlas& atlas = test::grass_atlas(kind);
    const RenderOptions o{HashKind::LongPeriod, 1, 2, false};
    // mip 0: magnified, off the texel centres (bilinear across tile borders); then a tilted view
    // whose level of detail runs from magnification at the bottom to about level 7 at the top
    const View flat{1024, 1024, 0.37, 1000.3, -77.7, 0}, tilted{1024, 1024, 0.6, -5000, 300, 12};
    RgbaImage gl_flat, gl_tilted;
    SKIP_WITHOUT_EGL(gl_flat = render_glsl(atlas, flat, o));
    gl_tilted = render_glsl(atlas, tilted, o);
    const Diff d0 = diff(gl_flat, render_cpu(atlas, flat, o)), d1 = diff(gl_tilted, render_cpu(atlas, tilted, o));
    EXPECT_LE(d0.max, 1) << kind_name(kind) << " mip 0, mean " << d0.mean;
    EXPECT_LE(d1.max, 2) << kind_name(kind) << " all levels, mean " << d1.mean;
    RecordProperty(std::string(kind_name(kind)) + "_max_mip0", d0.max);
    RecordProperty(std::string(kind_name(kind)) + "_max_all", d1.max);
  }
}

}  // namespace
}  // namespace tilekit
