// `tilekit tiled tileset|map|import` end to end: --help, one JSON object, exit 2 on bad input with
// nothing written, the import printing the set as `tileset show` does, and the map against
// `tilekit tile --algo direct`'s picture as rendered by Tiled's tmxrasterizer.
#include <gtest/gtest.h>

#include "image/image.hpp"
#include "tests/tilemap/tiled_checker.hpp"

namespace tilekit::test {
namespace {

TEST(TiledCli, EverySubcommandHasHelp) {
  const CliResult group = run_cli("tiled --help");
  EXPECT_EQ(group.code, 0);
  for (const char* sub : {"tileset", "map", "import"}) {
    EXPECT_NE(group.out.find(std::string("  ") + sub + " "), std::string::npos) << sub;
    const CliResult r = run_cli(std::string("tiled ") + sub + " --help");
    EXPECT_EQ(r.code, 0) << sub;
    EXPECT_NE(r.out.find("Usage: tilekit tiled " + std::string(sub)), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("--json"), std::string::npos) << sub;
  }
}

TEST(TiledCli, TilesetAndMapPrintOneJsonObjectAndWriteTheirFiles) {
  TempDir d;
  CliResult r =
      run_cli("tiled tileset --kind wang --colors 2 --tile-px 8 --name 'a<b & \"c\"' --json --out " + q(d / "ts"));
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json j = r.json();
  EXPECT_EQ(j.at("name"), "a<b & \"c\"");
  EXPECT_EQ(j.at("tiles"), 16);
  EXPECT_TRUE(std::filesystem::exists(j.at("tsx").get<std::string>()));
  EXPECT_TRUE(std::filesystem::exists(j.at("png").get<std::string>()));
  r = run_cli("tiled map --kind corner --colors 2 --size 10x6 --seed 4 --json --out " + q(d / "m"));
  ASSERT_EQ(r.code, 0) << r.err;
  j = r.json();
  EXPECT_EQ(j.at("width"), 10);
  EXPECT_EQ(j.at("height"), 6);
  EXPECT_TRUE(std::filesystem::exists(j.at("tmx").get<std::string>()));
  EXPECT_TRUE(std::filesystem::exists(j.at("tileset").at("tsx").get<std::string>()));
}

TEST(TiledCli, BadInputExits2WithOneLineAndWritesNothing) {
  TempDir d;
  write_text(d / "mixed.tsx",
             "<tileset><wangsets><wangset name=\"w\" type=\"mixed\"><wangcolor/>"
             "<wangtile tileid=\"0\" wangid=\"1,1,1,1,1,1,1,1\"/></wangset></wangsets></tileset>");
  const std::string out = " --out " + q(d / "out");
  for (const std::string& args : std::vector<std::string>{
           "tiled tileset --kind hex --colors 2" + out, "tiled tileset --kind corner --colors 0" + out,
           "tiled tileset --kind corner --colors 2 --tiles " + q(d / "missing") + out,
           "tiled tileset --kind corner --colors 2 --tile-px 1" + out, "tiled tileset --colors 2",
           "tiled tileset --kind corner --colors 17" + out, "tiled map --kind corner --colors 2 --size 0x4" + out,
           "tiled map --kind corner --colors 2 --size 4" + out, "tiled map --kind wang --colors 2 --size 70000x1" + out,
           "tiled import " + q(d / "mixed.tsx"), "tiled import " + q(d / "none.tsx"), "tiled import " + q(d / "out")}) {
    const CliResult r = run_cli(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(d / "out")) << args;
  }
}

TEST(TiledCli, ImportPrintsTheSetLikeTilesetShow) {
  TempDir d;
  ASSERT_EQ(run_cli("tiled tileset --kind corner --colors 3 --out " + q(d / "ts")).code, 0);
  const CliResult r = run_cli("tiled import --json " + q(d / "ts/corner-3.tsx"));
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = r.json();
  const CliResult show = run_cli("tileset show complete-corner-3 --json");
  ASSERT_EQ(show.code, 0);
  const nlohmann::json s = show.json();
  for (const char* key : {"kind", "tiles", "colors", "format"}) EXPECT_EQ(j.at(key), s.at(key)) << key;
  std::set<std::vector<int>> a, b;
  for (const auto& t : j.at("list")) a.insert(t.get<std::vector<int>>());
  for (const auto& t : s.at("list")) b.insert(t.get<std::vector<int>>());
  EXPECT_EQ(a, b);
  EXPECT_EQ(j.at("tiled_type"), "corner");
  const CliResult human = run_cli("tiled import " + q(d / "ts/corner-3.tsx"));
  EXPECT_EQ(human.code, 0);
  EXPECT_NE(human.out.find("81 corner tiles"), std::string::npos) << human.out;
}

// Texture tiles (`texture tiles --out DIR` names them tile-NNNN.png by index) make a tileset as
// drawn tiles do: the tile at each Tiled tile id of the sheet is the image of that tile's index.
TEST(TiledCli, TextureTilesMakeASheetWithEachTileAtItsTiledId) {
  TempDir d;
  const std::string exemplar = std::string(TILEKIT_SOURCE_DIR) + "/docs/images/texture-grid-gravel.png";
  ASSERT_EQ(run_cli("texture tiles --exemplar " + q(exemplar) + " --kind wang --colors 2 --tile-px 16 --threads 1 " +
                    "--out " + q(d / "tex"))
                .code,
            0);
  ASSERT_EQ(run_cli("tiled tileset --kind wang --colors 2 --tiles " + q(d / "tex") + " --out " + q(d / "ts")).code, 0);
  const CliResult r = run_cli("tiled import --json " + q(d / "ts/wang-2.tsx"));
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = r.json();
  const Image sheet = read_image(d / "ts/wang-2.png");
  ASSERT_EQ(sheet.width, 4 * 16);
  ASSERT_EQ(j.at("list").size(), 16u);
  for (std::size_t k = 0; k < 16; ++k) {
    const auto c = j.at("list").at(k).get<std::vector<int>>();    // n s w e
    const int index = ((c[0] * 2 + c[3]) * 2 + c[1]) * 2 + c[2];  // thesis eq. 2.2
    const Image tile =
        read_image(d / ("tex/tile-" + std::string(index < 10 ? "000" : "00") + std::to_string(index) + ".png"));
    const int id = j.at("tile_ids").at(k).get<int>(), x0 = id % 4 * 16, y0 = id / 4 * 16;
    int differ = 0;
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) differ += sheet.get(x0 + x, y0 + y) != tile.get(x, y);
    EXPECT_EQ(differ, 0) << "tile " << index << " at Tiled id " << id;
  }
}

TEST(TiledCli, TmxrasterizerDrawsTheMapAsTileAlgoDirectDoes) {
  if (!tiled::installed()) GTEST_SKIP() << tiled::kSkip;
  TempDir d;
  for (const char* kind : {"corner", "wang"}) {
    const std::string k = kind;
    ASSERT_EQ(
        run_cli("tiled map --kind " + k + " --colors 3 --size 20x12 --seed 9 --tile-px 12 --out " + q(d / "m")).code,
        0);
    ASSERT_EQ(run_cli("tile --set complete-" + k + "-3 --algo direct --size 20x12 --seed 9 --tile-size 12 --out " +
                      q(d / "own.png"))
                  .code,
              0);
    ASSERT_EQ(tiled::run_qt("tmxrasterizer", q(d / ("m/" + k + "-3-map.tmx")) + " " + q(d / "tiled.png")), 0);
    const Image a = read_image(d / "tiled.png"), b = read_image(d / "own.png");
    ASSERT_EQ(a.width, b.width);
    ASSERT_EQ(a.height, b.height);
    EXPECT_TRUE(a.pixels == b.pixels) << kind;
  }
}

}  // namespace
}  // namespace tilekit::test
