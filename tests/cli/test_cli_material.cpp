// `texture tiles --map`, `texture atlas` of a material set and `texture transfer`: every map's
// tiles copied at the texels DIR/coords/ records, maps of another size resampled (and said so),
// 16 bits kept, colour spaces in the manifests; --period X,Y and --quiet.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "../cli_runner.hpp"
#include "../texture/texture_fixtures.hpp"
#include "image/image.hpp"
#include "texture/material.hpp"

namespace tilekit {
namespace {

using test::run_cli;
using test::TempDir;

TEST(CliMaterial, EveryMapIsCopiedAtTheRecordedTexelsAndAtlasedTheSameWay) {
  TempDir d;
  const Image albedo = test::synthetic_image(96, 96, 11);
  write_png(d / "albedo.png", albedo);
  write_png(d / "normal.png", normal_map_from_height(test::synthetic_image(48, 48, 12), 8, false));  // half size
  Image height = Image(96, 96).to_depth(16);
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 96; ++x)
      for (int c = 0; c < 3; ++c) height.set_sample(x, y, c, 1000u + unsigned(x * 96 + y) * 2000u / 9215u);
  write_png(d / "height.png", height);
  const auto t = run_cli("texture tiles --exemplar " + (d / "albedo.png") + " --map normal=" + (d / "normal.png") +
                         " --map height=" + (d / "height.png") +
                         ":linear --colors 2 --tile-px 32 --search 8 --period off --out " + (d / "mat") + " --json");
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.err.find("map normal: 48x48 resampled to the exemplar's 96x96"), std::string::npos) << t.err;
  const nlohmann::json j = t.json();
  EXPECT_EQ(j["map_cost"], "all");
  ASSERT_EQ(j["maps"].size(), 2u);
  EXPECT_EQ(j["maps"][0]["colour_space"], "normal");
  EXPECT_EQ(j["maps"][1]["bits"], 16);
  EXPECT_EQ(test::read_json(d / "mat/maps/height/tiles.json")["colour_space"], "linear");
  EXPECT_EQ(test::read_json(d / "mat/tiles.json")["colour_space"], "srgb");
  for (int t_index : {0, 5, 15}) {
    const std::string name = "tile-" + std::string(t_index < 10 ? "000" : "00") + std::to_string(t_index) + ".png";
    const Image where = read_image(d / ("mat/coords/" + name), 4, true);
    const Image colour = read_image(d / ("mat/" + name));
    const Image h = read_image(d / ("mat/maps/height/" + name), 4, true);
    ASSERT_EQ(where.depth, 16);
    ASSERT_EQ(h.depth, 16);
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x) {
        const int sx = int(where.sample(x, y, 0)), sy = int(where.sample(x, y, 1));
        ASSERT_LT(sx, 96);
        ASSERT_LT(sy, 96);
        for (int c = 0; c < 3; ++c) {
          ASSERT_EQ(colour.sample(x, y, c), albedo.sample(sx, sy, c));
          ASSERT_EQ(h.sample(x, y, c), height.sample(sx, sy, c));
        }
      }
  }
  // The atlas of every map, into a folder that does not exist yet.
  const auto a = run_cli("texture atlas " + (d / "mat") + " --out " + (d / "new/folder/atlas.png") + " --json");
  ASSERT_EQ(a.code, 0) << a.err;
  EXPECT_EQ(a.json()["colour_space"], "srgb");
  EXPECT_EQ(a.json()["maps"]["height"]["bits"], 16);
  EXPECT_EQ(a.json()["maps"]["normal"]["colour_space"], "normal");
  EXPECT_EQ(test::read_json(d / "new/folder/atlas-height.json")["colour_space"], "linear");
  EXPECT_EQ(read_image(d / "new/folder/atlas-height.mip1.png", 4, true).depth, 16);
  // A map carried later equals the same map given at synthesis.
  const auto tr = run_cli("texture transfer " + (d / "mat") + " --map again=" + (d / "height.png") + " --json");
  ASSERT_EQ(tr.code, 0) << tr.err;
  for (const char* name : {"tile-0000.png", "tile-0009.png"})
    EXPECT_EQ(read_image(d / (std::string("mat/maps/again/") + name), 4, true).pixels,
              read_image(d / (std::string("mat/maps/height/") + name), 4, true).pixels);
}

TEST(CliMaterial, BadMapsAndPeriodsAreExitTwoAndQuietPrintsNothing) {
  TempDir d;
  write_png(d / "ex.png", test::synthetic_image(96, 96));
  const std::string base =
      "texture tiles --exemplar " + (d / "ex.png") + " --colors 1 --tile-px 32 --search 0 --out " + (d / "o") + " ";
  EXPECT_EQ(run_cli(base + "--map nofile").code, 2);
  EXPECT_EQ(run_cli(base + "--map a=" + (d / "missing.png")).code, 2);
  EXPECT_EQ(run_cli(base + "--map coords=" + (d / "ex.png")).code, 2);
  EXPECT_EQ(run_cli(base + "--period 3,0").code, 2);
  EXPECT_EQ(run_cli(base + "--period 0,0").code, 2);
  EXPECT_EQ(run_cli(base + "--period 12,x").code, 2);
  EXPECT_EQ(run_cli("texture transfer " + (d / "nowhere") + " --map a=" + (d / "ex.png")).code, 2);
  const auto q = run_cli(base + "--period 24,0 --quiet");
  ASSERT_EQ(q.code, 0) << q.err;
  EXPECT_EQ(q.out, "");
  EXPECT_EQ(test::read_json(d / "o/tiles.json")["period"][0], 24.0);
}

