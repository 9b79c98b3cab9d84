// Terrain transition tiles (texture/terrain_tiles.hpp), checked on the pixels alone: with
// terrains whose colours cannot be confused (one dominant channel each) every texel shows a
// terrain of its tile's corners and each corner shows its own; on the packed sheet, wrapped
// around, the strips either side of every border equal those of every other border with the same
// two colours, texel for texel (so neighbouring tiles join the same way wherever they meet); and a
// stochastic map of real textures keeps its tile borders as smooth as its tiles' insides.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "base/error.hpp"
#include "tests/texture/texture_fixtures.hpp"
#include "texture/seam_metrics.hpp"
#include "texture/terrain_tiles.hpp"
#include "tilesets/constructions.hpp"
#include "tilesets/tile_set.hpp"
#include "tiling/tiling_algorithms.hpp"

namespace tilekit::test {
namespace {

// Terrain k: channel k carries a textured 110..250, the other two stay below 60.
Exemplar channel_terrain(int k, int side = 160) {
  Image img = synthetic_image(side, side, 17 + std::uint64_t(k));
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      std::uint8_t* p = img.at(x, y);
      const int v = (p[0] + p[1] + p[2]) / 3;
      for (int c = 0; c < 3; ++c) p[c] = std::uint8_t(c == k ? 110 + v * 140 / 255 : v * 60 / 255);
    }
  return exemplar_from_image(std::move(img), "channel-" + std::to_string(k));
}

int terrain_of(const std::uint8_t* p) {
  return p[0] >= p[1] && p[0] >= p[2] ? 0 : p[1] >= p[2] ? 1 : 2;
}

std::vector<TerrainTexture> channel_terrains(std::uint32_t c) {
  const char* names[] = {"red", "green", "blue"};
  std::vector<TerrainTexture> t;
  for (std::uint32_t k = 0; k < c; ++k) t.push_back({names[k], channel_terrain(int(k))});
  return t;
}

// The tiles laid out by the constructed packing: the sheet, and the packing.
std::pair<Image, Tiling> packed_sheet(const TextureTileSet& s) {
  const auto p = construct_packing(TileKind::Corner, s.colours);
  EXPECT_TRUE(p.has_value());
  const Tiling& t = p->tiling;
  return {stitch_tiles(s, t), t};
}

// Problems on the wrapped sheet: for every border between neighbouring cells (wrapping around),
// the 2m x n strip across it must equal the strip of the first border seen with the same two
// corner colours; and the m x m texels at every lattice point of colour k those of the first one.
std::vector<std::string> strip_mismatches(const Image& sheet, const Tiling& t, int n, int m) {
  std::vector<std::string> bad;
  const int W = sheet.width, H = sheet.height;
  auto px = [&](int x, int y) { return sheet.at(((x % W) + W) % W, ((y % H) + H) % H); };
  auto same = [&](int x0, int y0, int x1, int y1, int w, int h) {
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c)
          if (px(x0 + x, y0 + y)[c] != px(x1 + x, y1 + y)[c]) return false;
    return true;
  };
  std::map<std::pair<Colour, Colour>, std::pair<int, int>> hfirst, vfirst;
  std::map<Colour, std::pair<int, int>> pfirst;
  for (int r = 0; r < t.rows; ++r)
    for (int c = 0; c < t.cols; ++c) {
      const CornerTile k = corner_tile(t.cells[std::size_t(r * t.cols + c)], t.colours);
      const int x = c * n, y = r * n;
      // the south border (this tile's sw, se) and the east one (ne, se)
      const auto [hs, hnew] = hfirst.try_emplace({k.sw, k.se}, x, y + n);
      if (!hnew && !same(hs->second.first, hs->second.second - m, x, y + n - m, n, 2 * m))
        bad.push_back("south border of cell " + std::to_string(r) + "," + std::to_string(c));
      const auto [vs, vnew] = vfirst.try_emplace({k.ne, k.se}, x + n, y);
      if (!vnew && !same(vs->second.first - m, vs->second.second, x + n - m, y, 2 * m, n))
        bad.push_back("east border of cell " + std::to_string(r) + "," + std::to_string(c));
      const auto [ps, pnew] = pfirst.try_emplace(k.nw, x, y);
      if (!pnew && !same(ps->second.first - m, ps->second.second - m, x - m, y - m, 2 * m, 2 * m))
        bad.push_back("north-west corner of cell " + std::to_string(r) + "," + std::to_string(c));
    }
  return bad;
}

