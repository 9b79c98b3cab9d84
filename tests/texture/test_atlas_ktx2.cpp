// atlas.ktx2 of `texture atlas`: every level of the atlas in one file, read back by the project's
// own reader (image/ktx2.hpp) with the colour space the atlas names and the packing in its
// key/value data. (The users' tools read the same files in tests/texture/ktx2_three.test.mjs.)
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>
#include <iterator>
#include <nlohmann/json.hpp>

#include "../cli_runner.hpp"
#include "atlas/lookup.hpp"
#include "image/ktx2.hpp"
#include "texture/texture_atlas.hpp"
#include "texture_fixtures.hpp"

namespace tilekit {
namespace {

TEST(AtlasKtx2, HoldsEveryLevelTheColourSpaceAndThePacking) {
  test::TempDir d;
  const AtlasLookup lookup = atlas_lookup(TileKind::Corner, 2);
  std::vector<Image> tiles;
  for (std::size_t i = 0; i < lookup.cells.size(); ++i) tiles.push_back(test::synthetic_image(16, 16, i + 1));
  for (const ColourSpace space : {ColourSpace::Srgb, ColourSpace::Linear, ColourSpace::Normal}) {
    const TextureAtlas a = build_texture_atlas(lookup, tiles, space);
    const Ktx2Transfer transfer = space == ColourSpace::Srgb ? Ktx2Transfer::Srgb : Ktx2Transfer::Linear;
    const AtlasFiles f = write_texture_atlas(a, d / "atlas.png", "// glsl\n");
    std::ifstream in(f.ktx2, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const Ktx2Texture k = decode_ktx2(bytes, f.ktx2);
    EXPECT_EQ(k.transfer, transfer);
    EXPECT_EQ(k.width, a.levels[0].width);
    ASSERT_EQ(k.levels.size(), a.levels.size());
    for (std::size_t i = 0; i < a.levels.size(); ++i) EXPECT_EQ(k.levels[i], a.levels[i].pixels) << "level " << i;
    ASSERT_EQ(k.key_values.back().first, "tilekit.atlas");
    const auto packing = nlohmann::json::parse(k.key_values.back().second);
    EXPECT_EQ(packing["rows"], lookup.rows);
    EXPECT_EQ(packing["cols"], lookup.cols);
    EXPECT_EQ(packing["tile_px"], 16);
    EXPECT_EQ(packing["kind"], "corner");
    // The manifest names the colour space, and reading the atlas back keeps it.
    EXPECT_EQ(read_texture_atlas(d / "atlas.png").colour_space, space);
  }
}

// 16-bit tiles: data keeps 16 bits (RGBA16 UNORM); sRGB colour has no 16-bit Vulkan format, so
// its KTX2 levels are the atlas's rounded to 8 bits (RGBA8 sRGB).
TEST(AtlasKtx2, SixteenBitDataStaysSixteenBitAndColourIsRoundedToEight) {
  const AtlasLookup lookup = atlas_lookup(TileKind::Corner, 2);
  std::vector<Image> tiles;
  for (std::size_t i = 0; i < lookup.cells.size(); ++i) tiles.push_back(test::synthetic_image(8, 8, i + 1).to_depth(16));
  const TextureAtlas data = build_texture_atlas(lookup, tiles, ColourSpace::Linear);
  const Ktx2Texture kd = texture_atlas_ktx2(data);
  EXPECT_EQ(kd.bytes_per_channel, 2);
  for (std::size_t i = 0; i < data.levels.size(); ++i) EXPECT_EQ(kd.levels[i], data.levels[i].pixels) << "level " << i;
  const TextureAtlas colour = build_texture_atlas(lookup, tiles, ColourSpace::Srgb);
  const Ktx2Texture kc = texture_atlas_ktx2(colour);
  EXPECT_EQ(kc.bytes_per_channel, 1);
  EXPECT_EQ(kc.transfer, Ktx2Transfer::Srgb);
  EXPECT_EQ(kc.levels[0], colour.levels[0].to_depth(8).pixels);
}

}  // namespace
}  // namespace tilekit