// `texture atlas` of a material with a normal map and a map called roughness folds the length the
// normal mips lose into the roughness mips (Toksvig); --no-toksvig keeps plain averages.
TEST(CliMaterial, AtlasFoldsTheNormalsLostLengthIntoRoughness) {
  TempDir d;
  write_png(d / "albedo.png", test::synthetic_image(96, 96, 11));
  write_png(d / "normal.png", normal_map_from_height(test::synthetic_image(96, 96, 12), 40, false));
  write_png(d / "roughness.png", Image(96, 96, Rgb{77, 77, 77}));
  const auto t = run_cli("texture tiles --exemplar " + (d / "albedo.png") + " --map normal=" + (d / "normal.png") +
                         " --map roughness=" + (d / "roughness.png") +
                         " --colors 2 --tile-px 32 --search 8 --period off --quiet --out " + (d / "mat"));
  ASSERT_EQ(t.code, 0) << t.err;
  const auto on = run_cli("texture atlas " + (d / "mat") + " --out " + (d / "on/atlas.png") + " --json");
  ASSERT_EQ(on.code, 0) << on.err;
  EXPECT_EQ(on.json()["maps"]["roughness"]["toksvig"], "normal");
  const auto off = run_cli("texture atlas " + (d / "mat") + " --no-toksvig --out " + (d / "off/atlas.png") + " --json");
  ASSERT_EQ(off.code, 0) << off.err;
  EXPECT_TRUE(off.json()["maps"]["roughness"]["toksvig"].is_null());
  EXPECT_EQ(read_image(d / "on/atlas-roughness.png").pixels, read_image(d / "off/atlas-roughness.png").pixels);
  const auto mean = [](const Image& img) {
    double sum = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) sum += img.at(x, y)[0];
    return sum / (double(img.width) * img.height);
  };
  const double widened = mean(read_image(d / "on/atlas-roughness.mip2.png"));
  EXPECT_NEAR(mean(read_image(d / "off/atlas-roughness.mip2.png")), 77, 0.5);
  EXPECT_GT(widened, 80);
}

// --tile-px auto (the default): a periodic exemplar gets the fewest whole periods of 64 px or more, a
// fine-grained one the smallest tiles; the choice and its reason on stderr and in tiles.json.
TEST(CliTexture, TilePxAutoFollowsThePeriodOrTheFeatureSize) {
  TempDir d;
  Image stripes(200, 200);  // vertical bars every 24 px, horizontal ones every 30 px
  for (int y = 0; y < 200; ++y)
    for (int x = 0; x < 200; ++x) {
      const std::uint8_t v = x % 24 < 3 || y % 30 < 3 ? 40 : std::uint8_t(180 + (x * 7 + y * 13) % 40);
      stripes.set(x, y, {v, v, v});
    }
  write_png(d / "stripes.png", stripes);
  write_png(d / "grain.png", test::blob_image(200));
  const auto p = run_cli("texture tiles --exemplar " + (d / "stripes.png") +
                         " --colors 1 --search 0 --tile-px auto --out " + (d / "p") + " --json");
  ASSERT_EQ(p.code, 0) << p.err;
  EXPECT_EQ(p.json()["tile_px"], 90);  // 3 periods of 30 (the larger), the least multiple of at least 64 px
  EXPECT_NE(p.err.find("--tile-px auto: period 30"), std::string::npos) << p.err;
  EXPECT_EQ(test::read_json(d / "p/tiles.json")["tile_px_auto"]["tile_px"], 90);
  // auto is the default (BENCHMARKS.md, "Texture structure and tile size")
  const auto g = run_cli("texture tiles --exemplar " + (d / "grain.png") + " --colors 1 --search 0 --out " + (d / "g") +
                         " --json");
  ASSERT_EQ(g.code, 0) << g.err;
  EXPECT_EQ(g.json()["tile_px"], 64);
  EXPECT_NE(g.err.find("--tile-px auto: features up to about"), std::string::npos) << g.err;
  EXPECT_EQ(test::read_json(d / "g/tiles.json")["tile_px_auto"]["tile_px"], 64);
  for (const char* bad : {"abc", "-64", "0x40", "99999999999999999999"})
    EXPECT_EQ(
        run_cli("texture tiles --exemplar " + (d / "grain.png") + " --tile-px " + bad + " --out " + (d / "x")).code, 2)
        << bad;
}

}  // namespace
}  // namespace tilekit
