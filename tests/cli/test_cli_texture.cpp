// `tilekit texture tiles|atlas|render` end to end: JSON output, files, bad input (exit 2, one line
// naming the file or flag), and the GLSL path where EGL cannot give a context.
#include <gtest/gtest.h>

#include <filesystem>

#include "../cli_runner.hpp"
#include "../texture/texture_fixtures.hpp"

namespace tilekit {
namespace {

using test::run_cli;
using test::TempDir;

int lines(const std::string& s) {
  return int(std::count(s.begin(), s.end(), '\n'));
}

// A 2-colour tile set made from a synthetic exemplar and its atlas, as d/t and d/a.png.
void make_small_atlas(const TempDir& d) {
  write_png(d / "ex.png", test::synthetic_image(80, 80));
  ASSERT_EQ(run_cli("texture tiles --exemplar " + (d / "ex.png") + " --colors 2 --tile-px 16 --search 2 --out " +
                    (d / "t") + " --quiet")
                .code,
            0);
  ASSERT_EQ(run_cli("texture atlas " + (d / "t") + " --out " + (d / "a.png") + " --no-db").code, 0);
}

TEST(CliTexture, TilesAtlasAndRenderMakeTheirFilesAndReportJson) {
  TempDir d;
  write_png(d / "ex.png", test::synthetic_image(120, 120));
  auto t = run_cli("texture tiles --exemplar " + (d / "ex.png") + " --kind corner --colors 2 --tile-px 32 --out " +
                   (d / "tiles") + " --search 8 --seed 3 --json --quiet");
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_EQ(t.json()["tiles"], 16);
  EXPECT_EQ(t.json()["method"], "corner-strips");
  auto a = run_cli("texture atlas " + (d / "tiles") + " --out " + (d / "atlas.png") + " --no-db --json");
  ASSERT_EQ(a.code, 0) << a.err;
  EXPECT_EQ(a.json()["width"], 128);
  EXPECT_EQ(a.json()["levels"].size(), 8u);
  for (const char* f : {"atlas.png", "atlas.mip7.png", "atlas.json", "atlas.h", "atlas.glsl"})
    EXPECT_TRUE(std::filesystem::exists(d / f)) << f;
  auto r = run_cli("texture render --atlas " + (d / "atlas.png") + " --size 200x100 --scale 0.5 --tilt 2 --out " +
                   (d / "r.png") + " --json --quiet --threads 2");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.json()["renderer"], "cpu");
  EXPECT_GT(r.json()["cpu_mpixels_per_second"].get<double>(), 0);
  EXPECT_EQ(read_image(d / "r.png").width, 200);
  auto human =
      run_cli("texture render --atlas " + (d / "atlas.json") + " --size 20x10 --out " + (d / "h.png") + " --quiet");
  EXPECT_EQ(human.code, 0);
  EXPECT_NE(human.out.find("cpu renderer"), std::string::npos) << human.out;
}

// texture analyze on a render of a small atlas: the measures in JSON, the labels of the same
// view for the cut visibility, the spectrum plot; and bad input is exit 2 with nothing written.
TEST(CliTexture, AnalyzeReportsTheMeasuresAndRefusesBadInputWritingNothing) {
  TempDir d;
  ASSERT_NO_FATAL_FAILURE(make_small_atlas(d));
  ASSERT_EQ(run_cli("texture atlas " + (d / "t/labels") + " --out " + (d / "l.png") + " --no-db").code, 0);
  const std::string view = " --size 128x128 --quiet --out ";
  ASSERT_EQ(run_cli("texture render --atlas " + (d / "a.png") + view + (d / "r.png")).code, 0);
  ASSERT_EQ(run_cli("texture render --atlas " + (d / "l.png") + view + (d / "rl.png")).code, 0);
  auto r = run_cli("texture analyze " + (d / "r.png") + " --tile-px 16 --exemplar " + (d / "ex.png") + " --labels " +
                   (d / "rl.png") + " --plot " + (d / "p.png") + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = r.json();
  for (const char* k : {"grid_repetition", "seam_ratio", "cut_visibility", "histogram_distance", "lattice_peak_db"})
    EXPECT_TRUE(j[k].is_number()) << k;
  EXPECT_EQ(j["lattice_lags"].size(), 5u);
  EXPECT_GT(j["cut_visibility"].get<double>(), 0.5);
  EXPECT_EQ(read_image(d / "p.png").width, 640);
  auto hex = run_cli("texture analyze " + (d / "r.png") + " --lattice 16,0,8,13.86 --json");
  ASSERT_EQ(hex.code, 0) << hex.err;
  EXPECT_TRUE(hex.json()["seam_ratio"].is_null());
  test::write_text(d / "corrupt.png", "not an image");
  std::filesystem::create_directory(d / "dir.png");
  const std::string img = (d / "r.png") + " --tile-px 16";
  for (const auto& [args, what] :
       std::vector<std::pair<std::string, std::string>>{{(d / "missing.png") + " --tile-px 16", "missing.png"},
                                                        {(d / "corrupt.png") + " --tile-px 16", "corrupt.png"},
                                                        {img + " --plot " + (d / "no/such/folder/p2.png"), "p2.png"},
                                                        {img + " --plot " + (d / "dir.png"), "dir.png"},
                                                        {img + " --exemplar " + (d / "none.png"), "none.png"},
                                                        {img + " --labels " + (d / "ex.png"), "labels"},
                                                        {(d / "r.png") + " --tile-px 64", "too small"},
                                                        {(d / "r.png") + " --lattice 16,0,x,4", "--lattice"},
                                                        {(d / "r.png") + " --tile-px 16 --lattice 16,0,0,16", "either"},
                                                        {(d / "r.png"), "either"}}) {
    auto bad = run_cli("texture analyze " + args + " --json");
    EXPECT_EQ(bad.code, 2) << args << "\n" << bad.err;
    EXPECT_EQ(lines(bad.err), 1) << bad.err;
    EXPECT_NE(bad.err.find(what), std::string::npos) << bad.err;
    EXPECT_TRUE(bad.out.empty()) << bad.out;
  }
  EXPECT_FALSE(std::filesystem::exists(d / "no"));
}

TEST(CliTexture, BadExemplarsAndSizesAreExitTwoWithOneLineNamingTheProblem) {
  TempDir d;
  test::write_text(d / "corrupt.png", "not an image at all");
  write_png(d / "tiny.png", test::synthetic_image(12, 12));
  write_png(d / "ex.png", test::synthetic_image(80, 80));
  const std::string tiles = " --kind corner --colors 2 --out " + (d / "o");
  for (const auto& [args, what] : std::vector<std::pair<std::string, std::string>>{
           {"--exemplar " + (d / "missing.png") + tiles, "missing.png"},
           {"--exemplar " + (d / "corrupt.png") + tiles, "corrupt.png"},
           {"--exemplar " + (d / "tiny.png") + tiles, "tiny.png"},
           {"--exemplar " + (d / "ex.png") + tiles + " --tile-px 128", "tile-px"},
           {"--exemplar " + (d / "ex.png") + tiles + " --tile-px 31", "tile-px"}}) {
    auto r = run_cli("texture tiles " + args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_EQ(lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
  }
  EXPECT_EQ(run_cli("texture atlas " + (d / "nothing") + " --out " + (d / "a.png")).code, 2);
  EXPECT_EQ(run_cli("texture render --atlas " + (d / "nothing.png") + " --out " + (d / "r.png")).code, 2);
}

TEST(CliTexture, GlslWithoutAnEglContextIsExitTwoWithASkipMessageAndCpuStillRenders) {
  TempDir d;
  ASSERT_NO_FATAL_FAILURE(make_small_atlas(d));
  // No EGL vendor library: libglvnd finds no implementation, so no display can be made.
  const std::string no_egl =
      "env __EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json __EGL_VENDOR_LIBRARY_DIRS=/nonexistent ";
  const std::string render = " texture render --atlas " + (d / "a.png") + " --size 64x64 --out " + (d / "g.png");
  auto r = test::run_cli_prefixed(no_egl, render + " --glsl");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("skipped"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(d / "g.png"));
  EXPECT_EQ(test::run_cli_prefixed(no_egl, render).code, 0);
}

TEST(CliTexture, CompareRendersBothWaysAndReportsTheDifference) {
  TempDir d;
  ASSERT_NO_FATAL_FAILURE(make_small_atlas(d));
  auto r = run_cli("texture render --atlas " + (d / "a.png") +
                   " --size 128x96 --scale 0.7 --tilt 3 --compare --json --quiet --out " + (d / "g.png"));
  if (r.code == 2 && r.err.find("skipped") != std::string::npos) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_LE(r.json()["max_difference"].get<int>(), 2);
}

}  // namespace
}  // namespace tilekit
