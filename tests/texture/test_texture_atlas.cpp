// Atlases from packings (thesis sec. 5.4): the mip chain of a packed atlas equals the mip chain of
// the infinite tiling near every tile border; any other arrangement does not.
#include <gtest/gtest.h>

#include "../cli_runner.hpp"
#include "base/error.hpp"
#include "texture/mipmap.hpp"
#include "texture/seam_metrics.hpp"
#include "texture_fixtures.hpp"
#include "tiling/direct_tiling.hpp"

namespace tilekit {
namespace {

TEST(Mipmap, EvenSizesUseTheOneThreeThreeOneTentWithWrapAround) {
  Image img(4, 1, std::vector<std::uint8_t>{});
  for (int v : {0, 64, 128, 255}) img.pixels.insert(img.pixels.end(), {std::uint8_t(v), 0, 0, 255});
  const Image half = downsample(img, MipEdge::Wrap, ColourSpace::Linear);  // data: averaged as stored
  ASSERT_EQ(half.width, 2);
  EXPECT_EQ(half.at(0, 0)[0], 72);   // (255 + 3*0 + 3*64 + 128) / 8 = 71.9, the west neighbour wraps
  EXPECT_EQ(half.at(1, 0)[0], 152);  // (64 + 3*128 + 3*255 + 0) / 8 = 151.6
  EXPECT_EQ(downsample(img, MipEdge::Clamp, ColourSpace::Linear).at(0, 0)[0], 40);  // (0 + 0 + 3*64 + 128) / 8
  const auto chain = mip_chain(test::synthetic_image(36, 20), MipEdge::Wrap);
  ASSERT_EQ(chain.size(), 6u);  // 36x20 18x10 9x5 4x2 2x1 1x1
  EXPECT_EQ(chain[3].width, 4);
  EXPECT_EQ(chain[3].height, 2);
}

struct Comparison {
  std::size_t texels = 0, differing = 0, near_corner_only = 0;
  int max = 0;
  double mean = 0;
};

// Level k of `atlas` against level k of a stitched tiling, tile by tile over the tiling's
// interior tiles (one tile away from its edge, where clamping plays no part).
Comparison compare(const std::vector<Image>& atlas, const AtlasLookup& l, const std::vector<Image>& truth,
                   const Tiling& t, int tile_px, int k) {
  Comparison c;
  const int n = tile_px >> k;
  double sum = 0;
  for (int r = 1; r + 1 < t.rows; ++r)
    for (int col = 1; col + 1 < t.cols; ++col) {
      const auto [ar, ac] = l.positions[t.at(r, col)];
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const std::uint8_t* p = atlas[std::size_t(k)].at(ac * n + x, ar * n + y);
          const std::uint8_t* q = truth[std::size_t(k)].at(col * n + x, r * n + y);
          int d = 0;
          for (int ch = 0; ch < 4; ++ch) d = std::max(d, std::abs(int(p[ch]) - int(q[ch])));
          ++c.texels;
          sum += d;
          c.max = std::max(c.max, d);
          if (d) {
            ++c.differing;
            // texels whose level-0 footprint (the [1 3 3 1] tent k times: texel i covers level-0
            // texels 2^k i - 2^k + 1 .. 2^k i + 2^(k+1) - 2) reaches within 8 texels of a corner
            const int edge = (8 + (1 << k) - 1 + (1 << k) - 1) >> k;
            const bool corner = (x < edge || x >= n - edge) && (y < edge || y >= n - edge);
            c.near_corner_only += corner;
          }
        }
    }
  c.mean = sum / double(c.texels);
  return c;
}

TEST(TextureAtlas, PackedAtlasMipLevelsZeroToTwoEqualTheStitchedTilingAndARandomArrangementDoesNot) {
  const TextureTileSet& tiles = test::grass_tiles(TileKind::Corner);
  const TextureAtlas& atlas = test::grass_atlas(TileKind::Corner);
  ASSERT_EQ(atlas.levels[0].width, 256);
  // ground truth: the tiles stitched as a 10x10 window of the direct stochastic tiling
  const Tiling t = DirectCornerTiling(2, HashKind::LongPeriod, 11).generate(10, 10);
  const std::vector<Image> truth = mip_chain(stitch_tiles(tiles, t), MipEdge::Clamp);
  for (int k = 0; k <= 2; ++k) {
    const Comparison c = compare(atlas.levels, atlas.lookup, truth, t, 64, k);
    EXPECT_EQ(c.differing, 0u) << "level " << k << ": " << c.differing << " of " << c.texels << " texels differ, max "
                               << c.max;
  }
  // the same tiles in a random arrangement of the atlas cells (not a tiling)
  const AtlasLookup shuffled = test::shuffled_lookup(atlas.lookup, 4);
  const TextureAtlas random = build_texture_atlas(shuffled, tiles.tiles);
  const Comparison c1 = compare(random.levels, shuffled, truth, t, 64, 1),
                   c2 = compare(random.levels, shuffled, truth, t, 64, 2);
  EXPECT_EQ(compare(random.levels, shuffled, truth, t, 64, 0).differing, 0u);  // level 0 holds the tiles themselves
  EXPECT_GT(c1.differing, c1.texels / 50) << c1.differing;
  EXPECT_GT(c2.differing, c2.texels / 20) << c2.differing;
  EXPECT_GT(c1.max, 10);
  EXPECT_GT(c2.mean, 0.2);
}

// Wang tiles have the corner problem (thesis 5.4: Wei needs a second packing of the corners): the
// half-diamonds meet at the tile corners, so near a corner a neighbour's texels depend on more
// than the shared edge. Away from the corners the packed atlas filters exactly like the tiling.
TEST(TextureAtlas, WangAtlasDiffersFromTheTilingOnlyNearTileCorners) {
  const TextureTileSet& tiles = test::grass_tiles(TileKind::Wang);
  const TextureAtlas& atlas = test::grass_atlas(TileKind::Wang);
  const Tiling t = DirectWangTiling(2, 2, HashKind::LongPeriod, 11).generate(10, 10);
  const std::vector<Image> truth = mip_chain(stitch_tiles(tiles, t), MipEdge::Clamp);
  EXPECT_EQ(compare(atlas.levels, atlas.lookup, truth, t, 64, 0).differing, 0u);
  for (int k = 1; k <= 2; ++k) {
    const Comparison c = compare(atlas.levels, atlas.lookup, truth, t, 64, k);
    EXPECT_EQ(c.near_corner_only, c.differing) << "level " << k;
    EXPECT_LT(c.differing, c.texels / 20) << "level " << k;
  }
}

TEST(TextureAtlas, WrittenAtlasReadsBackWithEveryLevel) {
  test::TempDir d;
  const TextureAtlas& atlas = test::grass_atlas(TileKind::Corner);
  const AtlasFiles f = write_texture_atlas(atlas, d / "a.png", "// glsl\n");
  EXPECT_EQ(f.levels.size(), 9u);  // 256 ... 1
  const TextureAtlas back = read_texture_atlas(d / "a.png");
  ASSERT_EQ(back.levels.size(), atlas.levels.size());
  for (std::size_t k = 0; k < back.levels.size(); ++k) EXPECT_EQ(back.levels[k].pixels, atlas.levels[k].pixels) << k;
  EXPECT_EQ(back.lookup.cells, atlas.lookup.cells);
  EXPECT_EQ(back.tile_px, 64);
  // a manifest whose cells are not a packing, or a level of the wrong size, is bad input
  auto j = nlohmann::json::parse(test::slurp(d / "a.json"));
  std::swap(j["lookup"]["cells"][0][0], j["lookup"]["cells"][0][1]);
  test::write_text(d / "b.json", j.dump());
  EXPECT_THROW(read_texture_atlas(d / "b.json"), InputError);
  write_png(d / "a.mip2.png", test::synthetic_image(10, 10));
  EXPECT_THROW(read_texture_atlas(d / "a.png"), InputError);
  EXPECT_THROW(read_texture_atlas(d / "none.png"), InputError);
}

}  // namespace
}  // namespace tilekit
