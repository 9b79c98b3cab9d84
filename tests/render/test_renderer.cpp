// The CPU reference renderer and the GLSL sampler through headless EGL (surfaceless Mesa,
// llvmpipe): the same hash bit for bit, the same tiles, the same pixels within 1/255 at mip 0
// and 2/255 over all levels.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>

#include "../cli_runner.hpp"
#include "../texture/texture_fixtures.hpp"
#include "gl_test.hpp"
#include "render/cpu_renderer.hpp"
#include "render/gl_renderer.hpp"
#include "render/glsl_sampler.hpp"
#include "texture/mipmap.hpp"
#include "texture/seam_metrics.hpp"

namespace tilekit {
namespace {

int sh(const std::string& cmd) {
  return std::system(cmd.c_str());
}

TEST(CpuRenderer, ScaleOneAtTexelCentresEqualsTheStitchedTiling) {
  const TextureAtlas& atlas = test::grass_atlas(TileKind::Corner);
  const View v{320, 192, 1.0, 128, 64, 0};  // origin at texel (128, 64): tile (2, 1)
  for (int threads : {1, 2}) {
    const Image img = render_cpu(atlas, v, {HashKind::LongPeriod, 9, threads, false});
    const Tiling t = DirectCornerTiling(2, HashKind::LongPeriod, 9).generate(3, 5, 2, 1);
    const Image truth = stitch_tiles(test::grass_tiles(TileKind::Corner), t);
    EXPECT_EQ(img.pixels, truth.pixels) << threads << " threads";
  }
}

// Trilinear sampling (GL_LINEAR_MIPMAP_LINEAR, as sample_trilinear) of the mip chain of a
// stitched tiling at level-0 texel (u, v) of that image: the ground truth of a render. The atlas
// is sRGB: R, G and B are filtered in linear light and encoded back, as an SRGB8_ALPHA8 texture.
std::array<double, 4> sample_chain(const std::vector<Image>& chain, double u, double v, float lambda) {
  std::array<double, 4> acc{0, 0, 0, 0};
  const auto texel = [](const Image& img, int i, int j, int c) {
    const double t = img.at(i, j)[c];
    return c < 3 ? srgb_to_linear(t / 255.0) * 255.0 : t;
  };
  auto level = [&](int k, double w) {
    const Image& img = chain[std::size_t(k)];
    const double x = u / double(1 << k) - 0.5, y = v / double(1 << k) - 0.5;
    const int i = int(std::floor(x)), j = int(std::floor(y));
    const double a = x - i, b = y - j;
    for (int c = 0; c < 4; ++c)
      acc[std::size_t(c)] += w * ((1 - a) * (1 - b) * texel(img, i, j, c) + a * (1 - b) * texel(img, i + 1, j, c) +
                                  (1 - a) * b * texel(img, i, j + 1, c) + a * b * texel(img, i + 1, j + 1, c));
  };
  if (!(lambda > 0)) {
    level(0, 1);
  } else {
    const int d = int(std::floor(lambda));
    level(d, 1 - (lambda - float(d)));
    level(d + 1, lambda - float(d));
  }
  for (int c = 0; c < 3; ++c)
    acc[std::size_t(c)] = linear_to_srgb(std::clamp(acc[std::size_t(c)] / 255.0, 0.0, 1.0)) * 255.0;
  return acc;
}

// Renders of a packed atlas filter across tile borders as the tiling itself does: bilinear at
// mip 0 (magnified, off the texel centres) and trilinear between levels 1 and 2 (minified), within
// 1/255 of the same samples of a stitched tiling's mip chain. The same tiles in a random
// arrangement of the atlas (not a packing) read wrong neighbours at the borders.
TEST(CpuRenderer, PackedAtlasFiltersAcrossTileBordersLikeTheTilingAndARandomArrangementDoesNot) {
  const TextureTileSet& tiles = test::grass_tiles(TileKind::Corner);
  const TextureAtlas& atlas = test::grass_atlas(TileKind::Corner);
  const AtlasLookup shuffled = test::shuffled_lookup(atlas.lookup, 4);
  const TextureAtlas random = build_texture_atlas(shuffled, tiles.tiles);
  const int n = tiles.tile_px, first = 1, count = 18;  // the stitched window: tiles 1..18 each way
  const Tiling t = DirectCornerTiling(2, HashKind::LongPeriod, 9).generate(count, count, first, first);
  const std::vector<Image> chain = mip_chain(stitch_tiles(tiles, t), MipEdge::Clamp);
  const RenderOptions o{HashKind::LongPeriod, 9, 2, false};
  for (double scale : {0.9, 2.6}) {  // lambda = log2(scale): mip 0 bilinear; levels 1 and 2
    const View v{300, 300, scale, 200.3, 150.7, 0};
    const Image packed = render_cpu(atlas, v, o), wrong = render_cpu(random, v, o);
    const ViewRows vr = view_rows(v, n);
    int max_packed = 0, max_random = 0;
    std::size_t differ_random = 0;
    for (int y = 0; y < v.height; ++y) {
      const ViewRow& r = vr.rows[std::size_t(y)];
      const double tv = r.tile_v + double(r.frac_v) / kFracOne;
      for (int x = 0; x < v.width; ++x) {
        const double tu = r.tile_u0 + (double(r.frac_u0) + double(x) * r.step_u) / kFracOne;
        ASSERT_TRUE(tu > first + 0.3 && tu < first + count - 0.3 && tv > first + 0.3 && tv < first + count - 0.3);
        const auto truth = sample_chain(chain, (tu - first) * n, (tv - first) * n, view_lod(r, vr.dudy_step, x, n));
        int dp = 0, dr = 0;
        for (int c = 0; c < 3; ++c) {
          dp = std::max(dp, int(std::abs(packed.at(x, y)[c] - truth[std::size_t(c)]) + 0.5));
          dr = std::max(dr, int(std::abs(wrong.at(x, y)[c] - truth[std::size_t(c)]) + 0.5));
        }
        max_packed = std::max(max_packed, dp);
        max_random = std::max(max_random, dr);
        differ_random += dr > 2;
      }
    }
    EXPECT_LE(max_packed, 1) << "scale " << scale;
    EXPECT_GT(max_random, 10) << "scale " << scale;
    EXPECT_GT(differ_random, std::size_t(v.width) * std::size_t(v.height) / 100) << "scale " << scale;
  }
}

TEST(CpuRenderer, BadViewsAreInputErrors) {
  const TextureAtlas& atlas = test::grass_atlas(TileKind::Corner);
  EXPECT_THROW(render_cpu(atlas, View{0, 10, 1, 0, 0, 0}, {}), InputError);
  EXPECT_THROW(render_cpu(atlas, View{10, 10, -1, 0, 0, 0}, {}), InputError);
  EXPECT_THROW(render_cpu(atlas, View{10, 10, 200, 0, 0, 0}, {}), InputError);  // 3 tiles per pixel
  EXPECT_THROW(render_cpu(atlas, View{10, 10, 1, 1e12, 0, 0}, {}), InputError);
}

TEST(GlslSampler, CompilesAsAnEs300FragmentShaderForEveryKindPositionAndMethod) {
  ASSERT_EQ(sh("command -v glslangValidator >/dev/null"), 0) << "glslangValidator missing: run scripts/setup.sh";
  test::TempDir d;
  for (auto [kind, c] :
       {std::pair{TileKind::Corner, 2u}, std::pair{TileKind::Corner, 3u}, std::pair{TileKind::Wang, 2u}})
    for (HashKind h : {HashKind::Permutation, HashKind::LongPeriod})
      for (GlslMode mode : {GlslMode::Texture, GlslMode::FlatTexture, GlslMode::AtlasCell}) {
        const TextureAtlas a{atlas_lookup(kind, c), 64, {}, ""};
        test::write_text(d / "t.frag", glsl_fragment_shader(RenderSource{RenderMethod::Tiles, &a, nullptr},
                                                            RenderOptions{h, 3, 1, false}, mode));
        EXPECT_EQ(sh("glslangValidator " + (d / "t.frag") + " > " + (d / "log.txt") + " 2>&1"), 0)
            << test::slurp(d / "log.txt");
      }
  const ExemplarSurface ex = make_exemplar_surface(test::synthetic_image(96, 96), "synthetic");
  for (RenderMethod m : {RenderMethod::Hex, RenderMethod::Hpn}) {
    test::write_text(d / "t.frag", glsl_fragment_shader(RenderSource{m, nullptr, &ex}, {}, GlslMode::Texture));
    EXPECT_EQ(sh("glslangValidator " + (d / "t.frag") + " > " + (d / "log.txt") + " 2>&1"), 0)
        << test::slurp(d / "log.txt");
  }
}

// The generated hash (tables inline, as in atlas.glsl and the lookup snippet), run through EGL:
// the C++ colour at every lattice point of windows far apart, negative coordinates included.
TEST(GlslSampler, LatticeHashIsBitIdenticalToTheCpp) {
  const int w = 300, h = 80;
  for (HashKind hash : {HashKind::Permutation, HashKind::LongPeriod})
    for (TileKind kind : {TileKind::Corner, TileKind::Wang}) {
      const DirectTiling tiling(kind, 2, hash, 77);
      const ColourHash& colour = *tiling.hashes()[0];
      for (auto [ox, oy] : {std::pair{-150, -40}, std::pair{-1000003, 999979}, std::pair{2147400000, -2147400000}}) {
        const std::string shader =
            "#version 300 es\nprecision highp float;\nprecision highp int;\nout vec4 tk_out;\n" +
            direct_tiling_glsl(tiling, GlslTables::Inline) +
            fmt::format(
                "void main() {{\n"
                "  ivec2 p = ivec2(int(gl_FragCoord.x), {} - int(gl_FragCoord.y)) + ivec2({}, {});\n"
                "  tk_out = vec4(float(tk_lattice0(p)) / 255.0, 0.0, 0.0, 1.0);\n"
                "}}\n",
                h - 1, ox, oy);
        Image img;
        SKIP_WITHOUT_EGL(img = run_fragment_shader(shader, w, h));
        int wrong = 0;
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x)
            wrong += img.at(x, y)[0] != colour.colour(std::int64_t(x) + ox, std::int64_t(y) + oy);
        EXPECT_EQ(wrong, 0) << hash_kind_name(hash) << " " << kind_name(kind) << " origin " << ox << "," << oy;
      }
    }
}

// The one direct stochastic tiling four ways on a window: the C++ class (random access and row
// fill), the atlas lookup's CPU reference (virtual_to_atlas), the atlas lookup's GLSL snippet
// (`atlas lookup --format glsl`, tables inline) and the renderer's GLSL (the tiling's look-up
// textures), both run through EGL: the same tile at every (x, y), for closed-form and stored
// packings, corner and Wang, both hashes.
TEST(DirectTiling, CppAtlasLookupAndGlslAgreeTileForTileOnAWindow) {
  const int w = 72, h = 40;
  struct Case {
    TileKind kind;
    std::uint32_t c;
    HashKind hash;
    int ox, oy;
  };
  for (auto [kind, c, hash, ox, oy] : {Case{TileKind::Corner, 3, HashKind::Permutation, -40, -23},
                                       Case{TileKind::Corner, 3, HashKind::LongPeriod, 5003, -70001},
                                       Case{TileKind::Corner, 4, HashKind::LongPeriod, -40, -23},
                                       Case{TileKind::Corner, 4, HashKind::Permutation, 5003, -70001},
                                       Case{TileKind::Wang, 3, HashKind::LongPeriod, -40, -23},
                                       Case{TileKind::Wang, 3, HashKind::Permutation, 5003, -70001}}) {
    const std::string what = fmt::format("{} C={} {} origin {},{}", kind_name(kind), c, hash_kind_name(hash), ox, oy);
    const AtlasLookup lookup = atlas_lookup(kind, c);
    const DirectTiling tiling(kind, c, hash, 11);
    std::vector<TileIndex> truth(std::size_t(w) * h);
    tiling.fill(ox, oy, h, w, truth.data());
    // The lookup snippet: the atlas cell of each tile's centre, as 4 bytes.
    const std::string shader =
        "#version 300 es\nprecision highp float;\nprecision highp int;\nout vec4 tk_out;\n" +
        lookup_glsl(lookup, tiling) +
        fmt::format(
            "void main() {{\n"
            "  ivec2 p = ivec2(int(gl_FragCoord.x), {} - int(gl_FragCoord.y)) + ivec2({}, {});\n"
            "  ivec2 cell = ivec2(floor(tk_atlas_coord(vec2(p) + 0.5) * vec2(TK_COLS, TK_ROWS)));\n"
            "  tk_out = vec4(cell.x & 255, cell.x >> 8, cell.y & 255, cell.y >> 8) / 255.0;\n"
            "}}\n",
            h - 1, ox, oy);
    Image snippet;
    SKIP_WITHOUT_EGL(snippet = run_fragment_shader(shader, w, h));
    // The renderer's sampler (the tiling's look-up textures), atlas cells.
    const TextureAtlas atlas{lookup, 4, mip_chain(Image(lookup.cols * 4, lookup.rows * 4), MipEdge::Wrap), ""};
    GlRenderer r(atlas, View{w, h, 1, 0, 0, 0}, {hash, 11, 1, false}, GlslMode::AtlasCell);
    r.set_origin(ox, oy);
    r.draw();
    const Image cells = r.read();
    int wrong = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const TileIndex t = truth[std::size_t(y) * w + std::size_t(x)];
        const std::uint8_t *p = snippet.at(x, y), *q = cells.at(x, y);
        const auto [s, tt] = virtual_to_atlas(lookup, tiling, ox + x + 0.5, oy + y + 0.5);
        const int col = int(s * lookup.cols), row = int(tt * lookup.rows);
        wrong += tiling.tile(ox + x, oy + y) != t;
        wrong += lookup.cells[std::size_t(row) * std::size_t(lookup.cols) + std::size_t(col)] != t;
        wrong += lookup.cells[std::size_t(p[2] | p[3] << 8) * std::size_t(lookup.cols) + (p[0] | p[1] << 8)] != t;
        wrong += lookup.cells[std::size_t(q[2] | q[3] << 8) * std::size_t(lookup.cols) + (q[0] | q[1] << 8)] != t;
      }
    EXPECT_EQ(wrong, 0) << what;
  }
}

