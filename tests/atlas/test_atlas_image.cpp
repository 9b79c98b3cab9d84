#include <gtest/gtest.h>

#include <numeric>
#include <random>

#include "atlas/atlas_image.hpp"
#include "atlas/lookup.hpp"
#include "tests/cli_runner.hpp"
#include "base/error.hpp"

using namespace tilekit;
using namespace tilekit::test;

namespace {
AtlasLookup lookup(TileKind k, std::uint32_t c) {
  return atlas_lookup(k, c);
}

// The same tiles in a random order: not a packing, so borders no longer match.
AtlasLookup shuffled(AtlasLookup a) {
  std::mt19937 rng(5);
  std::shuffle(a.cells.begin(), a.cells.end(), rng);
  return a;
}
}  // namespace

TEST(AtlasImage, GeneratedAtlasIsContinuousAcrossEveryTileBorderIncludingWrapAround) {
  for (auto [kind, c] : {std::pair{TileKind::Corner, 3u}, std::pair{TileKind::Wang, 2u}, std::pair{TileKind::Wang, 3u}}) {
    AtlasLookup a = lookup(kind, c);
    Image img = atlas_from_generated_tiles(a, 24);
    EXPECT_EQ(img.width, a.cols * 24);
    SeamReport packed = measure_seams(img, 24);
    // Across a border the colour changes no more than between neighbouring pixels inside a tile.
    EXPECT_LE(packed.seam_jump, packed.interior_jump + 2) << kind_name(kind) << " C=" << c;
    SeamReport random = measure_seams(atlas_from_generated_tiles(shuffled(a), 24), 24);
    EXPECT_GT(random.seam_jump, 3 * packed.interior_jump) << kind_name(kind) << " C=" << c;
  }
}

TEST(AtlasImage, CornerTilesShowTheirCornerColours) {
  Image t = generated_tile(TileKind::Corner, 3, corner_index(CornerTile{1, 2, 0, 1}, 3), 40);
  auto near = [](const std::uint8_t* p, std::array<std::uint8_t, 3> c) {
    return std::abs(p[0] - c[0]) <= 3 && std::abs(p[1] - c[1]) <= 3 && std::abs(p[2] - c[2]) <= 3;
  };
  EXPECT_TRUE(near(t.at(39, 0), palette_colour(1, 3)));   // NE
  EXPECT_TRUE(near(t.at(39, 39), palette_colour(2, 3)));  // SE
  EXPECT_TRUE(near(t.at(0, 39), palette_colour(0, 3)));   // SW
  EXPECT_TRUE(near(t.at(0, 0), palette_colour(1, 3)));    // NW
}

TEST(AtlasImage, TileImagesNamedByIndexArePlacedWhereThePackingSays) {
  TempDir d;
  AtlasLookup a = lookup(TileKind::Corner, 2 + 1);
  std::filesystem::create_directories(d / "tiles");
  for (TileIndex i = 0; i < a.cells.size(); ++i)
    write_png(d / ("tiles/tile-" + std::to_string(1000 + i).substr(1) + ".png"), generated_tile(a.kind, 3, i, 8));
  Image from_files = atlas_from_tile_images(a, d / "tiles");
  Image generated = atlas_from_generated_tiles(a, 8);
  EXPECT_EQ(from_files.width, generated.width);
  EXPECT_TRUE(from_files.pixels == generated.pixels);
}

TEST(AtlasImage, IncompleteOrInconsistentTileFoldersAreRejected) {
  TempDir d;
  AtlasLookup a = lookup(TileKind::Corner, 1);  // one tile
  std::filesystem::create_directories(d / "empty");
  EXPECT_THROW(atlas_from_tile_images(a, d / "empty"), InputError);
  EXPECT_THROW(atlas_from_tile_images(a, d / "missing"), InputError);
  std::filesystem::create_directories(d / "range");
  write_png(d / "range/5.png", generated_tile(a.kind, 1, 0, 4));
  EXPECT_THROW(atlas_from_tile_images(a, d / "range"), InputError);
  std::filesystem::create_directories(d / "junk");
  write_text(d / "junk/0.png", "not a png");
  EXPECT_THROW(atlas_from_tile_images(a, d / "junk"), InputError);
}
