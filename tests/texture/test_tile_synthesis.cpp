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

// Corner tiles: the texels within `margin` of a border depend only on the border's two corner
// colours (the same band sample, corner squares and cuts), so any two tiles that share them agree
// there, and a tile's top row and the bottom row of a tile with the same colours below are
// consecutive rows of the border's band sample.
TEST(CornerTiles, BorderBandsDependOnlyOnTheBordersCornerColours) {
  const Exemplar e = test::synthetic_exemplar();
  SynthesisOptions o = test::small_options(TileKind::Corner, 2, 32);
  o.keep_period = false;  // texels straight from `e` (its smoothed sines repeat: no resampling to whole periods)
  const TextureTileSet s = synthesize_corner_tiles(e, o);
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
  // the band sample of the border from a lattice point of colour a to one of colour b (eastwards)
  // is sample 2 + 2a + b; it spans lattice x from margin - 1, rows from -extent
  for (TileIndex t = 0; t < s.tiles.size(); ++t) {
    const CornerTile c = corner_tile(t, 2);
    const auto& top = s.samples[2 + 2 * c.nw + c.ne];
    const auto& bottom = s.samples[2 + 2 * c.sw + c.se];
    for (int x = g.strip + 1; x < 32 - g.strip - 1; ++x) {
      EXPECT_EQ(0, std::memcmp(s.tiles[t].at(x, 0), e.at(top[0] + x - g.margin + 1, top[1] + g.extent), 4)) << t;
      EXPECT_EQ(0, std::memcmp(s.tiles[t].at(x, 31), e.at(bottom[0] + x - g.margin + 1, bottom[1] + g.extent - 1), 4))
          << t;
    }
  }
}

// The shared samples cover only the bands: every texel at least `strip` from every border is the
// tile's own centre patch, no centre texel lies within `margin` of a border, and the centre
// patches of different tiles come from different places in the exemplar.
TEST(CornerTiles, EveryTileIsMostlyItsOwnCentrePatchFromItsOwnRegion) {
  const TextureTileSet s =
      synthesize_corner_tiles(test::synthetic_exemplar(320), test::small_options(TileKind::Corner, 2, 64));
  const TileGeometry g(64);
  ASSERT_EQ(s.shared_sources, 2u + 2 * 4);
  for (TileIndex t = 0; t < s.tiles.size(); ++t) {
    std::size_t own = 0;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const std::uint32_t src = s.sources[t][std::size_t(y * 64 + x)];
        const int d = std::min({x, y, 63 - x, 63 - y});
        if (d >= g.strip) {
          EXPECT_EQ(src, s.shared_sources + t) << t << " " << x << "," << y;
        }
        if (d < g.margin) {
          EXPECT_LT(src, s.shared_sources) << t << " " << x << "," << y;
        }
        own += src == s.shared_sources + t;
      }
    EXPECT_GE(own, std::size_t((64 - 2 * g.strip) * (64 - 2 * g.strip))) << t;
  }
  const std::set<std::array<int, 2>> distinct(s.centres.begin(), s.centres.end());
  EXPECT_EQ(distinct.size(), s.tiles.size());
}

TEST(CornerTiles, SearchLowersTheCutErrorAndSpreadsTheSharedSamples) {
  const Exemplar e = test::real_exemplar("gravel");
  SynthesisOptions o = test::small_options(TileKind::Corner, 2, 64, 2);
  const TextureTileSet s = synthesize_corner_tiles(e, o);
  EXPECT_LT(s.cut_error, 0.9 * s.cut_error_initial);
  EXPECT_LT(s.overlap, 0.05);  // no two shared samples cover the same exemplar pixels
  o.search = 0;
  const TextureTileSet plain = synthesize_corner_tiles(e, o);
  EXPECT_EQ(plain.cut_error, plain.cut_error_initial);
  EXPECT_EQ(plain.cut_error_initial, s.cut_error_initial);  // the same first draw
}

