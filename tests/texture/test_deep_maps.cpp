// 16-bit TIFF and float OpenEXR maps of a material set keep their depth through the tiles (copies
// of the recorded texels), the files the tiles are written as, the atlas and its mips (texture/
// material.hpp, texture/texture_atlas.hpp, texture/mipmap.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "../cli_runner.hpp"
#include "../image/tiff_writer.hpp"
#include "base/error.hpp"
#include "base/input.hpp"
#include "image/image.hpp"
#include "image/ktx2.hpp"
#include "texture/material.hpp"
#include "texture/mipmap.hpp"
#include "texture/texture_atlas.hpp"
#include "texture/tile_synthesis.hpp"
#include "texture_fixtures.hpp"

namespace tilekit {
namespace {

namespace fs = std::filesystem;

// The tiles of one map as `texture tiles --map` makes them: the synthesis on the albedo (the map's
// term in its costs), the map copied at the recorded texels.
struct DeepTiles {
  TextureTileSet set;
  std::vector<Image> tiles;
};
DeepTiles deep_map_tiles(const Image& albedo, MaterialMap map) {
  SynthesisOptions o = test::small_options(TileKind::Corner, 2, 32);
  o.record_coords = true;
  o.keep_period = false;
  std::vector<MaterialMap> maps{std::move(map)};
  resize_maps(maps, albedo.width, albedo.height, false);
  o.cost_maps = seam_cost_maps(maps);
  DeepTiles r;
  r.set = synthesize_tiles(exemplar_from_image(albedo, "albedo"), o);
  r.tiles = transfer_tiles(r.set.coords, 32, maps[0].image);
  return r;
}

// Texel (x, y) of atlas level 0 is the copy of the source texel its tile recorded: byte for byte.
void expect_atlas_copies_source(const TextureAtlas& atlas, const TextureTileSet& set, const Image& source) {
  const std::size_t bytes = std::size_t(source.texel_bytes());
  ASSERT_EQ(atlas.levels[0].texel_bytes(), source.texel_bytes());
  for (int row = 0; row < atlas.lookup.rows; ++row)
    for (int col = 0; col < atlas.lookup.cols; ++col) {
      const std::size_t t = atlas.lookup.cells[std::size_t(row) * std::size_t(atlas.lookup.cols) + std::size_t(col)];
      for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
          const std::uint32_t c = set.coords[t][std::size_t(y) * 32 + std::size_t(x)];
          ASSERT_EQ(std::memcmp(atlas.levels[0].at(col * 32 + x, row * 32 + y),
                                source.at(int(c & 0xffff), int(c >> 16)), bytes),
                    0)
              << "tile " << t << " texel " << x << "," << y;
        }
    }
}

// The same tiles through their files: write_map_tiles, then the atlas built from the folder.
TextureAtlas atlas_through_files(const std::vector<Image>& tiles, const fs::path& dir) {
  write_map_tiles(dir.string(), tiles, ColourSpace::Linear, nlohmann::json::object());
  return build_texture_atlas(atlas_lookup(TileKind::Corner, 2), dir.string(), ColourSpace::Linear);
}

TEST(DeepMaps, SixteenBitTiffRampSurvivesTilesAtlasAndMips) {
  const test::TempDir tmp;  // a fresh folder, removed however the test ends
  const fs::path dir = tmp.path;
  // Heights 1000..3000 of 65535 (6 grey levels at 8 bits) as a 16-bit grey TIFF, deflated, tiled.
  Image ramp = Image::grey(128, 128).to_depth(16);
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x) ramp.set_sample(x, y, 0, 1000 + unsigned((x + y * 128) * 2000 / (128 * 128 - 1)));
  test::write_tiff((dir / "height.tif").string(), ramp, {true, false, 8, 3});
  MaterialMap map = parse_material_map("height=" + (dir / "height.tif").string());
  ASSERT_EQ(map.image.depth, 16);
  const Image source = map.image;
  const DeepTiles r = deep_map_tiles(test::synthetic_image(128, 128, 6), map);
  const TextureAtlas atlas = atlas_through_files(r.tiles, dir / "tiles");
  EXPECT_TRUE(fs::exists(dir / "tiles/tile-0000.png"));
  EXPECT_EQ(nlohmann::json::parse(read_input_file((dir / "tiles/tiles.json").string(), "json"))["bits"], 16);
  // Level 0: every texel a copy, exact (no more than 1/65535 off: none at all).
  expect_atlas_copies_source(atlas, r.set, source);
  for (const Image& level : atlas.levels) EXPECT_EQ(level.depth, 16);
  std::set<unsigned> values;
  for (int y = 0; y < atlas.levels[1].height; ++y)
    for (int x = 0; x < atlas.levels[1].width; ++x) values.insert(atlas.levels[1].sample(x, y, 0));
  EXPECT_GT(values.size(), 200u);  // an 8-bit chain would hold at most 9 values in 1000..3000
}

