// `texture tiles --map` with a 16-bit TIFF and a float OpenEXR map, `texture atlas` of the set:
// depths kept (16-bit PNG tiles, OpenEXR tiles and levels, RGBA32 SFLOAT KTX2), each map's depth
// and colour space in the manifests; damaged TIFF and OpenEXR files, sRGB float and a float
// exemplar refused with exit 2 and one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "../cli_runner.hpp"
#include "../image/tiff_writer.hpp"
#include "../texture/texture_fixtures.hpp"
#include "image/image.hpp"
#include "image/ktx2.hpp"

namespace tilekit {
namespace {

using test::run_cli;
using test::TempDir;

void expect_one_line_exit_2(const test::CliResult& r, const std::string& fragment) {
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST(CliDeepMaps, SixteenBitTiffAndFloatExrMapsKeepTheirDepthThroughTilesAndAtlas) {
  TempDir d;
  write_png(d / "albedo.png", test::synthetic_image(96, 96, 11));
  Image height = Image::grey(96, 96).to_depth(16);
  Image depth = Image::grey(96, 96).to_depth(32);
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 96; ++x) {
      height.set_sample(x, y, 0, 1000u + unsigned(x * 96 + y) * 2000u / 9215u);
      depth.set_value(x, y, 0, -3.5 + (x * 96 + y) * 0.125);
    }
  test::write_tiff(d / "height.tif", height, {false, false, 5, 3});
  write_exr(d / "depth.exr", depth);
  const auto t = run_cli("texture tiles --exemplar " + (d / "albedo.png") + " --map height=" + (d / "height.tif") +
                         " --map depth=" + (d / "depth.exr") +
                         " --colors 2 --tile-px 32 --search 8 --period off --out " + (d / "mat") + " --json");
  ASSERT_EQ(t.code, 0) << t.err;
  const nlohmann::json j = t.json();
  ASSERT_EQ(j["maps"].size(), 2u);
  EXPECT_EQ(j["maps"][0]["bits"], 16);
  EXPECT_EQ(j["maps"][1]["bits"], 32);
  EXPECT_EQ(j["maps"][1]["colour_space"], "linear");
  const nlohmann::json mj = test::read_json(d / "mat/maps/depth/tiles.json");
  EXPECT_EQ(mj["bits"], 32);
  EXPECT_EQ(mj["format"], "exr float");
  EXPECT_EQ(mj["colour_space"], "linear");
  EXPECT_EQ(test::read_json(d / "mat/maps/height/tiles.json")["format"], "png unorm");
  for (const char* name : {"tile-0000", "tile-0011"}) {
    const Image where = read_image(d / (std::string("mat/coords/") + name + ".png"), 4, true);
    const Image h = read_image(d / (std::string("mat/maps/height/") + name + ".png"), 4, true);
    const Image z = read_image(d / (std::string("mat/maps/depth/") + name + ".exr"), 4, true);
    ASSERT_EQ(h.depth, 16);
    ASSERT_EQ(z.depth, 32);
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x) {
        const int sx = int(where.sample(x, y, 0)), sy = int(where.sample(x, y, 1));
        ASSERT_EQ(h.sample(x, y, 0), height.sample(sx, sy, 0));
        ASSERT_EQ(z.value(x, y, 0), depth.value(sx, sy, 0));  // bit-exact float copies
      }
  }
  const auto a = run_cli("texture atlas " + (d / "mat") + " --out " + (d / "atlas/atlas.png") + " --json");
  ASSERT_EQ(a.code, 0) << a.err;
  const nlohmann::json aj = a.json();
  EXPECT_EQ(aj["maps"]["height"]["bits"], 16);
  EXPECT_EQ(aj["maps"]["depth"]["bits"], 32);
  EXPECT_EQ(aj["maps"]["depth"]["colour_space"], "linear");
  EXPECT_EQ(aj["maps"]["depth"]["out"], d / "atlas/atlas-depth.exr");
  const nlohmann::json am = test::read_json(d / "atlas/atlas-depth.json");
  EXPECT_EQ(am["bits"], 32);
  EXPECT_EQ(am["format"], "exr float");
  EXPECT_EQ(am["levels"][1]["file"], "atlas-depth.mip1.exr");
  const Image mip1 = read_image(d / "atlas/atlas-depth.mip1.exr", 4, true);
  EXPECT_EQ(mip1.depth, 32);
  const Ktx2Texture k = decode_ktx2(test::slurp(d / "atlas/atlas-depth.ktx2"), "atlas-depth.ktx2");
  EXPECT_EQ(k.vk_format(), kVkR32G32B32A32Sfloat);
  float first = 0;
  std::memcpy(&first, k.levels[1].data(), 4);
  EXPECT_EQ(double(first), mip1.value(0, 0, 0));
  EXPECT_EQ(read_image(d / "atlas/atlas-height.mip1.png", 4, true).depth, 16);
}

TEST(CliDeepMaps, DamagedTiffAndExrSrgbFloatAndFloatExemplarsAreExitTwo) {
  TempDir d;
  write_png(d / "ex.png", test::synthetic_image(96, 96));
  const std::string base = "texture tiles --exemplar " + (d / "ex.png") +
                           " --colors 1 --tile-px 32 --search 0 --quiet --out " + (d / "o") + " ";
  test::write_text(d / "bad.tif", std::string("II*\0", 4) + std::string(64, '\x11'));
  test::write_text(d / "bad.exr", std::string("\x76\x2f\x31\x01", 4) + std::string(64, '\x11'));
  expect_one_line_exit_2(run_cli(base + "--map h=" + (d / "bad.tif")), "bad.tif: cannot read the TIFF");
  expect_one_line_exit_2(run_cli(base + "--map h=" + (d / "bad.exr")), "bad.exr: cannot read the OpenEXR image");
  write_exr(d / "f.exr", Image(96, 96).to_depth(32));
  expect_one_line_exit_2(run_cli(base + "--map albedo2=" + (d / "f.exr") + ":srgb"), "which are linear");
  expect_one_line_exit_2(run_cli("texture tiles --exemplar " + (d / "f.exr") +
                                 " --colors 1 --tile-px 32 --search 0 --quiet --out " + (d / "o2")),
                         "a float exemplar");
  expect_one_line_exit_2(run_cli("texture tiles --exemplar " + (d / "bad.tif") +
                                 " --colors 1 --tile-px 32 --search 0 --quiet --out " + (d / "o3")),
                         "cannot read the TIFF");
}

}  // namespace
}  // namespace tilekit
