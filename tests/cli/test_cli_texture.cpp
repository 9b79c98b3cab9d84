// `tilekit texture tiles|atlas|render` end to end: JSON output, files, bad input (exit 2, one line
// naming the file or flag), and the GLSL path where EGL cannot give a context.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include "../cli_runner.hpp"
#include "../texture/texture_fixtures.hpp"
#include "base/hash.hpp"
#include "render/exemplar_surface.hpp"
#include "render/glsl_sampler.hpp"
#include "results/results_db.hpp"
#include "tilesets/constructions.hpp"

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
  EXPECT_EQ(human.out, "") << "--quiet: no summary";
  human = run_cli("texture render --atlas " + (d / "atlas.json") + " --size 20x10 --out " + (d / "h.png"));
  EXPECT_EQ(human.code, 0);
  EXPECT_NE(human.out.find("cpu renderer"), std::string::npos) << human.out;
}

// `texture atlas` lays the tiles out by the constructed (or reference) packing unless --db names a
// database: a packing stored in the user's default database changes `atlas lookup`'s answer, never
// the texture atlas's.
TEST(CliTexture, AtlasUsesTheConstructedPackingUnlessADatabaseIsNamed) {
  TempDir d;
  ASSERT_NO_FATAL_FAILURE(make_small_atlas(d));
  const Tiling t = construct_packing(TileKind::Corner, 2)->tiling;
  Tiling shifted = t;  // another packing: the constructed one shifted by (1, 2)
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) shifted.at(r, c) = t.at((r + 1) % 4, (c + 2) % 4);
  {
    ResultsDb db(d / "r.sqlite");
    SolutionRecord s;
    s.tiling = shifted;
    s.method = "search";
    s.validated = true;
    db.add_solution(s);
  }
  const std::string user_db = "env TILEKIT_DB=" + (d / "r.sqlite") + " ";
  auto plain = test::run_cli_prefixed(user_db, "texture atlas " + (d / "t") + " --out " + (d / "c.png") + " --json");
  ASSERT_EQ(plain.code, 0) << plain.err;
  EXPECT_EQ(plain.json()["source"], "construct");
  EXPECT_EQ(read_texture_atlas(d / "c.png").lookup.cells, t.cells);
  auto named =
      run_cli("texture atlas " + (d / "t") + " --out " + (d / "s.png") + " --db " + (d / "r.sqlite") + " --json");
  ASSERT_EQ(named.code, 0) << named.err;
  EXPECT_EQ(named.json()["source"], "db");
  EXPECT_EQ(read_texture_atlas(d / "s.png").lookup.cells, shifted.cells);
  // `atlas lookup` keeps reading the default database.
  auto lookup = test::run_cli_prefixed(user_db, "atlas lookup --kind corner --colors 2");
  ASSERT_EQ(lookup.code, 0) << lookup.err;
  EXPECT_EQ(lookup.json()["source"], "db");
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

TEST(CliTexture, EveryMethodRendersAndReportsItsFetchesAndMemoryAndNeedsWhatItSamples) {
  TempDir d;
  ASSERT_NO_FATAL_FAILURE(make_small_atlas(d));
  const std::string view = " --size 96x64 --tilt 3 --scale 0.5 --quiet --json --threads 2";
  std::map<std::string, double> fetches;
  for (const std::string m : {"tiles", "hex", "hpn"}) {
    auto r = run_cli("texture render --method " + m + " --atlas " + (d / "a.png") + " --exemplar " + (d / "ex.png") +
                     view + " --out " + (d / (m + ".png")));
    ASSERT_EQ(r.code, 0) << m << ": " << r.err;
    EXPECT_EQ(r.json()["method"], m);
    EXPECT_EQ(r.json()["aniso"], 16);
    EXPECT_GT(r.json()["memory_bytes"].get<double>(), 0);
    fetches[m] = r.json()["fetches_per_pixel"].get<double>();
    EXPECT_EQ(read_image(d / (m + ".png")).width, 96);
  }
  // One trilinear fetch per anisotropic tap for tiles, three for hex, three and three look-ups for hpn.
  EXPECT_GT(fetches["tiles"], 1.0);
  EXPECT_NEAR(fetches["hex"], 3 * fetches["tiles"], 1e-9);
  EXPECT_NEAR(fetches["hpn"], 3 * fetches["tiles"] + 3, 1e-9);
  auto trilinear = run_cli("texture render --atlas " + (d / "a.png") + view + " --aniso 1 --out " + (d / "t.png"));
  ASSERT_EQ(trilinear.code, 0) << trilinear.err;
  EXPECT_EQ(trilinear.json()["fetches_per_pixel"], 1.0);
  for (const auto& [args, what] : std::vector<std::pair<std::string, std::string>>{
           {"--method hex --atlas " + (d / "a.png"), "--exemplar"},
           {"--method hpn", "--exemplar"},
           {"--method tiles --exemplar " + (d / "ex.png"), "--atlas"},
           {"--method bilinear --atlas " + (d / "a.png"), "--method"},
           {"--method hex --exemplar " + (d / "missing.png"), "missing.png"},
           {"--atlas " + (d / "a.png") + " --aniso 17", "--aniso"},
           {"--atlas " + (d / "a.png") + " --origin 1,2,3", "--origin"},
           {"--method hex --exemplar " + (d / "ex.png") + " --cell-px 100", "too small"}}) {
    auto r = run_cli("texture render " + args + " --size 8x8 --out " + (d / "bad.png"));
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_EQ(lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(d / "bad.png")) << args;
  }
}

