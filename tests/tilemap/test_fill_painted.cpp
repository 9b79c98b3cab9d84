// `tilekit fill --cells MAP.tmx`: a map painted in Tiled (saved by the real Tiled) filled around its
// painted cells, for a Tilekit set, the Tiled Wang set of its sheet and a WFC set; checked from
// Tiled's own JSON export by tests/tilemap/tiled_checker.hpp (painted gids unchanged, no empty
// cell, every neighbour pair agrees on its wangid) and, for WFC, tmxrasterizer's picture equal to
// Tilekit's. Bad painted maps exit 2 naming the problem and write nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "tests/tilemap/tiled_checker.hpp"

namespace tilekit::test {
namespace {

std::string wfc_xml(const std::string& name) {
  return (std::filesystem::path(TILEKIT_SOURCE_DIR) / "tilemap" / "data" / "wfc" / (name + ".xml")).string();
}

// The CSV layer of a .tmx Tilekit wrote, and the file with the layer replaced.
std::vector<long long> csv_of(const std::string& tmx) {
  const auto a = tmx.find("<data encoding=\"csv\">"), b = tmx.find("</data>");
  std::vector<long long> out;
  std::string tok;
  for (std::size_t i = a + 21; i < b; ++i) {
    const char c = tmx[i];
    if (c == ',') {
      out.push_back(std::stoll(tok));
      tok.clear();
    } else if (c >= '0' && c <= '9') {
      tok += c;
    }
  }
  if (!tok.empty()) out.push_back(std::stoll(tok));
  return out;
}

std::string with_csv(const std::string& tmx, const std::vector<long long>& gids, int cols) {
  const auto a = tmx.find("<data encoding=\"csv\">") + 21, b = tmx.find("</data>");
  std::string csv = "\n";
  for (std::size_t i = 0; i < gids.size(); ++i)
    csv += std::to_string(gids[i]) + (i + 1 == gids.size() ? "\n" : (int(i) % cols == cols - 1 ? ",\n" : ","));
  return tmx.substr(0, a) + csv + tmx.substr(b);
}

// A painting: the cells of row 4, column 3 and a 2x2 block of `full` kept, every other cell empty.
std::vector<long long> painting(const std::vector<long long>& full, int cols) {
  std::vector<long long> out(full.size(), 0);
  for (std::size_t i = 0; i < full.size(); ++i) {
    const int r = int(i) / cols, c = int(i) % cols;
    if (r == 4 || c == 3 || (r >= 1 && r <= 2 && c >= 7 && c <= 8)) out[i] = full[i];
  }
  return out;
}

// The first layer's gids of a map Tiled exported as JSON.
std::vector<long long> exported_gids(const std::string& json) {
  std::vector<long long> out;
  const nlohmann::json j = nlohmann::json::parse(slurp(json));
  for (const auto& g : j.at("layers").at(0).at("data")) out.push_back(g.get<long long>());
  return out;
}

TEST(FillPainted, ATiledMapIsFilledAroundItsPaintedCells) {
  if (!tiled::installed()) GTEST_SKIP() << tiled::kSkip;
  TempDir d;
  CliResult r = run_cli("fill --set complete-corner-3 --size 12x9 --seed 5 --tiled " + q(d / "a") + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string full_tmx = slurp(r.json().at("tmx").get<std::string>());
  const std::vector<long long> painted = painting(csv_of(full_tmx), 12);
  write_text(d / "a/raw.tmx", with_csv(full_tmx, painted, 12));
  // the painted map as Tiled itself saves it
  ASSERT_EQ(tiled::run_qt("tiled", "--export-map " + q(d / "a/raw.tmx") + " " + q(d / "a/painted.tmx")), 0);
  std::size_t kept = 0;
  for (long long g : painted) kept += g != 0;
  // the Tilekit set by name, and the Tiled Wang set of its sheet
  for (const std::string& set : {std::string("complete-corner-3"), d / "a/corner-3.tsx"}) {
    SCOPED_TRACE(set);
    std::filesystem::remove_all(d / "out");
    r = run_cli("fill --set " + q(set) + " --cells " + q(d / "a/painted.tmx") + " --seed 9 --tiled " + q(d / "out") +
                " --json");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.json().at("fixed").get<std::size_t>(), kept);
    EXPECT_EQ(r.json().at("size"), "12x9");
    const std::string tmx = r.json().at("tmx");
    ASSERT_EQ(tiled::run_qt("tiled", "--embed-tilesets --export-map json " + q(tmx) + " " + q(d / "p.json")), 0);
    const nlohmann::json j = nlohmann::json::parse(slurp(d / "p.json"));
    const auto& ts = j.at("tilesets").at(0);
    const std::vector<long long> gids = exported_gids(d / "p.json");
    ASSERT_EQ(gids.size(), painted.size());
    std::vector<int> ids;
    for (std::size_t i = 0; i < gids.size(); ++i) {
      ASSERT_NE(gids[i], 0) << "cell " << i << " left empty";
      if (painted[i] != 0) {
        ASSERT_EQ(gids[i], painted[i]) << "painted cell " << i << " changed";
      }
      ids.push_back(int(gids[i] - ts.at("firstgid").get<long long>()));
    }
    const auto bad = tiled::mismatches(tiled::wang_set_of(ts), ids, 9, 12, false);
    EXPECT_TRUE(bad.empty()) << bad.front();
  }
}

TEST(FillPainted, AWfcMapPaintedInTiledIsFilledAndDrawnAsTiledDrawsIt) {
  if (!tiled::installed()) GTEST_SKIP() << tiled::kSkip;
  TempDir d;
  CliResult r =
      run_cli("fill --set " + q(wfc_xml("Knots")) + " --size 12x9 --seed 3 --tiled " + q(d / "a") + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string full_tmx = slurp(r.json().at("tmx").get<std::string>());
  const std::vector<long long> painted = painting(csv_of(full_tmx), 12);
  write_text(d / "a/raw.tmx", with_csv(full_tmx, painted, 12));
  ASSERT_EQ(tiled::run_qt("tiled", "--export-map " + q(d / "a/raw.tmx") + " " + q(d / "a/painted.tmx")), 0);
  r = run_cli("fill --set " + q(wfc_xml("Knots")) + " --cells " + q(d / "a/painted.tmx") + " --seed 11 --png " +
              q(d / "w.png") + " --tiled " + q(d / "out") + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.json().at("valid").get<bool>());
  const std::string tmx = r.json().at("tmx");
  ASSERT_EQ(tiled::run_qt("tiled", "--export-map json " + q(tmx) + " " + q(d / "p.json")), 0);
  const std::vector<long long> gids = exported_gids(d / "p.json");
  ASSERT_EQ(gids.size(), painted.size());
  for (std::size_t i = 0; i < gids.size(); ++i) {
    EXPECT_NE(gids[i], 0) << i;
    if (painted[i] != 0) {
      EXPECT_EQ(gids[i], painted[i]) << "painted cell " << i << " changed";
    }
  }
  ASSERT_EQ(tiled::run_qt("tmxrasterizer", q(tmx) + " " + q(d / "tiled.png")), 0);
  EXPECT_EQ(tiled::differing_pixels(read_image(d / "tiled.png"), read_image(d / "w.png")), 0);
}

// Bad painted maps (no Tiled needed: the maps are written here) exit 2 with the problem and write nothing.
TEST(FillPainted, BadPaintedMapsExit2NamingTheProblem) {
  TempDir d;
  CliResult r = run_cli("fill --set complete-corner-3 --size 6x5 --seed 5 --tiled " + q(d / "a") + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string tmx = slurp(r.json().at("tmx").get<std::string>());
  std::vector<long long> g = painting(csv_of(tmx), 6);
  write_text(d / "a/ok.tmx", with_csv(tmx, g, 6));
  auto variant = [&](const std::string& name, std::size_t cell, long long gid) {
    std::vector<long long> v = g;
    v[cell] = gid;
    write_text(d / ("a/" + name), with_csv(tmx, v, 6));
  };
  variant("past.tmx", 0, 82);             // corner-3.tsx holds 81 tiles
  variant("flipped.tmx", 1, 2147483650);  // gid 2, flipped horizontally
  std::string other = tmx;
  other.replace(other.find("corner-3.tsx"), 12, "missing.tsx");
  write_text(d / "a/missing.tmx", other);
  write_text(d / "a/b64.tmx", std::string(tmx).replace(tmx.find("encoding=\"csv\""), 14, "encoding=\"base64\""));
  const std::string ok = q(d / "a/ok.tmx");
  const struct {
    std::string args, says;
  } cases[] = {
      {"--set complete-corner-3 --size 7x5 --cells " + ok, "--size is 7x5, the painted map"},
      {"--set complete-corner-2 --cells " + ok, "is no tile of the set complete-corner-2"},
      {"--set compact-wang-3 --cells " + ok, "of type corner, the fill set is a Wang (edge) set"},
      {"--set " + q(wfc_xml("Knots")) + " --cells " + ok, "the WFC set"},
      {"--set complete-corner-3 --cells " + q(d / "a/past.tmx"), "is past the 81 tiles of corner-3.tsx"},
      {"--set complete-corner-3 --cells " + q(d / "a/flipped.tmx"), "is flipped or rotated"},
      {"--set complete-corner-3 --cells " + q(d / "a/missing.tmx"), "missing.tsx"},
      {"--set complete-corner-3 --cells " + q(d / "a/b64.tmx"), "Tile Layer Format CSV"},
      {"--set blob-47 --cells " + ok, "the blob set has no Tiled tileset"},
      {"--set complete-corner-3", "--size is needed unless --cells is a Tiled map"},
  };
  for (const auto& c : cases) {
    r = run_cli("fill " + c.args + " --png " + q(d / "o.png") + " --tiled " + q(d / "o"));
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(d / "o.png")) << c.args;
    EXPECT_FALSE(std::filesystem::exists(d / "o")) << c.args;
  }
  // the painted map alone sets the size
  r = run_cli("fill --set complete-corner-3 --cells " + ok + " --seed 2 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.json().at("size"), "6x5");
}

}  // namespace
}  // namespace tilekit::test