TEST(TerrainTiles, EveryTexelShowsATerrainOfItsCornersAndEachCornerItsOwn) {
  for (const std::uint32_t c : {2u, 3u}) {
    const TerrainTileSet r = synthesize_terrain_tiles(channel_terrains(c), small_options(TileKind::Corner, c, 32));
    ASSERT_EQ(r.set.tiles.size(), std::size_t(c * c * c * c));
    const int n = r.set.tile_px;
    for (TileIndex t = 0; t < r.set.tiles.size(); ++t) {
      const CornerTile k = corner_tile(t, c);
      const std::set<int> corners = {int(k.nw), int(k.ne), int(k.sw), int(k.se)};
      std::map<int, int> shown;
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) ++shown[terrain_of(r.set.tiles[t].at(x, y))];
      for (const auto& [terrain, count] : shown) EXPECT_TRUE(corners.count(terrain)) << "tile " << t;
      // a corner's terrain keeps at least the square of side n/8 at that corner (the cuts stay
      // within n/4 of the tile's middle lines, the graph cut within n/8 of the cuts)
      for (const int terrain : corners) EXPECT_GE(shown[terrain], n * n / 64) << "tile " << t << " terrain " << terrain;
      const int at[4][2] = {{1, 1}, {n - 2, 1}, {1, n - 2}, {n - 2, n - 2}};
      const Colour want[4] = {k.nw, k.ne, k.sw, k.se};
      for (int q = 0; q < 4; ++q)
        EXPECT_EQ(terrain_of(r.set.tiles[t].at(at[q][0], at[q][1])), int(want[q])) << "tile " << t << " corner " << q;
    }
    double sum = 0;
    for (double f : r.texel_fraction) sum += f;
    EXPECT_NEAR(sum, 1.0, 1e-9);
  }
}

TEST(TerrainTiles, TheWrappedSheetsBorderStripsAgreeWhereverTheirColoursMeet) {
  const std::uint32_t c = 3;
  const TerrainTileSet r = synthesize_terrain_tiles(channel_terrains(c), small_options(TileKind::Corner, c, 32));
  const auto [sheet, packing] = packed_sheet(r.set);
  const int n = r.set.tile_px, m = TileGeometry(n).margin;
  const auto bad = strip_mismatches(sheet, packing, n, m);
  EXPECT_TRUE(bad.empty()) << bad.size() << " mismatches, first: " << bad.front();
  // The check can fail: two tiles of the sheet swapped break the borders around them.
  Tiling swapped = packing;
  std::swap(swapped.cells[0], swapped.cells[4]);
  EXPECT_FALSE(strip_mismatches(stitch_tiles(r.set, swapped), swapped, n, m).empty());
}

// The figures, on the fetched real textures (procedural stand-ins where the cache lacks
// them): C = 2 and 3, the wrapped sheet's strips, and the seam ratio of a 16 x 16 stochastic map.
TEST(TerrainTiles, RealTexturesJoinSeamlesslyOnTheSheetAndInAStochasticMap) {
  const std::vector<TerrainTexture> all = {
      {"grass", real_exemplar("grass")}, {"dirt", real_exemplar("oa-dirt")}, {"gravel", real_exemplar("gravel")}};
  for (const std::uint32_t c : {2u, 3u}) {
    SynthesisOptions o;
    o.tile_px = 64;
    o.threads = 2;
    o.seed = 3;
    const TerrainTileSet r = synthesize_terrain_tiles({all.begin(), all.begin() + c}, o);
    const auto [sheet, packing] = packed_sheet(r.set);
    const auto bad = strip_mismatches(sheet, packing, 64, TileGeometry(64).margin);
    EXPECT_TRUE(bad.empty()) << "C=" << c << ": " << bad.front();
    TilingRequest req;
    req.rows = req.cols = 16;
    req.seed = 7;
    const Tiling map = generate_tiling(complete_corner_set(c), req);
    const SeamStatistics st = seam_statistics(stitch_tiles(r.set, map), 64);
    EXPECT_LE(st.seam_ratio, 1.10) << "C=" << c;
    EXPECT_GT(st.seam_ratio, 0.5) << "C=" << c;
  }
}

TEST(TerrainTiles, TheSameSeedGivesTheSameTilesOnAnyThreadCount) {
  SynthesisOptions o = small_options(TileKind::Corner, 2, 32, 1);
  const TerrainTileSet one = synthesize_terrain_tiles(channel_terrains(2), o);
  o.threads = 3;
  const TerrainTileSet three = synthesize_terrain_tiles(channel_terrains(2), o);
  ASSERT_EQ(one.set.tiles.size(), three.set.tiles.size());
  for (std::size_t t = 0; t < one.set.tiles.size(); ++t) {
    EXPECT_EQ(one.set.tiles[t].pixels, three.set.tiles[t].pixels) << "tile " << t;
    EXPECT_EQ(one.set.sources[t], three.set.sources[t]) << "tile " << t;
  }
  o.seed = 6;
  EXPECT_NE(synthesize_terrain_tiles(channel_terrains(2), o).set.tiles[5].pixels, one.set.tiles[5].pixels);
}

TEST(TerrainTiles, RefusesWhatItCannotMake) {
  const SynthesisOptions o = small_options(TileKind::Corner, 2, 32);
  std::vector<TerrainTexture> one = channel_terrains(1);
  EXPECT_THROW(synthesize_terrain_tiles(one, o), InputError);
  std::vector<TerrainTexture> twice = channel_terrains(2);
  twice[1].name = twice[0].name;
  EXPECT_THROW(synthesize_terrain_tiles(twice, o), InputError);
  std::vector<TerrainTexture> odd = channel_terrains(2);
  odd[0].name = "a b";
  EXPECT_THROW(synthesize_terrain_tiles(odd, o), InputError);
  SynthesisOptions wang = o;
  wang.kind = TileKind::Wang;
  EXPECT_THROW(synthesize_terrain_tiles(channel_terrains(2), wang), InputError);
  SynthesisOptions big = o;
  big.tile_px = 512;  // larger than the 160-pixel textures allow
  EXPECT_THROW(synthesize_terrain_tiles(channel_terrains(2), big), InputError);
}

}  // namespace
}  // namespace tilekit::test
