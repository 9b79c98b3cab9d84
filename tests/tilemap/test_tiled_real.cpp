// Tilekit's Tiled files against the real Tiled 1.8 (headless): Tiled reads every tileset and map
// (exit 0), the independent checker of tests/tilemap/tiled_checker.hpp finds every neighbour pair
// agreeing in Tiled's exported JSON (the sheet on the torus, the map without wrap-around), and
// tmxrasterizer renders the map to exactly Tilekit's own picture of it. Skipped with a message
// where Tiled is not installed.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "atlas/render.hpp"
#include "image/image.hpp"
#include "tests/tilemap/tiled_checker.hpp"
#include "tilemap/tiled_files.hpp"
#include "tilemap/tsx_reader.hpp"

namespace tilekit::test {
namespace {

nlohmann::json exported(const std::string& what, const std::string& in, const std::string& out,
                        const std::string& extra = "") {
  EXPECT_EQ(tiled::run_qt("tiled", extra + "--export-" + what + " json " + q(in) + " " + q(out)), 0) << in;
  return nlohmann::json::parse(slurp(out));
}

tilemap::TilesetRequest request(TileKind kind, std::uint32_t colours, const std::string& out, int px = 8) {
  return {kind, colours, "", px, "", out, {}, {}};
}

TEST(TiledReal, EverySheetTilesSeamlesslyOnTheTorusInTiledsExport) {
  if (!tiled::installed()) GTEST_SKIP() << tiled::kSkip;
  TempDir d;
  for (const auto& [kind, colours] : {std::pair{TileKind::Corner, 2u},
                                      {TileKind::Corner, 3u},
                                      {TileKind::Corner, 4u},
                                      {TileKind::Wang, 2u},
                                      {TileKind::Wang, 3u}}) {
    const auto o = tilemap::write_tiled_tileset(request(kind, colours, d / "ts"));
    const tiled::WangSetJson w = tiled::wang_set_of(exported("tileset", o.tsx_path, d / "ts.json"));
    const std::string label = o.name;
    EXPECT_EQ(w.type, kind == TileKind::Corner ? "corner" : "edge") << label;
    EXPECT_EQ(w.colours, int(colours)) << label;
    const int n = int(colours * colours * colours * colours);
    ASSERT_EQ(w.tilecount, n) << label;
    ASSERT_EQ(int(w.wangid.size()), n) << label;
    std::set<std::array<int, 8>> distinct;
    for (const auto& [id, wid] : w.wangid) distinct.insert(wid);
    EXPECT_EQ(int(distinct.size()), n) << label << ": every tile of the complete set once";
    const auto bad = tiled::mismatches(w, tiled::sheet_ids(w), n / w.columns, w.columns, true);
    EXPECT_TRUE(bad.empty()) << label << ": " << bad.front();
  }
}

TEST(TiledReal, MapNeighboursAgreeInTiledsExport) {
  if (!tiled::installed()) GTEST_SKIP() << tiled::kSkip;
  TempDir d;
  for (const auto kind : {TileKind::Corner, TileKind::Wang}) {
    const auto o = tilemap::write_tiled_map({request(kind, 3, d / "m"), 37, 23, 11});
    exported("map", o.tmx_path, d / "plain.json");  // as written: an external tileset
    const nlohmann::json j = exported("map", o.tmx_path, d / "m.json", "--embed-tilesets ");
    ASSERT_EQ(j.at("width").get<int>(), 37);
    ASSERT_EQ(j.at("height").get<int>(), 23);
    const auto& ts = j.at("tilesets").at(0);
    const tiled::WangSetJson w = tiled::wang_set_of(ts);
    const int first = ts.at("firstgid").get<int>();
    std::vector<int> ids;
    for (const auto& g : j.at("layers").at(0).at("data")) ids.push_back(g.get<int>() - first);
    ASSERT_EQ(ids.size(), 37u * 23u);
    const auto bad = tiled::mismatches(w, ids, 23, 37, false);
    EXPECT_TRUE(bad.empty()) << o.tileset.name << ": " << bad.front();
  }
}

TEST(TiledReal, TmxrasterizerDrawsExactlyTilekitsPictureOfTheMap) {
  if (!tiled::installed()) GTEST_SKIP() << tiled::kSkip;
  TempDir d;
  for (const auto kind : {TileKind::Corner, TileKind::Wang}) {
    const auto o = tilemap::write_tiled_map({request(kind, 3, d / "m", 16), 24, 15, 3});
    ASSERT_EQ(tiled::run_qt("tmxrasterizer", q(o.tmx_path) + " " + q(d / "tiled.png")), 0);
    const Image tiled_png = read_image(d / "tiled.png");
    const std::vector<Rgb> own = atlas::rasterise(atlas::draw_tiling(o.map, {16, false}));
    ASSERT_EQ(tiled_png.width, 24 * 16);
    ASSERT_EQ(tiled_png.height, 15 * 16);
    int differ = 0;
    for (int y = 0; y < tiled_png.height; ++y)
      for (int x = 0; x < tiled_png.width; ++x)
        differ += tiled_png.get(x, y) != own[std::size_t(y * tiled_png.width + x)] || tiled_png.at(x, y)[3] != 255;
    EXPECT_EQ(differ, 0) << o.tileset.name << ": pixels that differ";
  }
}

// Tiles a user drew (here: each tile's index written into its pixels, so that every tile looks
// different) keep their place: Tiled's render shows in each cell the image of the cell's tile.
TEST(TiledReal, DrawnTilesLandInTheCellsOfTheirTiles) {
  if (!tiled::installed()) GTEST_SKIP() << tiled::kSkip;
  TempDir d;
  std::filesystem::create_directories(d / "tiles");
  auto tile_rgb = [](TileIndex i, int x, int y) {
    return Rgb{std::uint8_t(i * 16 + x), std::uint8_t(255 - i * 8), std::uint8_t(y * 20)};
  };
  for (TileIndex i = 0; i < 16; ++i) {
    Image img(6, 6);
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 6; ++x) img.set(x, y, tile_rgb(i, x, y));
    write_png(d / fmt::format("tiles/tile-{:02}.png", i), img);
  }
  tilemap::TilesetRequest req = request(TileKind::Corner, 2, d / "m");
  req.tiles_dir = d / "tiles";
  const auto o = tilemap::write_tiled_map({req, 9, 7, 5});
  EXPECT_EQ(o.tileset.tile_px, 6);
  ASSERT_EQ(tiled::run_qt("tmxrasterizer", q(o.tmx_path) + " " + q(d / "tiled.png")), 0);
  const Image img = read_image(d / "tiled.png");
  ASSERT_EQ(img.width, 9 * 6);
  int differ = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) differ += img.get(x, y) != tile_rgb(o.map.at(y / 6, x / 6), x % 6, y % 6);
  EXPECT_EQ(differ, 0);
}