// The renderer's look-up textures at the ends of the int range, where the floored modulo of
// negative coordinates matters: the C++ tiling's tile at every (x, y).
TEST(GlslSampler, TilingTexturesGiveTheCppTilesAtTheEndsOfTheIntRange) {
  const int w = 64, h = 16;
  for (HashKind hash : {HashKind::Permutation, HashKind::LongPeriod})
    for (TileKind kind : {TileKind::Corner, TileKind::Wang}) {
      const AtlasLookup lookup = atlas_lookup(kind, 2);
      const DirectTiling tiling(kind, 2, hash, 5);
      const TextureAtlas atlas{lookup, 4, mip_chain(Image(lookup.cols * 4, lookup.rows * 4), MipEdge::Wrap), ""};
      std::unique_ptr<GlRenderer> r;
      SKIP_WITHOUT_EGL(r = std::make_unique<GlRenderer>(atlas, View{w, h, 1, 0, 0, 0}, RenderOptions{hash, 5, 1, false},
                                                        GlslMode::AtlasCell));
      for (auto [ox, oy] : {std::pair{-2147483647 - 1, 2147483647 - h}, std::pair{2147483647 - w, -2147483647 - 1}}) {
        r->set_origin(ox, oy);
        r->draw();
        const Image cells = r->read();
        int wrong = 0;
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x) {
            const std::uint8_t* q = cells.at(x, y);
            wrong += lookup.cells[std::size_t(q[2]) * std::size_t(lookup.cols) + q[0]] !=
                     tiling.tile(std::int64_t(ox) + x, std::int64_t(oy) + y);
          }
        EXPECT_EQ(wrong, 0) << hash_kind_name(hash) << " " << kind_name(kind) << " origin " << ox << "," << oy;
      }
    }
}

