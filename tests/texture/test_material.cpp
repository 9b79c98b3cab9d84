// Colour-correct mip chains (linear light, premultiplied alpha, normals as vectors), 16-bit data
// through tiles, atlases and mips, and material sets: every map of a set copied at the texels the
// synthesis recorded (texture/mipmap.hpp, texture/material.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numeric>
#include <set>
#include <string>
#include <vector>

#include "../cli_runner.hpp"
#include "base/random.hpp"
#include "image/image.hpp"
#include "texture/material.hpp"
#include "texture/mipmap.hpp"
#include "texture/seam_metrics.hpp"
#include "texture/texture_atlas.hpp"
#include "texture/tile_synthesis.hpp"
#include "texture_fixtures.hpp"
#include "tiling/direct_tiling.hpp"

namespace tilekit {
namespace {

double mean_channel(const Image& img, int c) {
  double sum = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) sum += img.sample(x, y, c);
  return sum / (double(img.width) * img.height);
}

TEST(ColourMips, OnePixelCheckerAveragesInLinearLight) {
  Image checker(64, 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const std::uint8_t v = (x + y) % 2 ? 255 : 0;
      checker.set(x, y, {v, v, v});
    }
  const auto srgb = mip_chain(checker, MipEdge::Wrap, ColourSpace::Srgb);
  for (std::size_t k = 1; k < srgb.size(); ++k) {
    const double m = mean_channel(srgb[k], 0);
    EXPECT_GE(m, 186) << "level " << k;
    EXPECT_LE(m, 190) << "level " << k;
    EXPECT_EQ(srgb[k].sample(0, 0, 3), 255u);
  }
  // Averaged as stored (the old behaviour, and right for data): 128, so the test can fail.
  EXPECT_NEAR(mean_channel(mip_chain(checker, MipEdge::Wrap, ColourSpace::Linear).back(), 0), 128, 1);
}

TEST(ColourMips, UniformColoursRoundTripExactly) {
  for (int v = 0; v < 256; ++v) {
    const Image flat(4, 4, Rgb{std::uint8_t(v), std::uint8_t(255 - v), std::uint8_t(v / 2)});
    const Image half = downsample(flat, MipEdge::Wrap, ColourSpace::Srgb);
    EXPECT_EQ(half.get(1, 1), (Rgb{std::uint8_t(v), std::uint8_t(255 - v), std::uint8_t(v / 2)})) << v;
  }
}

TEST(ColourMips, PremultipliedAlphaLeavesNoDarkFringe) {
  // Opaque red on the left half, fully transparent black on the right: a straight-alpha average
  // would darken the red where the two meet.
  Image img(32, 32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      std::uint8_t* p = img.at(x, y);
      const bool red = x < 16;
      p[0] = red ? 255 : 0, p[1] = 0, p[2] = 0, p[3] = red ? 255 : 0;
    }
  for (ColourSpace space : {ColourSpace::Srgb, ColourSpace::Linear}) {
    const auto chain = mip_chain(img, MipEdge::Clamp, space);
    int partial = 0;
    for (std::size_t k = 1; k < chain.size(); ++k)
      for (int y = 0; y < chain[k].height; ++y)
        for (int x = 0; x < chain[k].width; ++x) {
          const std::uint8_t* p = chain[k].at(x, y);
          if (p[3] == 0) continue;
          partial += p[3] < 255;
          EXPECT_GE(p[0], 254) << "level " << k << " (" << x << ", " << y << ") alpha " << int(p[3]);
          EXPECT_EQ(p[1], 0);
        }
    EXPECT_GT(partial, 0);  // the edge was averaged
  }
}

// A bumpy normal map: normals tilted up to ~60 degrees, changing every texel.
Image bumpy_normals(int side, std::uint64_t seed) {
  Image img(side, side);
  SplitMix64 rng(seed);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const double a = rng.uniform() * 6.283185307, t = rng.uniform() * 1.0;
      const double n[3] = {std::sin(t) * std::cos(a), std::sin(t) * std::sin(a), std::cos(t)};
      std::uint8_t* p = img.at(x, y);
      for (int c = 0; c < 3; ++c) p[c] = std::uint8_t(std::lround((n[c] + 1) / 2 * 255));
    }
  return img;
}

double mean_normal_length(const Image& img) {
  double sum = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      double len = 0;
      for (int c = 0; c < 3; ++c) {
        const double v = 2.0 * img.sample(x, y, c) / img.max_value() - 1;
        len += v * v;
      }
      sum += std::sqrt(len);
    }
  return sum / (double(img.width) * img.height);
}

