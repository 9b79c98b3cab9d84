// Texture tiles from an exemplar: bad input, determinism, the geometry that makes tile borders
// seamless, and the patch search.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "../cli_runner.hpp"
#include "base/error.hpp"
#include "texture_fixtures.hpp"

namespace tilekit {
namespace {

using test::TempDir;

TEST(Exemplar, MissingCorruptOrTooSmallFilesAreInputErrors) {
  TempDir d;
  EXPECT_THROW(load_exemplar(d / "missing.png"), InputError);
  test::write_text(d / "corrupt.png", "\x89PNG\r\n\x1a\n this is not a PNG");
  EXPECT_THROW(load_exemplar(d / "corrupt.png"), InputError);
  write_png(d / "small.png", test::synthetic_image(8, 40));
  EXPECT_THROW(load_exemplar(d / "small.png"), InputError);
  write_png(d / "ok.png", test::synthetic_image(40, 40));
  EXPECT_EQ(load_exemplar(d / "ok.png").width(), 40);
}

TEST(Exemplar, TileSizeLargerThanTheExemplarAllowsIsAnInputError) {
  const Exemplar e = test::synthetic_exemplar(100);
  for (int px : {96, 128, 2000, 15, 33})
    EXPECT_THROW(check_synthesis_options(e, test::small_options(TileKind::Corner, 2, px)), InputError) << px;
  EXPECT_NO_THROW(check_synthesis_options(e, test::small_options(TileKind::Corner, 2, 64)));
}

TEST(TextureTiles, SameSeedGivesTheSameBytesOnOneAndThreeThreads) {
  const Exemplar e = test::synthetic_exemplar();
  for (TileKind kind : {TileKind::Corner, TileKind::Wang}) {
    const TextureTileSet a = synthesize_tiles(e, test::small_options(kind, 2, 32, 1));
    const TextureTileSet b = synthesize_tiles(e, test::small_options(kind, 2, 32, 3));
    ASSERT_EQ(a.tiles.size(), 16u);
    for (std::size_t t = 0; t < a.tiles.size(); ++t) EXPECT_EQ(a.tiles[t].pixels, b.tiles[t].pixels) << t;
    SynthesisOptions other = test::small_options(kind, 2, 32, 1);
    other.seed = 6;
    EXPECT_NE(synthesize_tiles(e, other).tiles[5].pixels, a.tiles[5].pixels);
  }
}

// Corner tiles (Ng et al.): the texels within `margin` of a border depend only on the border's two
// corner colours (the same pair cut and the same patches), so any two tiles that share them
// agree there, and a tile's border rows continue the patch of the tile across the border.
TEST(CornerTiles, BorderBandsDependOnlyOnTheBordersCornerColours) {
  const Exemplar e = test::synthetic_exemplar();
  const TextureTileSet s = synthesize_corner_tiles(e, test::small_options(TileKind::Corner, 2, 32));
  const TileGeometry g(32);
  std::map<std::pair<Colour, Colour>, const Image*> north;
  int compared = 0;
  for (TileIndex t = 0; t < s.tiles.size(); ++t) {
    const CornerTile c = corner_tile(t, 2);
    auto [it, fresh] = north.emplace(std::pair{c.nw, c.ne}, &s.tiles[t]);
    if (fresh) continue;
    for (int y = 0; y < g.margin; ++y)
      for (int x = 0; x < 32; ++x)
        ASSERT_EQ(0, std::memcmp(s.tiles[t].at(x, y), it->second->at(x, y), 4)) << t << " " << x << "," << y;
    ++compared;
  }
  EXPECT_EQ(compared, 12);
  // the top row of a tile with (NW, NE) = (a, b) and the bottom row of a tile with (SW, SE) = (a, b)
  // are consecutive rows of the same patches: at the tile's west end both are patch a's pixels
  const auto& pos = s.samples;
  for (TileIndex t = 0; t < s.tiles.size(); ++t) {
    const CornerTile c = corner_tile(t, 2);
    const int off = g.half + g.overlap;
    EXPECT_EQ(0, std::memcmp(s.tiles[t].at(0, 0), e.at(pos[c.nw][0] + off, pos[c.nw][1] + off), 4));
    EXPECT_EQ(0, std::memcmp(s.tiles[t].at(0, 31), e.at(pos[c.sw][0] + off, pos[c.sw][1] + off - 1), 4));
  }
}

TEST(CornerTiles, TheCrossIsCoveredByATileUniqueCentrePatchInsideTheCircle) {
  const TextureTileSet s =
      synthesize_corner_tiles(test::synthetic_exemplar(), test::small_options(TileKind::Corner, 2, 64));
  const TileGeometry g(64);
  std::set<std::uint32_t> centres;
  for (TileIndex t = 0; t < s.tiles.size(); ++t)
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const std::uint32_t src = s.sources[t][std::size_t(y * 64 + x)];
        const double r = std::hypot(x + 0.5 - 32, y + 0.5 - 32);
        if (src >= 2) {
          EXPECT_EQ(src, 2 + t);  // the tile's own centre patch
          EXPECT_LT(r, g.radius);
          centres.insert(src);
        }
        const bool cross = std::abs(x + 0.5 - 32) < g.overlap + 2 || std::abs(y + 0.5 - 32) < g.overlap + 2;
        if (cross && r < g.radius - g.inner) {
          EXPECT_EQ(src, 2 + t) << x << "," << y;
        }
      }
  EXPECT_EQ(centres.size(), 16u);
}

TEST(CornerTiles, SearchLowersTheCutErrorOnARealTexture) {
  const Exemplar e = test::real_exemplar("gravel");
  SynthesisOptions o = test::small_options(TileKind::Corner, 2, 64, 2);
  const TextureTileSet s = synthesize_corner_tiles(e, o);
  EXPECT_LT(s.cut_error, 0.8 * s.cut_error_initial);
  o.search = 0;
  const TextureTileSet plain = synthesize_corner_tiles(e, o);
  EXPECT_EQ(plain.cut_error, plain.cut_error_initial);
  EXPECT_EQ(plain.cut_error_initial, s.cut_error_initial);  // the same first draw
}

// Wang tiles (Cohen et al.): every border (but its two corner pixels) is a row of its edge
// colour's diamond: the tile with north colour c shows the diamond's row 0 below its centre, the
// tile with south colour c its row -1, so they continue each other.
TEST(WangTiles, EveryBorderIsARowOfItsEdgeColoursDiamond) {
  const Exemplar e = test::synthetic_exemplar();
  const TextureTileSet s = synthesize_wang_tiles(e, test::small_options(TileKind::Wang, 2, 32));
  const TileGeometry g(32);
  const int off = g.half + g.overlap;
  for (TileIndex t = 0; t < s.tiles.size(); ++t) {
    const WangTile w = wang_tile(t, 2);
    const auto &hn = s.samples[w.n], &hs = s.samples[w.s], &ve = s.samples[2 + w.e], &vw = s.samples[2 + w.w];
    for (int i = 1; i + 1 < 32; ++i) {
      EXPECT_EQ(0, std::memcmp(s.tiles[t].at(i, 0), e.at(hn[0] + off + i - 16, hn[1] + off), 4)) << t << " N " << i;
      EXPECT_EQ(0, std::memcmp(s.tiles[t].at(i, 31), e.at(hs[0] + off + i - 16, hs[1] + off - 1), 4))
          << t << " S " << i;
      EXPECT_EQ(0, std::memcmp(s.tiles[t].at(0, i), e.at(vw[0] + off, vw[1] + off + i - 16), 4)) << t << " W " << i;
      EXPECT_EQ(0, std::memcmp(s.tiles[t].at(31, i), e.at(ve[0] + off - 1, ve[1] + off + i - 16), 4))
          << t << " E " << i;
    }
  }
  EXPECT_LE(s.cut_error, s.cut_error_initial);
}

TEST(TextureTiles, TileSetFolderHoldsOneImagePerTileAndAReport) {
  TempDir d;
  const TextureTileSet s = synthesize_tiles(test::synthetic_exemplar(), test::small_options(TileKind::Corner, 2, 32));
  write_tile_set(s, d / "set", "synthetic");
  EXPECT_TRUE(std::filesystem::exists(d / "set/tile-0015.png"));
  EXPECT_TRUE(std::filesystem::exists(d / "set/tileset.png"));
  const auto j = nlohmann::json::parse(test::slurp(d / "set/tiles.json"));
  EXPECT_EQ(j["tiles"], 16);
  EXPECT_EQ(j["kind"], "corner");
  EXPECT_EQ(read_image(d / "set/tile-0007.png").pixels, s.tiles[7].pixels);
}

}  // namespace
}  // namespace tilekit
