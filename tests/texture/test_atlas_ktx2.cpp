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
  for (const Ktx2Transfer transfer : {Ktx2Transfer::Srgb, Ktx2Transfer::Linear}) {
    TextureAtlas a = build_texture_atlas(lookup, tiles);
    a.transfer = transfer;
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
    EXPECT_EQ(read_texture_atlas(d / "atlas.png").transfer, transfer);
  }
}

}  // namespace
}  // namespace tilekit