TEST(ColourMips, NormalMapsAreAveragedAsVectorsAndRenormalised) {
  const Image normals = bumpy_normals(64, 9);
  const auto chain = mip_chain(normals, MipEdge::Wrap, ColourSpace::Normal);
  for (std::size_t k = 0; k < chain.size(); ++k) EXPECT_GE(mean_normal_length(chain[k]), 0.99) << "level " << k;
  // Plain averages shorten them (the test can fail), and that lost length is what Toksvig folds
  // into roughness.
  const auto plain = mip_chain(normals, MipEdge::Wrap, ColourSpace::Linear);
  EXPECT_LT(mean_normal_length(plain[3]), 0.95);
  const std::vector<double> len = normal_lengths(normals, MipEdge::Wrap);
  ASSERT_EQ(len.size(), 32u * 32u);
  const double mean_len = std::accumulate(len.begin(), len.end(), 0.0) / double(len.size());
  EXPECT_LT(mean_len, 0.97);
  EXPECT_GT(toksvig_roughness(0.3, mean_len), 0.3);
  EXPECT_DOUBLE_EQ(toksvig_roughness(0.3, 1.0), 0.3);
}

// A 16-bit grey ramp with values 1000..3000 of 65535 (what the height map collapsed to 6
// grey levels at 8 bits), as RGBA.
Image ramp16(int w, int h) {
  Image img = Image(w, h).to_depth(16);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const unsigned v = 1000 + unsigned((x + y * w) * 2000 / (w * h - 1));
      for (int c = 0; c < 3; ++c) img.set_sample(x, y, c, v);
    }
  return img;
}

TEST(SixteenBit, PngKeepsSixteenBitsWhenAsked) {
  const test::TempDir tmp;  // a fresh folder, removed however the test ends
  const std::filesystem::path dir = tmp.path;
  const Image ramp = ramp16(40, 30);
  write_png((dir / "ramp.png").string(), ramp);
  const Image back = read_image((dir / "ramp.png").string(), 4, true);
  EXPECT_EQ(back.depth, 16);
  EXPECT_EQ(back.pixels, ramp.pixels);
  const Image eight = read_image((dir / "ramp.png").string());  // the default: rounded to 8 bits
  EXPECT_EQ(eight.depth, 8);
  EXPECT_NEAR(eight.sample(0, 0, 0), 1000.0 / 257.0, 1.0);
}

// Material synthesis as `texture tiles --map` runs it (cli/cmd_texture.cpp): the albedo with every
// map's term in the seam costs, the synthesis recording its texels, each map copied at them.
struct MaterialResult {
  TextureTileSet set;
  Image albedo_sampled;
};
MaterialResult material_tiles(const Image& albedo, std::vector<MaterialMap>& maps, const SynthesisOptions& o0) {
  SynthesisOptions o = o0;
  o.record_coords = true;
  o.keep_period = false;  // the texels as they are: no resampling to whole periods
  resize_maps(maps, albedo.width, albedo.height, false);
  o.cost_maps = seam_cost_maps(maps);
  MaterialResult r;
  r.set = synthesize_tiles(exemplar_from_image(albedo, "albedo"), o);
  r.albedo_sampled = map_as_sampled(albedo, false, r.set.perspective, r.set.exemplar_scale);
  r.set.tiles = transfer_tiles(r.set.coords, r.set.tile_px, r.albedo_sampled);
  return r;
}