// The reader against Tiled's own writer: a tileset that Tiled saved again (`--export-tileset tsx`)
// reads back as the complete set, its user-supplied name (markup characters included) intact.
TEST(TiledReal, ImportReadsTheTilesetsTiledSavesAgain) {
  if (!tiled::installed()) GTEST_SKIP() << tiled::kSkip;
  TempDir d;
  for (const auto kind : {TileKind::Corner, TileKind::Wang}) {
    tilemap::TilesetRequest req = request(kind, 3, d / "ts");
    req.name = "grass <&> \"sand\" 'n'";
    const auto o = tilemap::write_tiled_tileset(req);
    EXPECT_EQ(tiled::run_qt("tiled", "--export-tileset tsx " + q(o.tsx_path) + " " + q(d / "again.tsx")), 0);
    const nlohmann::json j = exported("tileset", d / "again.tsx", d / "again.json");
    EXPECT_EQ(j.at("name").get<std::string>(), req.name);
    const tilemap::ImportedWangSet w = tilemap::read_tiled_wang_set(d / "again.tsx");
    EXPECT_EQ(w.set.kind(), kind);
    EXPECT_EQ(w.set.name(), req.name);
    EXPECT_EQ(w.set.size(), 81u);
    EXPECT_EQ(w.wang_tiles, 81u);
    EXPECT_EQ(w.type, kind == TileKind::Corner ? "corner" : "edge");
  }
}

// The checker can fail: two tiles of a packed sheet swapped break the torus at both places.
TEST(TiledChecker, FindsTwoSwappedTilesInAPackedSheet) {
  if (!tiled::installed()) GTEST_SKIP() << tiled::kSkip;
  TempDir d;
  const auto o = tilemap::write_tiled_tileset(request(TileKind::Corner, 2, d / "ts"));
  tiled::WangSetJson w = tiled::wang_set_of(exported("tileset", o.tsx_path, d / "ts.json"));
  ASSERT_TRUE(tiled::mismatches(w, tiled::sheet_ids(w), 4, 4, true).empty());
  std::swap(w.wangid[0], w.wangid[5]);
  EXPECT_FALSE(tiled::mismatches(w, tiled::sheet_ids(w), 4, 4, true).empty());
  w.wangid[0][0] = 1;  // an edge entry in a corner set
  std::swap(w.wangid[0], w.wangid[5]);
  EXPECT_FALSE(tiled::mismatches(w, tiled::sheet_ids(w), 4, 4, true).empty());
}

}  // namespace
}  // namespace tilekit::test
