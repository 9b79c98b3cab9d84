#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tilesets/compact_sets.hpp"
#include "base/error.hpp"
#include "tilesets/tile_set.hpp"
#include "tilesets/tile_set_io.hpp"

using namespace tilekit;

TEST(TileEncoding, WangIndexRoundTripsForEveryTileOfC3) {
  for (TileIndex i = 0; i < 81; ++i) EXPECT_EQ(wang_index(wang_tile(i, 3), 3), i);
  // thesis eq. (2.2): i = ((N C + E) C + S) C + W
  EXPECT_EQ(wang_index(WangTile{1, 2, 0, 1}, 3), ((1u * 3 + 2) * 3 + 0) * 3 + 1);
}

TEST(TileEncoding, CornerIndexFollowsEq25) {
  EXPECT_EQ(corner_index(CornerTile{1, 0, 1, 1}, 2), 0b1011u);
  for (TileIndex i = 0; i < 256; ++i) EXPECT_EQ(corner_index(corner_tile(i, 4), 4), i);
}

TEST(TileEncoding, MixedRadixCoversEveryIndexOnce) {
  const std::uint32_t ch = 2, cv = 3;
  std::vector<int> hit(complete_size(ch, cv), 0);
  for (Colour n = 0; n < ch; ++n)
    for (Colour s = 0; s < ch; ++s)
      for (Colour e = 0; e < cv; ++e)
        for (Colour w = 0; w < cv; ++w) {
          TileIndex i = wang_index({n, e, s, w}, ch, cv);
          ASSERT_LT(i, hit.size());
          ++hit[i];
          EXPECT_EQ(wang_tile(i, ch, cv), (WangTile{n, e, s, w}));
        }
  for (int h : hit) EXPECT_EQ(h, 1);
}

TEST(TileSetSizes, CompleteSetsHaveCToTheFourthTiles) {
  const std::size_t expected[] = {16, 81, 256, 625, 1296, 2401, 4096};
  for (std::uint32_t c = 2; c <= 8; ++c) {
    EXPECT_EQ(complete_wang_set(c, c).size(), expected[c - 2]);
    EXPECT_EQ(complete_corner_set(c).size(), expected[c - 2]);
  }
  EXPECT_EQ(complete_wang_set(2, 3).size(), 36u);
}

TEST(TileSetSizes, CompactSetsHave2C2C3And2C3Tiles) {
  for (std::uint32_t c = 2; c <= 8; ++c) {
    EXPECT_EQ(compact_wang_set(c).size(), 2 * c * c);
    EXPECT_EQ(compact_wang3_set(c).size(), c * c * c);
    EXPECT_EQ(compact_corner_set(c).size(), 2 * c * c * c);
  }
}

TEST(TileSetSizes, CompactCornerSetOverTwoColoursIsTheCompleteSet) {
  EXPECT_EQ(compact_corner_set(2).size(), 16u);
}

TEST(TileSetFactories, RejectImpossibleColourCounts) {
  EXPECT_THROW(complete_corner_set(0), InputError);
  EXPECT_THROW(complete_wang_set(256, 256), InputError);
  EXPECT_THROW(resolve_tile_set("complete-corner-0"), InputError);
  EXPECT_THROW(resolve_tile_set("complete-wang-256"), InputError);
}

TEST(TileSetFiles, ReferenceSetsLoadWithTheirPublishedSizes) {
  struct Case {
    const char* name;
    std::size_t tiles;
    std::uint32_t colours;
  } cases[] = {{"culik-13", 13, 5}, {"kari-14", 14, 6}, {"ammann-gs-16", 16, 6}, {"jeandel-rao-11", 11, 4},
               {"labbe-19", 19, 0}};
  for (auto& c : cases) {
    TileSet s = resolve_tile_set(c.name);
    EXPECT_EQ(s.size(), c.tiles) << c.name;
    if (c.colours) {
      EXPECT_EQ(s.colours(), c.colours) << c.name;
    }
    EXPECT_FALSE(s.source().empty()) << c.name;
  }
}

TEST(TileSetFiles, TextAndJsonRoundTrip) {
  TileSet s = resolve_tile_set("kari-14");
  TileSet t = parse_tile_set(format_tile_set_text(s), "roundtrip.tiles");
  TileSet u = parse_tile_set(tile_set_to_json(s).dump(), "roundtrip.json");
  ASSERT_EQ(t.size(), s.size());
  ASSERT_EQ(u.size(), s.size());
  for (std::size_t k = 0; k < s.size(); ++k) {
    EXPECT_EQ(t.wang_tiles()[k], s.wang_tiles()[k]);
    EXPECT_EQ(u.wang_tiles()[k], s.wang_tiles()[k]);
  }
  TileSet c = complete_corner_set(2);
  TileSet d = parse_tile_set(format_tile_set_text(c), "c.tiles");
  EXPECT_EQ(d.kind(), TileKind::Corner);
  for (std::size_t k = 0; k < c.size(); ++k) EXPECT_EQ(d.corner_tiles()[k], c.corner_tiles()[k]);
}

static std::string error_of(const std::string& text) {
  try {
    parse_tile_set(text, "bad.tiles");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(TileSetFiles, MalformedInputNamesFileLineAndProblem) {
  EXPECT_EQ(error_of("0 1 2\n"), "bad.tiles:1: expected 4 colours (n s w e), found 3 fields");
  EXPECT_EQ(error_of("# c\n0 1 x 2\n"), "bad.tiles:2: 'x' is not a colour (a non-negative integer)");
  EXPECT_EQ(error_of("0 1 -1 2\n"), "bad.tiles:1: negative colour -1");
  EXPECT_EQ(error_of("# colors: 2\n0 1 2 1\n"), "bad.tiles:2: colour 2 is out of range for 2 colours");
  EXPECT_EQ(error_of("# only comments\n"), "bad.tiles: the tile set has no tiles");
  EXPECT_EQ(error_of("0 1 1 0\n1 1 0 0\n0 1 1 0\n"), "bad.tiles:3: duplicate tile: repeats the tile of bad.tiles:1 (0 1 1 0)");
  EXPECT_EQ(error_of("# kind: hex\n"), "bad.tiles:1: unknown kind 'hex' (expected wang or corner)");
  EXPECT_EQ(error_of("{\"tiles\": [[0,1,2]]}"), "bad.tiles: tiles[0]: expected an array of 4 elements, got 3");
  EXPECT_NE(error_of("{\"tiles\": ").find("invalid JSON"), std::string::npos);
}

TEST(CornerToWang, EquivalentSetHasCSquaredColoursAndSameSize) {
  TileSet w = corner_to_wang(complete_corner_set(2));
  EXPECT_EQ(w.kind(), TileKind::Wang);
  EXPECT_EQ(w.size(), 16u);
  EXPECT_EQ(w.colours(), 4u);  // thesis Fig. 2.7: 16 tiles over 4 colours
}

TEST(TileSetFiles, JsonFormKeepsTheSourceLine) {
  // Found by fuzz_tile_set: the JSON form dropped "# source:", so it did not read back whole.
  const TileSet set = parse_tile_set("# source: Culik 1996\n0 1 3 4\n0 3 3 3\n", "c.tiles");
  const TileSet again = parse_tile_set(tile_set_to_json(set).dump(), "c.json");
  EXPECT_EQ(again.source(), "Culik 1996");
  EXPECT_EQ(again.size(), 2u);
}