TEST(DeepMaps, FloatExrRampSurvivesTilesAndAtlasBitExactAndItsMipsAreFloatAverages) {
  const test::TempDir tmp;  // a fresh folder, removed however the test ends
  const fs::path dir = tmp.path;
  // Heights -3.5 .. 1200.25 in metres, far outside 0..1: a sawtooth ramp, so that every tile
  // holds the whole range.
  Image heights = Image::grey(128, 128).to_depth(32);
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x) heights.set_value(x, y, 0, -3.5 + ((x * 37 + y * 11) % 128) * (1203.75 / 127));
  write_exr((dir / "height.exr").string(), heights);
  EXPECT_THROW(parse_material_map("height=" + (dir / "height.exr").string() + ":srgb"), InputError);
  MaterialMap map = parse_material_map("height=" + (dir / "height.exr").string());
  ASSERT_EQ(map.image.depth, 32);
  ASSERT_EQ(map.image.value(0, 0, 0), -3.5);
  ASSERT_EQ(map.image.value(83, 0, 2), 1200.25);  // 83 * 37 = 127 (mod 128)
  const Image source = map.image;
  const DeepTiles r = deep_map_tiles(test::synthetic_image(128, 128, 6), map);
  const TextureAtlas atlas = atlas_through_files(r.tiles, dir / "tiles");
  EXPECT_TRUE(fs::exists(dir / "tiles/tile-0000.exr"));
  EXPECT_FALSE(fs::exists(dir / "tiles/tile-0000.png"));
  const auto manifest = nlohmann::json::parse(read_input_file((dir / "tiles/tiles.json").string(), "json"));
  EXPECT_EQ(manifest["bits"], 32);
  EXPECT_EQ(manifest["format"], "exr float");
  EXPECT_EQ(manifest["colour_space"], "linear");
  expect_atlas_copies_source(atlas, r.set, source);
  // Each mip texel is the tent filter's float average of the level above ([1 3 3 1] / 8 per
  // axis, wrapping), computed here independently, and the float levels keep the range.
  for (std::size_t k = 1; k < atlas.levels.size(); ++k) {
    const Image &up = atlas.levels[k - 1], &level = atlas.levels[k];
    ASSERT_EQ(level.depth, 32);
    if (up.width < 2 || up.height < 2 || up.width % 2 || up.height % 2) break;
    const double w[4] = {1, 3, 3, 1};
    for (int y = 0; y < level.height; ++y)
      for (int x = 0; x < level.width; ++x) {
        double sum = 0;
        for (int j = 0; j < 4; ++j)
          for (int i = 0; i < 4; ++i)
            sum += w[i] * w[j] *
                   up.value((2 * x - 1 + i + up.width) % up.width, (2 * y - 1 + j + up.height) % up.height, 0);
        ASSERT_NEAR(level.value(x, y, 0), sum / 64, 1e-6 * (1 + std::abs(sum / 64))) << "level " << k;
        ASSERT_EQ(level.value(x, y, 3), 1.0);
      }
  }
  // Nothing clamped to 0..1: level 0 spans the heights, level 1's averages reach far beyond 1.
  const auto range = [](const Image& img) {
    double lo = 1e9, hi = -1e9;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) lo = std::min(lo, img.value(x, y, 0)), hi = std::max(hi, img.value(x, y, 0));
    return std::pair{lo, hi};
  };
  EXPECT_EQ(range(atlas.levels[0]), (std::pair{-3.5, 1200.25}));
  EXPECT_GE(range(atlas.levels[1]).first, -3.5);
  EXPECT_GT(range(atlas.levels[1]).second, 800);
  EXPECT_LE(range(atlas.levels[1]).second, 1200.25);
  // The KTX2 of a float atlas: RGBA32 SFLOAT, level 0 the atlas's floats.
  const Ktx2Texture k = texture_atlas_ktx2(atlas);
  EXPECT_EQ(k.vk_format(), kVkR32G32B32A32Sfloat);
  EXPECT_EQ(k.levels[0], atlas.levels[0].pixels);
  // And the atlas's own files: OpenEXR levels that read back bit for bit.
  const AtlasFiles f = write_texture_atlas(atlas, (dir / "atlas.png").string(), "// glsl\n");
  EXPECT_EQ(f.levels[0], (dir / "atlas.exr").string());
  const TextureAtlas back = read_texture_atlas((dir / "atlas.json").string());
  ASSERT_EQ(back.levels.size(), atlas.levels.size());
  for (std::size_t l = 0; l < back.levels.size(); ++l) EXPECT_EQ(back.levels[l].pixels, atlas.levels[l].pixels);
  EXPECT_THROW(build_texture_atlas(atlas_lookup(TileKind::Corner, 2), r.tiles, ColourSpace::Srgb), InputError);
}

}  // namespace
}  // namespace tilekit