// The JSON block of a preview page (the data the script reads).
nlohmann::json preview_data(const std::string& html) {
  const std::string tag = "<script type=\"application/json\" id=\"tk-data\">";
  const std::size_t a = html.find(tag) + tag.size(), b = html.find("</script>", a);
  return nlohmann::json::parse(html.substr(a, b - a));
}

TEST(CliTexture, PreviewIsOneSelfContainedPageWithTheRenderersShaderText) {
  TempDir d;
  ASSERT_NO_FATAL_FAILURE(make_small_atlas(d));
  auto r = run_cli("texture preview --atlas " + (d / "a.png") + " --exemplar " + (d / "ex.png") + " --seed 9 --out " +
                   (d / "p.html") + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.json()["methods"], nlohmann::json({"tiles", "hex", "hpn"}));
  const std::string html = test::slurp(d / "p.html");
  EXPECT_EQ(html.find("http"), std::string::npos) << "the page must not load anything";
  EXPECT_EQ(std::count(html.begin(), html.end(), '\n') > 0, true);
  const nlohmann::json data = preview_data(html);
  // The same fragment shaders as the headless renderer, byte for byte, and the tables of seed 9.
  const TextureAtlas atlas = read_texture_atlas(d / "a.png");
  const ExemplarSurface ex = make_exemplar_surface(read_image(d / "ex.png"), d / "ex.png");
  const RenderOptions o{HashKind::LongPeriod, 9, 1, false, 16};
  for (const RenderSource& s :
       {RenderSource{RenderMethod::Tiles, &atlas, nullptr}, RenderSource{RenderMethod::Hex, nullptr, &ex},
        RenderSource{RenderMethod::Hpn, nullptr, &ex}}) {
    const nlohmann::json& m = data["methods"][render_method_name(s.method)];
    EXPECT_EQ(m["shader"].get<std::string>(), glsl_fragment_shader(s, o, GlslMode::Texture))
        << render_method_name(s.method);
    for (const auto& [name, values] : glsl_table_uniforms(s, o)) EXPECT_EQ(m["check"][name], values) << name;
    for (const GlslTableTexture& t : glsl_table_textures(s, o))
      EXPECT_EQ(m["check"][t.sampler],
                std::to_string(
                    StableHash()
                        .add(std::string_view(reinterpret_cast<const char*>(t.texels.data()), t.texels.size()))
                        .fnv()))
          << t.sampler;
  }
  // Every level of the atlas is embedded (the tiles method's texture: one image per level).
  EXPECT_EQ(data["methods"]["tiles"]["textures"][0]["levels"].size(), atlas.levels.size());
  auto tiles_only = run_cli("texture preview --atlas " + (d / "a.png") + " --out " + (d / "t.html") + " --json");
  ASSERT_EQ(tiles_only.code, 0) << tiles_only.err;
  EXPECT_EQ(tiles_only.json()["methods"], nlohmann::json({"tiles"}));
}

TEST(CliTexture, PreviewOfABadAtlasOrToAnUnwritableFileIsExitTwoAndWritesNothing) {
  TempDir d;
  ASSERT_NO_FATAL_FAILURE(make_small_atlas(d));
  for (const char* f : {"a.png", "a.json"}) std::filesystem::copy_file(d / f, d / (std::string("nomip-") + f));
  // An atlas whose manifest lists level 0 only, one whose level 3 is not a PNG, one without level 2.
  nlohmann::json manifest = nlohmann::json::parse(test::slurp(d / "a.json"));
  nlohmann::json levels = manifest["levels"];
  manifest["levels"] = nlohmann::json::array({levels[0]});
  test::write_text(d / "nomip-a.json", manifest.dump());
  std::filesystem::create_directory(d / "corrupt");
  std::filesystem::create_directory(d / "gap");
  for (const auto& entry : std::filesystem::directory_iterator(d.path))
    if (entry.path().filename().string().rfind("a.", 0) == 0) {
      std::filesystem::copy_file(entry.path(), d / ("corrupt/" + entry.path().filename().string()));
      std::filesystem::copy_file(entry.path(), d / ("gap/" + entry.path().filename().string()));
    }
  test::write_text(d / "corrupt/a.mip3.png", "not a png");
  std::filesystem::remove(d / "gap/a.mip2.png");
  for (const auto& [args, what] : std::vector<std::pair<std::string, std::string>>{
           {"--atlas " + (d / "none.png"), "none.json"},
           {"--atlas " + (d / "nomip-a.png"), "mip chain"},
           {"--atlas " + (d / "corrupt/a.png"), "a.mip3.png"},
           {"--atlas " + (d / "gap/a.png"), "a.mip2.png"},
           {"--atlas " + (d / "a.png") + " --exemplar " + (d / "missing.png"), "missing.png"},
           {"", "--atlas"}}) {
    auto r = run_cli("texture preview " + args + " --out " + (d / "p.html"));
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_EQ(lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(d / "p.html")) << args;
  }
  auto r = run_cli("texture preview --atlas " + (d / "a.png") + " --out " + (d / "no/such/dir/p.html"));
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("no/such/dir/p.html"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace tilekit
