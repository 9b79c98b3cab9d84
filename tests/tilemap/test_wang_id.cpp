// Tiled's wangid of every tile, the .tsx/.tmx text, and the refusals of the Wang-set reader.
#include <gtest/gtest.h>

#include <pugixml.hpp>

#include "base/error.hpp"
#include "tilemap/tiled_files.hpp"
#include "tilemap/tiled_tileset.hpp"
#include "tilemap/tsx_reader.hpp"
#include "tilemap/wang_id.hpp"
#include "tilemap/xml_text.hpp"

namespace tilekit::tilemap {
namespace {

TEST(WangId, CornerTileFillsTheFourCornerEntriesInTiledsOrder) {
  // Tiled's order: top, top-right, right, bottom-right, bottom, bottom-left, left, top-left.
  const CornerTile t{.ne = 0, .se = 1, .sw = 2, .nw = 3};
  EXPECT_EQ(wang_id_of(t), (WangId{0, 1, 0, 2, 0, 3, 0, 4}));
  EXPECT_EQ(format_wang_id(wang_id_of(t)), "0,1,0,2,0,3,0,4");
}

TEST(WangId, WangTileFillsTheFourEdgeEntriesInTiledsOrder) {
  const WangTile t{.n = 0, .e = 1, .s = 2, .w = 3};
  EXPECT_EQ(wang_id_of(t), (WangId{1, 0, 2, 0, 3, 0, 4, 0}));
  EXPECT_EQ(wang_type_name(TileKind::Wang), "edge");
  EXPECT_EQ(wang_type_name(TileKind::Corner), "corner");
}

TEST(WangId, EveryTileOfTheCompleteSetsRoundTrips) {
  for (std::uint32_t c : {1u, 2u, 3u, 5u})
    for (TileIndex i = 0; i < c * c * c * c; ++i) {
      EXPECT_EQ(corner_index(corner_tile_of(wang_id_of(TileKind::Corner, c, i), c, "t"), c), i);
      EXPECT_EQ(wang_index(wang_tile_of(wang_id_of(TileKind::Wang, c, i), c, "t"), c), i);
      EXPECT_EQ(parse_wang_id(format_wang_id(wang_id_of(TileKind::Corner, c, i)), "t"),
                wang_id_of(TileKind::Corner, c, i));
    }
}

TEST(WangId, RefusesUnsetMixedAndOutOfRangeEntries) {
  EXPECT_THROW(corner_tile_of({0, 1, 0, 0, 0, 1, 0, 1}, 2, "t"), InputError);  // bottom-right unset
  EXPECT_THROW(corner_tile_of({1, 1, 0, 1, 0, 1, 0, 1}, 2, "t"), InputError);  // an edge set: mixed
  EXPECT_THROW(corner_tile_of({0, 3, 0, 1, 0, 1, 0, 1}, 2, "t"), InputError);  // colour 3 of 2
  EXPECT_THROW(wang_tile_of({1, 0, 1, 0, 0, 0, 1, 0}, 2, "t"), InputError);    // bottom unset
  EXPECT_THROW(wang_tile_of({1, 1, 1, 0, 1, 0, 1, 0}, 2, "t"), InputError);    // a corner set: mixed
  try {
    corner_tile_of({0, 1, 0, 0, 0, 1, 0, 1}, 2, "f.tsx, tile 7");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("f.tsx, tile 7: the bottom-right entry"), std::string::npos) << e.what();
  }
}

TEST(WangId, ParseRefusesAnythingButEightNumbers) {
  for (const char* bad : {"", "0,1,0,1,0,1,0", "0,1,0,1,0,1,0,1,0", "0,1,0,1,0,1,0,x", "0,1,0,1,0,1,0,256",
                          "0x11111111", "0,1,0,1,0,1,0,-1", "0,1,0,1,0,1,0,1,"})
    EXPECT_THROW(parse_wang_id(bad, "t"), InputError) << bad;
  EXPECT_EQ(parse_wang_id("0,255,0,1,0,1,0,1", "t"), (WangId{0, 255, 0, 1, 0, 1, 0, 1}));
}

TEST(XmlText, EscapesMarkupAndRefusesControlCharacters) {
  EXPECT_EQ(xml_escape("a<b & \"c\" 'd'>", "name"), "a&lt;b &amp; &quot;c&quot; &apos;d&apos;&gt;");
  EXPECT_THROW(xml_escape(std::string("a\x01") + "b", "name"), InputError);
  EXPECT_THROW(xml_escape("\xff", "name"), InputError);
  EXPECT_EQ(file_stem("a<b & \"c\"/../x"), "a_b____c__.._x");
  EXPECT_EQ(file_stem(".."), "tileset..");
}

TEST(TiledSheet, IsTheConstructedPackingWithATileIdPerTile) {
  const TiledSheet s = sheet_layout(TileKind::Corner, 3);
  EXPECT_EQ(s.packing.rows, 9);
  EXPECT_EQ(s.packing.cols, 9);
  for (TileIndex i = 0; i < 81; ++i) EXPECT_EQ(s.packing.cells[s.tile_id[i]], i);
  EXPECT_THROW(sheet_layout(TileKind::Corner, 0), InputError);
  EXPECT_THROW(sheet_layout(TileKind::Wang, kMaxSheetColours + 1), InputError);
  EXPECT_THROW(sheet_layout(TileKind::Window, 2), InputError);
}

TEST(TsxText, ReadsBackAsTheCompleteSetWithItsNameEscaped) {
  for (const TileKind kind : {TileKind::Corner, TileKind::Wang}) {
    const TiledSheet s = sheet_layout(kind, 3);
    const std::string name = "grass <&> \"sand\"";
    const std::string text = tsx_text(s, {name, "x&y.png", 16, true, {}, {}});
    pugi::xml_document doc;
    ASSERT_TRUE(doc.load_string(text.c_str()));
    EXPECT_EQ(std::string(doc.child("tileset").attribute("name").value()), name);
    EXPECT_EQ(std::string(doc.child("tileset").child("image").attribute("source").value()), "x&y.png");
    const ImportedWangSet w = parse_tiled_wang_set(text, "mem.tsx");
    EXPECT_EQ(w.set.kind(), kind);
    EXPECT_EQ(w.set.name(), name);
    EXPECT_EQ(w.set.size(), 81u);
    EXPECT_EQ(w.colour_names.size(), 3u);
    for (std::size_t k = 0; k < w.set.size(); ++k)  // tile k of the set sits at its Tiled tile id in the sheet
      EXPECT_EQ(s.packing.cells[std::size_t(w.tile_ids[k])], w.set.index_of(k));
  }
}

TEST(TmxText, WritesGidsOfTheSheetsTileIdsRowByRow) {
  const TiledSheet s = sheet_layout(TileKind::Corner, 2);
  Tiling map(TileKind::Corner, 2, 2, 3, false);
  map.cells = {0, 1, 2, 3, 4, 15};
  const std::string text = tmx_text(s, map, "t.tsx", 8);
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_string(text.c_str()));
  const std::string csv = doc.child("map").child("layer").child("data").text().get();
  const std::string want = "\n" + std::to_string(s.tile_id[0] + 1) + "," + std::to_string(s.tile_id[1] + 1) + "," +
                           std::to_string(s.tile_id[2] + 1) + ",\n" + std::to_string(s.tile_id[3] + 1) + "," +
                           std::to_string(s.tile_id[4] + 1) + "," + std::to_string(s.tile_id[15] + 1) + "\n";
  EXPECT_EQ(csv, want);
  Tiling wang(TileKind::Wang, 2, 1, 1, false);
  EXPECT_THROW(tmx_text(s, wang, "t.tsx", 8), InputError);
}