// Wang tiles: every border pixel (but the corner pixels) is a row of its edge colour's sample: the
// tile with north colour c shows the sample's row `extent`, the tile with south colour c its row
// `extent` - 1, so they continue each other; columns likewise for the east and west colours.
TEST(WangTiles, EveryBorderIsARowOfItsEdgeColoursSample) {
  const Exemplar e = test::synthetic_exemplar();
  SynthesisOptions o = test::small_options(TileKind::Wang, 2, 32);
  o.keep_period = false;  // texels straight from `e` (its smoothed sines repeat: no resampling to whole periods)
  const TextureTileSet s = synthesize_wang_tiles(e, o);
  const TileGeometry g(32);
  const int E = g.extent;
  for (TileIndex t = 0; t < s.tiles.size(); ++t) {
    const WangTile w = wang_tile(t, 2);
    const auto &hn = s.samples[w.n], &hs = s.samples[w.s], &ve = s.samples[2 + w.e], &vw = s.samples[2 + w.w];
    for (int i = 1; i + 1 < 32; ++i) {
      EXPECT_EQ(0, std::memcmp(s.tiles[t].at(i, 0), e.at(hn[0] + i, hn[1] + E), 4)) << t << " N " << i;
      EXPECT_EQ(0, std::memcmp(s.tiles[t].at(i, 31), e.at(hs[0] + i, hs[1] + E - 1), 4)) << t << " S " << i;
      EXPECT_EQ(0, std::memcmp(s.tiles[t].at(0, i), e.at(vw[0] + E, vw[1] + i), 4)) << t << " W " << i;
      EXPECT_EQ(0, std::memcmp(s.tiles[t].at(31, i), e.at(ve[0] + E - 1, ve[1] + i), 4)) << t << " E " << i;
    }
  }
  EXPECT_LE(s.cut_error, s.cut_error_initial);
}

// A brick-like exemplar (mortar lines every 24 px across, rows of 12 px with the joints of
// alternate rows half a brick apart): its period is found, the exemplar is resampled so that a
// 64-pixel tile holds whole periods, and every shared sample and centre patch is in phase.
TEST(Period, BricksAreFoundResampledAndKeptInPhase) {
  Image img(240, 240);
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 240; ++x) {
      const int row = y / 12, joint = (x + (row % 2) * 12) % 24;
      const bool mortar = y % 12 < 2 || joint < 2;
      const std::uint8_t v = mortar ? 220 : std::uint8_t(90 + ((x * 73856093u) ^ (y * 19349663u)) % 23);
      img.set(x, y, {v, std::uint8_t(v / 2), 40});
    }
  const Exemplar e = exemplar_from_image(img, "bricks", true);
  const ExemplarPeriod p = dominant_period(e);
  EXPECT_NEAR(p.x, 24, 0.5);
  EXPECT_NEAR(p.y, 24, 0.5);  // two rows: the joints align only there
  SynthesisOptions o = test::small_options(TileKind::Corner, 2, 64);
  const SynthesisExemplar x(e, o);
  EXPECT_NEAR(x.scale()[0], 64.0 / 72, 1e-9);  // three bricks of 21.3 px per tile
  const TextureTileSet s = synthesize_corner_tiles(e, o);
  EXPECT_NEAR(s.exemplar_scale[1], 64.0 / 72, 1e-9);
  // in phase: any two centre patches differ by whole periods (21.33 px) each way, up to rounding
  for (std::size_t t = 1; t < s.centres.size(); ++t)
    for (int k = 0; k < 2; ++k) {
      const double d = std::remainder(s.centres[t][std::size_t(k)] - s.centres[0][std::size_t(k)], 64.0 / 3);
      EXPECT_LE(std::abs(d), 1.0) << t << " " << k;
    }
  o.keep_period = false;
  EXPECT_EQ(SynthesisExemplar(e, o).scale()[0], 1.0);
  // blobs at random places: no period found, at the first look or once smoothed
  const ExemplarPeriod none = dominant_period(exemplar_from_image(test::blob_image(200), "blobs"));
  EXPECT_EQ(none.x, 0.0);
  EXPECT_EQ(none.y, 0.0);
}

TEST(Exemplar, TileableExemplarsAreSampledAsATorus) {
  const Exemplar e = exemplar_from_image(test::synthetic_image(100, 90), "torus", true);
  EXPECT_EQ(e.wrap_w, 100);
  EXPECT_EQ(e.wrap_h, 90);
  ASSERT_GE(e.width(), 512);
  EXPECT_EQ(0, std::memcmp(e.at(3, 5), e.at(203, 95), 4));
  // windows that wrap round the torus overlap
  EXPECT_NEAR(window_overlap(e, {95, 0}, 10, 10, {195, 0}, 10, 10), 1.0, 1e-12);
  EXPECT_NEAR(window_overlap(e, {95, 0}, 10, 10, {0, 0}, 10, 10), 0.5, 1e-12);
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
  // the labels: one colour per sample, the same colour for the same sample in every tile
  const Image l5 = read_image(d / "set/labels/tile-0005.png"), l6 = read_image(d / "set/labels/tile-0006.png");
  EXPECT_TRUE(std::filesystem::exists(d / "set/labels/tiles.json"));
  for (std::size_t i = 0; i < 32 * 32; ++i)
    for (std::size_t j : {i, (i * 7) % (32 * 32)}) {
      const bool same = s.sources[5][i] == s.sources[6][j];
      EXPECT_EQ(same, 0 == std::memcmp(l5.pixels.data() + 4 * i, l6.pixels.data() + 4 * j, 3)) << i << " " << j;
    }
}

}  // namespace
}  // namespace tilekit