TEST(MaterialSet, EveryMapEqualsItsSourceAtTheRecordedCoordinate) {
  const Image albedo = test::synthetic_image(160, 160, 4);
  // A coordinate-encoded map (16-bit: R = x, G = y) and a normal map of another surface.
  Image encoded = Image(160, 160).to_depth(16);
  for (int y = 0; y < 160; ++y)
    for (int x = 0; x < 160; ++x) encoded.set_sample(x, y, 0, unsigned(x)), encoded.set_sample(x, y, 1, unsigned(y));
  std::vector<MaterialMap> maps(2);
  maps[0].name = "where", maps[0].space = ColourSpace::Linear, maps[0].image = encoded;
  maps[1].name = "normal", maps[1].space = ColourSpace::Normal, maps[1].image = bumpy_normals(160, 3);
  for (TileKind kind : {TileKind::Corner, TileKind::Wang}) {
    const MaterialResult r = material_tiles(albedo, maps, test::small_options(kind, 2, 32));
    ASSERT_EQ(r.set.coords.size(), r.set.tiles.size());
    const std::vector<Image> where = transfer_tiles(r.set.coords, 32, maps[0].image);
    const std::vector<Image> normal = transfer_tiles(r.set.coords, 32, maps[1].image);
    std::set<std::uint32_t> distinct;
    for (std::size_t t = 0; t < r.set.tiles.size(); ++t)
      for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
          const std::uint32_t c = r.set.coords[t][std::size_t(y) * 32 + std::size_t(x)];
          const int sx = int(c & 0xffff), sy = int(c >> 16);
          distinct.insert(c);
          ASSERT_EQ(where[t].sample(x, y, 0), unsigned(sx));
          ASSERT_EQ(where[t].sample(x, y, 1), unsigned(sy));
          for (int ch = 0; ch < 4; ++ch) {
            ASSERT_EQ(r.set.tiles[t].sample(x, y, ch), albedo.sample(sx, sy, ch)) << "tile " << t;
            ASSERT_EQ(normal[t].sample(x, y, ch), maps[1].image.sample(sx, sy, ch)) << "tile " << t;
          }
        }
    EXPECT_GT(distinct.size(), 16u * 32u * 32u / 4);  // the tiles copy many texels, not a few
    // The coordinates survive their own files (16-bit tiles) for `texture transfer`.
    EXPECT_EQ(coords_from_tiles(coordinate_tiles(r.set.coords, 32)), r.set.coords);
  }
}

// The albedo's term of the seam costs is exactly the albedo-only cost: a map of weight 0 changes
// no byte of the tiles (the old feature image, three principal components in 8 bits, did).
TEST(MaterialCosts, AMapOfWeightZeroLeavesTheAlbedoOnlyTilesUnchanged) {
  const Image albedo = test::synthetic_image(160, 160, 4);
  SynthesisOptions o = test::small_options(TileKind::Corner, 2, 32);
  o.record_coords = true;
  o.keep_period = false;
  const TextureTileSet plain = synthesize_tiles(exemplar_from_image(albedo, "albedo"), o);
  o.cost_maps = {{bumpy_normals(160, 3), true, 0.0}};
  const TextureTileSet zero = synthesize_tiles(exemplar_from_image(albedo, "albedo"), o);
  ASSERT_EQ(plain.tiles.size(), zero.tiles.size());
  for (std::size_t t = 0; t < plain.tiles.size(); ++t) EXPECT_EQ(plain.tiles[t].pixels, zero.tiles[t].pixels) << t;
  EXPECT_EQ(plain.coords, zero.coords);
  o.cost_maps[0].weight = 1;  // and a weight that counts changes them (so the test can fail)
  const TextureTileSet one = synthesize_tiles(exemplar_from_image(albedo, "albedo"), o);
  EXPECT_NE(plain.coords, one.coords);
}

// A relief the albedo does not show (a normal map of another surface): with its term in the
// costs, the cuts show less in the normal map, for corner and Wang tiles alike (same seeds).
TEST(MaterialCosts, NormalMapCutsShowLessWhenTheNormalsAreInTheCost) {
  const Image albedo = test::synthetic_image(192, 192, 4);
  const Image normals = normal_map_from_height(test::synthetic_image(192, 192, 11), 6.0, false);
  for (TileKind kind : {TileKind::Corner, TileKind::Wang}) {
    SynthesisOptions o = test::small_options(kind, 2, 32);
    o.record_coords = true;
    o.keep_period = false;
    double ratio[2] = {0, 0};
    for (int all = 0; all < 2; ++all) {
      if (all) o.cost_maps = {{normals, true, 1.0}};
      TextureTileSet s = synthesize_tiles(exemplar_from_image(albedo, "albedo"), o);
      s.tiles = transfer_tiles(s.coords, s.tile_px, normals);
      const Tiling t = kind == TileKind::Corner ? DirectCornerTiling(2, HashKind::LongPeriod, 1).generate(12, 12)
                                                : DirectWangTiling(2, 2, HashKind::LongPeriod, 1).generate(12, 12);
      std::vector<std::uint32_t> sources;
      const Image window = stitch_tiles(s, t, &sources);
      ratio[all] = seam_statistics(window, s.tile_px, &sources).cut_ratio;
    }
    EXPECT_LT(ratio[1], 0.95 * ratio[0]) << (kind == TileKind::Corner ? "corner" : "wang") << ": albedo-only "
                                         << ratio[0] << ", with the normals " << ratio[1];
  }
}