std::string tsx(const std::string& type, const std::string& tiles, int colours = 2) {
  std::string s = "<?xml version=\"1.0\"?>\n<tileset name=\"t\"><wangsets><wangset name=\"w\" type=\"" + type + "\">";
  for (int c = 0; c < colours; ++c) s += "<wangcolor name=\"c" + std::to_string(c) + "\" color=\"#ff0000\"/>";
  return s + tiles + "</wangset></wangsets></tileset>";
}

void expect_refused(const std::string& text, const std::string& words) {
  try {
    parse_tiled_wang_set(text, "in.tsx");
    ADD_FAILURE() << "accepted: " << text;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

TEST(TsxImport, RefusesWhatATileSetCannotRepresent) {
  expect_refused(tsx("mixed", "<wangtile tileid=\"0\" wangid=\"1,1,1,1,1,1,1,1\"/>"), "\"mixed\"");
  expect_refused(tsx("corner", "<wangtile tileid=\"0\" wangid=\"0,1,0,1,0,0,0,1\"/>"), "bottom-left entry");
  expect_refused(tsx("corner", "<wangtile tileid=\"0\" wangid=\"1,1,0,1,0,1,0,1\"/>"), "a mixed tile");
  expect_refused(tsx("edge", "<wangtile tileid=\"0\" wangid=\"1,0,1,0,1,0,0,0\"/>"), "left entry");
  expect_refused(tsx("corner", "<wangtile tileid=\"0\" wangid=\"0,3,0,1,0,1,0,1\"/>"), "has 2 colours");
  expect_refused(tsx("corner", "<wangtile tileid=\"x\" wangid=\"0,1,0,1,0,1,0,1\"/>"), "tileid");
  expect_refused(tsx("corner", ""), "no tiles");
  expect_refused(tsx("corner", "<wangtile tileid=\"0\" wangid=\"0,1,0,1,0,1,0,1\"/>", 0), "no colours");
  expect_refused(tsx("blob", ""), "not corner, edge or mixed");
  expect_refused("<tileset name=\"t\"/>", "no Wang set");
  expect_refused("<map/>", "a Tiled map");
  expect_refused("<tileset><wangsets><wangset", "not XML");
  expect_refused("\xff", "UTF-8");
  expect_refused("<tileset><wangsets><wangset name=\"w\"><wangcornercolor/></wangset></wangsets></tileset>",
                 "before 1.5");
  try {
    parse_tiled_wang_set(tsx("corner", "<wangtile tileid=\"0\" wangid=\"0,1,0,1,0,1,0,1\"/>"), "in.tsx", "nope");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no Wang set named \"nope\" (the file has: w)"), std::string::npos);
  }
}

TEST(TsxImport, MergesVariantsAndKeepsTheFirstTileId) {
  const ImportedWangSet w = parse_tiled_wang_set(tsx("edge",
                                                     "<wangtile tileid=\"4\" wangid=\"1,0,2,0,1,0,2,0\"/>"
                                                     "<wangtile tileid=\"5\" wangid=\"1,0,2,0,1,0,2,0\"/>"
                                                     "<wangtile tileid=\"9\" wangid=\"2,0,2,0,2,0,2,0\"/>"),
                                                 "in.tsx");
  EXPECT_EQ(w.set.kind(), TileKind::Wang);
  EXPECT_EQ(w.set.size(), 2u);
  EXPECT_EQ(w.wang_tiles, 3u);
  EXPECT_EQ(w.tile_ids, (std::vector<int>{4, 9}));
  EXPECT_EQ(w.set.wang_tiles()[0], (WangTile{0, 1, 0, 1}));
}

}  // namespace
}  // namespace tilekit::tilemap
