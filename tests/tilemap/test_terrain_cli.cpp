// `tilekit texture terrain` end to end: terrain textures in, the tile set folder (which `texture
// atlas` takes), the packed sheet and a Tiled tileset out. Tiled 1.8 reads the tileset (exit 0);
// from Tiled's own JSON the independent checker finds every neighbour pair of the sheet agreeing
// on the torus, the Wang colours carry the terrains' names, and every tile's corners in the sheet
// PNG show the terrain its wangid names (terrains of one dominant channel each, so a texel says
// which terrain it is). Bad input: exit 2, one line, nothing written.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "tests/texture/texture_fixtures.hpp"
#include "tests/tilemap/tiled_checker.hpp"

namespace tilekit::test {
namespace {

// Terrain k of three: channel k textured in 110..250, the others below 60.
std::string write_channel_texture(const std::string& path, int k) {
  Image img = synthetic_image(160, 160, 31 + std::uint64_t(k));
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      std::uint8_t* p = img.at(x, y);
      const int v = (p[0] + p[1] + p[2]) / 3;
      for (int c = 0; c < 3; ++c) p[c] = std::uint8_t(c == k ? 110 + v * 140 / 255 : v * 60 / 255);
    }
  write_png(path, img);
  return path;
}

int dominant_channel(const Image& img, int x, int y) {
  const std::uint8_t* p = img.at(x, y);
  return p[0] >= p[1] && p[0] >= p[2] ? 0 : p[1] >= p[2] ? 1 : 2;
}

TEST(TerrainCli, HasHelp) {
  const CliResult r = run_cli("texture terrain --help");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("Usage: tilekit texture terrain"), std::string::npos) << r.out;
  for (const char* flag : {"--terrain", "--out", "--tiled", "--tile-px", "--seed", "--json"})
    EXPECT_NE(r.out.find(flag), std::string::npos) << flag;
}

TEST(TerrainCli, WritesTheSetTheSheetAndATilesetTiledReads) {
  TempDir d;
  const std::string terrains = " --terrain red=" + q(write_channel_texture(d / "r.png", 0)) +
                               " --terrain green=" + q(write_channel_texture(d / "g.png", 1)) +
                               " --terrain blue=" + q(write_channel_texture(d / "b.png", 2));
  const CliResult r = run_cli("texture terrain" + terrains + " --tile-px 32 --search 8 --seed 2 --json --out " +
                              q(d / "set") + " --tiled " + q(d / "tiled"));
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = r.json();
  EXPECT_EQ(j.at("colors"), 3);
  EXPECT_EQ(j.at("tiles"), 81);
  EXPECT_EQ(j.at("method"), "terrain-corner");
  EXPECT_EQ(j.at("terrains").size(), 3u);
  EXPECT_EQ(j.at("terrains").at(1).at("name"), "green");
  for (const char* f : {"tile-0000.png", "tile-0080.png", "tiles.json", "sheet.png", "tileset.png", "labels"})
    EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(d / "set") / f)) << f;
  // The set is a texture tile set: `texture atlas` lays it out.
  EXPECT_EQ(run_cli("texture atlas " + q(d / "set") + " --out " + q(d / "atlas/atlas.png") + " --json").code, 0);
  // The packed sheet in the set folder is the Tiled sheet.
  const std::string png = j.at("tiled").at("png").get<std::string>(), tsx = j.at("tiled").at("tsx").get<std::string>();
  EXPECT_EQ(slurp(png), slurp(d / "set/sheet.png"));
  if (!tiled::installed()) GTEST_SKIP() << tiled::kSkip;
  ASSERT_EQ(tiled::run_qt("tiled", "--export-tileset json " + q(tsx) + " " + q(d / "ts.json")), 0);
  const nlohmann::json ts = nlohmann::json::parse(slurp(d / "ts.json"));
  const tiled::WangSetJson w = tiled::wang_set_of(ts);
  EXPECT_EQ(w.type, "corner");
  ASSERT_EQ(w.tilecount, 81);
  const auto bad = tiled::mismatches(w, tiled::sheet_ids(w), 9, 9, true);
  EXPECT_TRUE(bad.empty()) << bad.front();
  const auto& colours = ts.at("wangsets").at(0).at("colors");
  ASSERT_EQ(colours.size(), 3u);
  EXPECT_EQ(colours.at(0).at("name"), "red");
  EXPECT_EQ(colours.at(2).at("name"), "blue");
  // each Wang colour is drawn in its terrain's mean colour: terrain k's channel k dominates
  for (int k = 0; k < 3; ++k) {
    const std::string hex = colours.at(std::size_t(k)).at("color").get<std::string>();  // "#rrggbb"
    ASSERT_EQ(hex.size(), 7u) << hex;
    int ch[3];
    for (int c = 0; c < 3; ++c) ch[c] = std::stoi(hex.substr(std::size_t(1 + 2 * c), 2), nullptr, 16);
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(c == k || ch[k] > ch[c]) << "terrain " << k << " " << hex;
  }
  // Every tile's corners in the sheet PNG show the terrain its wangid names (entries 7, 1, 5, 3:
  // top-left, top-right, bottom-left, bottom-right; colours from 1).
  const Image sheet = read_image(png, 4);
  const int n = 32;
  for (const auto& [id, wid] : w.wangid) {
    const int x0 = (id % w.columns) * n, y0 = (id / w.columns) * n;
    const int at[4][3] = {{1, 1, 7}, {n - 2, 1, 1}, {1, n - 2, 5}, {n - 2, n - 2, 3}};
    for (const auto& a : at)
      EXPECT_EQ(dominant_channel(sheet, x0 + a[0], y0 + a[1]), wid[std::size_t(a[2])] - 1) << "tile id " << id;
  }
}

TEST(TerrainCli, BadInputExits2WithOneLineAndWritesNothing) {
  TempDir d;
  const std::string red = write_channel_texture(d / "r.png", 0), green = write_channel_texture(d / "g.png", 1);
  const std::string out = " --out " + q(d / "out");
  for (const std::string& args : std::vector<std::string>{
           "texture terrain --terrain red=" + q(red) + out,                    // one terrain
           "texture terrain --terrain red --terrain green=" + q(green) + out,  // no =FILE
           "texture terrain --terrain red=" + q(red) + " --terrain green=" + q(d / "none.png") + out,
           "texture terrain --terrain red=" + q(red) + " --terrain red=" + q(green) + out,  // one name twice
           "texture terrain --terrain 'r d'=" + q(red) + " --terrain green=" + q(green) + out,
           "texture terrain --terrain red=" + q(red) + " --terrain green=" + q(green) + " --tile-px 31" + out,
           "texture terrain --terrain red=" + q(red) + " --terrain green=" + q(green) + " --out " + q(red)}) {
    const CliResult r = run_cli(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(d / "out")) << args;
  }
}

}  // namespace
}  // namespace tilekit::test