// Toksvig in the atlas (texture/mipmap.hpp, toksvig_chain): where the normals under a texel
// disagree, the roughness mips widen; where they agree, the roughness is a plain average.
TEST(ColourMips, ToksvigWidensRoughnessWhereTheNormalsDisagree) {
  const Image rough(64, 64, Rgb{77, 77, 77});  // roughness 0.3
  const Image flat(64, 64, Rgb{128, 128, 255});
  const auto flat_chain = toksvig_chain(rough, mip_chain(flat, MipEdge::Wrap, ColourSpace::Normal), MipEdge::Wrap);
  ASSERT_EQ(flat_chain.size(), 7u);
  for (const Image& level : flat_chain) EXPECT_NEAR(mean_channel(level, 0), 77, 0.5);
  const Image bumpy = bumpy_normals(64, 9);
  const auto chain = toksvig_chain(rough, mip_chain(bumpy, MipEdge::Wrap, ColourSpace::Normal), MipEdge::Wrap);
  ASSERT_EQ(chain.size(), 7u);
  EXPECT_EQ(chain[0].pixels, rough.pixels);
  for (std::size_t k = 1; k < chain.size(); ++k) {
    // level 1 widens (the random normals disagree), and the deeper levels keep it (a plain average
    // of the widened level, widened again where the renormalised normals still disagree)
    EXPECT_GT(mean_channel(chain[k], 0), 77 + 40) << "level " << k;
    // the first step by the formula: alpha'^2 = alpha^2 + (1 - |n|) / |n|
    if (k == 1) {
      const std::vector<double> len = normal_lengths(bumpy, MipEdge::Wrap);
      EXPECT_NEAR(chain[1].sample(3, 5, 0) / 255.0, toksvig_roughness(77 / 255.0, len[5 * 32 + 3]), 1.0 / 255);
    }
    EXPECT_EQ(chain[k].sample(0, 0, 3), 255u);
  }
  EXPECT_TRUE(
      toksvig_chain(Image(32, 32), mip_chain(bumpy, MipEdge::Wrap, ColourSpace::Normal), MipEdge::Wrap).empty());
}

TEST(MaterialSet, SixteenBitRampSurvivesTilesAtlasAndMips) {
  const Image albedo = test::synthetic_image(128, 128, 6);
  std::vector<MaterialMap> maps(1);
  maps[0].name = "height", maps[0].space = ColourSpace::Linear, maps[0].image = ramp16(128, 128);
  const MaterialResult r = material_tiles(albedo, maps, test::small_options(TileKind::Corner, 2, 32));
  const std::vector<Image> tiles = transfer_tiles(r.set.coords, 32, maps[0].image);
  const TextureAtlas atlas = build_texture_atlas(atlas_lookup(TileKind::Corner, 2), tiles, ColourSpace::Linear);
  ASSERT_EQ(atlas.levels[0].depth, 16);
  // Level 0: every texel a copy, exact (well within 1/65535).
  for (int row = 0; row < atlas.lookup.rows; ++row)
    for (int col = 0; col < atlas.lookup.cols; ++col) {
      const std::size_t t = atlas.lookup.cells[std::size_t(row) * std::size_t(atlas.lookup.cols) + std::size_t(col)];
      for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
          const std::uint32_t c = r.set.coords[t][std::size_t(y) * 32 + std::size_t(x)];
          ASSERT_EQ(atlas.levels[0].sample(col * 32 + x, row * 32 + y, 0),
                    maps[0].image.sample(int(c & 0xffff), int(c >> 16), 0));
        }
    }
  // The mips stay 16-bit and keep the fine steps (an 8-bit chain would hold at most 9 values in
  // 1000..3000).
  for (const Image& level : atlas.levels) EXPECT_EQ(level.depth, 16);
  std::set<unsigned> values;
  for (int y = 0; y < atlas.levels[1].height; ++y)
    for (int x = 0; x < atlas.levels[1].width; ++x) values.insert(atlas.levels[1].sample(x, y, 0));
  EXPECT_GT(values.size(), 200u);
  EXPECT_GE(*values.begin(), 1000u);
  EXPECT_LE(*values.rbegin(), 3000u);
}

}  // namespace
}  // namespace tilekit