struct Diff {
  int max = 0;
  double mean = 0;
};
Diff diff(const Image& a, const Image& b) {
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
    Image gl_flat, gl_tilted;
    SKIP_WITHOUT_EGL(gl_flat = render_glsl(atlas, flat, o));
    gl_tilted = render_glsl(atlas, tilted, o);
    const Diff d0 = diff(gl_flat, render_cpu(atlas, flat, o)), d1 = diff(gl_tilted, render_cpu(atlas, tilted, o));
    EXPECT_LE(d0.max, 1) << kind_name(kind) << " mip 0, mean " << d0.mean;
    EXPECT_LE(d1.max, 2) << kind_name(kind) << " all levels, mean " << d1.mean;
    RecordProperty(std::string(kind_name(kind)) + "_max_mip0", d0.max);
    RecordProperty(std::string(kind_name(kind)) + "_max_all", d1.max);
  }
}

// A flat view has one footprint at every pixel: the renderer draws it with the level of detail as
// a uniform (GlslMode::FlatTexture), magnified and minified, within what the per-fragment shader
// keeps to the CPU; a tilted view keeps the footprint per fragment.
TEST(GlslSampler, FlatViewsDrawWithTheLevelOfDetailAsAUniformAndEqualTheCpuReference) {
  for (TileKind kind : {TileKind::Corner, TileKind::Wang})
    for (HashKind hash : {HashKind::LongPeriod, HashKind::Permutation})
      for (double scale : {0.9, 2.6, 5.3}) {  // magnified; levels 1-2; levels 2-3
        const TextureAtlas& atlas = test::grass_atlas(kind);
        const RenderOptions o{hash, 3, 2, false};
        const View v{512, 384, scale, 333.3, -1234.6, 0};
        std::unique_ptr<GlRenderer> r;
        SKIP_WITHOUT_EGL(r = std::make_unique<GlRenderer>(atlas, v, o));
        const std::string what = fmt::format("{} {} scale {}", kind_name(kind), hash_kind_name(hash), scale);
        EXPECT_EQ(r->mode(), GlslMode::FlatTexture) << what;
        r->draw();
        const Diff d = diff(r->read(), render_cpu(atlas, v, o));
        EXPECT_LE(d.max, scale < 1 ? 1 : 2) << what << ", mean " << d.mean;
      }
  const TextureAtlas& atlas = test::grass_atlas(TileKind::Corner);
  const RenderOptions o{HashKind::LongPeriod, 3, 2, false};
  const ViewRows tilted = view_rows(View{64, 64, 0.6, 0, 0, 3}, atlas.tile_px);
  EXPECT_FALSE(uniform_footprint(tilted, atlas.tile_px, 16));
  EXPECT_EQ(GlRenderer(atlas, View{64, 64, 0.6, 0, 0, 3}, o).mode(), GlslMode::Texture);
  EXPECT_EQ(GlRenderer(atlas, View{64, 64, 2.0, 0, 0, 0}, o, GlslMode::AtlasCell).mode(), GlslMode::AtlasCell);
}

}  // namespace
}  // namespace tilekit
