// End-to-end tests of `tilekit tile`, `tilekit tileset show --out` and `tilekit analyze`.
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/cli_runner.hpp"

using namespace tilekit::test;

TEST(CliTile, EveryAlgorithmPrintsAValidatedResult) {
  const char* runs[] = {"--set compact-wang-3 --algo scanline",
                        "--set compact-corner-3 --algo scanline",
                        "--set complete-corner-3 --algo direct",
                        "--set complete-wang-3 --algo direct",
                        "--set complete-wang-3 --algo direct-edge",
                        "--set compact-wang3-3 --algo direct-compact",
                        "--set complete-corner-3 --algo halton",
                        "--set complete-corner-3 --algo controlled",
                        "--set complete-corner-3 --algo direct --hash perm"};
  for (const char* run : runs) {
    CliResult r = run_cli(std::string("tile ") + run + " --size 30x20 --seed 4 --json");
    ASSERT_EQ(r.code, 0) << run << ": " << r.err;
    auto j = r.json();
    EXPECT_EQ(j["valid"], true) << run;
    EXPECT_EQ(j["rows"], 20) << run;
    EXPECT_EQ(j["cols"], 30) << run;
    EXPECT_GT(j["distinct_tiles"].get<int>(), 1) << run;
    EXPECT_GE(j["seconds"].get<double>(), 0.0) << run;
  }
}

TEST(CliTile, JsonOutputIsATilingFileThatCheckAccepts) {
  TempDir d;
  CliResult r = run_cli("tile --set complete-wang-2 --algo direct-edge --size 9x7 --out " + (d / "t.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("valid"), std::string::npos);
  CliResult c = run_cli("check " + (d / "t.json") + " --set complete-wang-2 --json");
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_EQ(c.json()["valid"], true);
  EXPECT_EQ(c.json()["rows"], 7);
  EXPECT_EQ(c.json()["cols"], 9);
}

TEST(CliTile, PicturesAreWrittenAsPngAndSvg) {
  TempDir d;
  ASSERT_EQ(run_cli("tile --set complete-corner-3 --algo direct --size 8x8 --borders --out " + (d / "t.png")).code, 0);
  EXPECT_EQ(slurp(d / "t.png").substr(0, 4), "\x89PNG");
  ASSERT_EQ(run_cli("tile --set complete-corner-3 --algo halton --size 8x8 --out " + (d / "t.svg")).code, 0);
  EXPECT_EQ(slurp(d / "t.svg").substr(0, 4), "<svg");
  CliResult r = run_cli("tileset show compact-wang-2 --out " + (d / "s.png") + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.json()["out"], d / "s.png");
  EXPECT_EQ(slurp(d / "s.png").substr(0, 4), "\x89PNG");
}

TEST(CliTile, ControlledTilingReadsAProbabilityMap) {
  TempDir d;
  write_text(d / "map.json", R"({"colors":3,"rows":1,"cols":2,"p":[[[1,0,0],[0,0,1]]]})");
  CliResult r =
      run_cli("tile --set complete-corner-3 --algo controlled --map " + (d / "map.json") + " --size 10x4 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.json()["valid"], true);
}

namespace {

void expect_bad_input(const std::string& args, const std::string& message) {
  CliResult r = run_cli(args);
  EXPECT_EQ(r.code, 2) << args << ": " << r.err;
  EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  EXPECT_TRUE(r.out.empty()) << args;
}

}  // namespace

TEST(CliTile, BadInputIsExit2WithOneLineNamingTheProblem) {
  TempDir d;
  const std::string base = "tile --set complete-corner-3 --size 4x4 ";
  expect_bad_input(base + "--algo magic", "unknown algorithm 'magic'");
  expect_bad_input("tile --set complete-corner-3 --algo direct --size 4by4",
                   "--size WxH: expected two positive integers such as 16x16, got '4by4'");
  expect_bad_input("tile --set complete-corner-3 --algo direct --size 0x4",
                   "--size WxH: each side must be between 1 and 65536, got '0x4'");
  expect_bad_input("tile --set complete-corner-3 --algo direct --size 70000x1",
                   "--size WxH: each side must be between 1 and 65536");
  expect_bad_input("tile --set complete-corner-3 --algo direct --size 8192x4096",
                   "--size WxH: 33554432 cells is more than the limit of 16777216");
  expect_bad_input("tile --set complete-corner-3 --algo direct --size 4096x4096 --tile-size 4 --out " + (d / "big.png"),
                   "more than 8192 per side");
  expect_bad_input(base + "--algo direct --hash md5", "unknown hash 'md5'");
  expect_bad_input(base + "--algo direct-edge", "makes wang tilings");
  expect_bad_input("tile --set compact-corner-3 --algo direct --size 4x4", "lacks");
  expect_bad_input("tile --set kari-14 --algo scanline --size 4x4", "(N, W) colour pair");
  expect_bad_input("tile --set no-such-set --algo direct --size 4x4", "unknown tile set 'no-such-set'");
  expect_bad_input(base + "--algo direct --out " + (d / "t.gif"), "unknown output format");
  expect_bad_input(base + "--algo direct --map " + (d / "m.json"), "--map only applies to --algo controlled");
  expect_bad_input(base + "--algo controlled --map " + (d / "missing.json"), "missing.json: no such probability map");
  write_text(d / "bad.json", R"({"colors":2,"rows":1,"cols":1,"p":[[[1,0]]]})");
  expect_bad_input(base + "--algo controlled --map " + (d / "bad.json"), "has 2 colours but tile set");
  expect_bad_input(base + "--algo direct --seed -3", "--seed");
  expect_bad_input(base + "--algo direct --out " + (d / "no-dir/t.png"), "cannot write");
  EXPECT_FALSE(std::filesystem::exists(d / "t.gif"));
  expect_bad_input("tileset show compact-wang-2 --out " + (d / "s.bmp"), "unknown picture format");
  EXPECT_FALSE(std::filesystem::exists(d / "s.bmp"));
}

TEST(CliAnalyze, NeighboursReportsMeanDeviationAndThePaperRow) {
  CliResult r = run_cli("analyze neighbors --colors 3 --algo halton --tilings 4 --max-size 300 --seed 2 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = r.json();
  EXPECT_EQ(j["colors"], 3);
  EXPECT_EQ(j["tilings"], 4);
  EXPECT_GT(j["corners"].get<long>(), 4);
  EXPECT_GT(j["mean"].get<double>(), 1.0);
  EXPECT_LT(j["mean"].get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(j["paper_mean"].get<double>(), 2.1548);
  EXPECT_NEAR(j["binomial_mean"].get<double>(), 8.0 / 3, 1e-12);
}

TEST(CliAnalyze, ReductionPrintsTable2WithAllThreeCountsEqual) {
  CliResult r = run_cli("analyze reduction --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto rows = r.json()["rows"];
  EXPECT_EQ(rows.size(), 20u);  // the entries of the paper's Table 2
  for (const auto& row : rows) {
    EXPECT_EQ(row["closed_form"], row["brute_force"]);
    EXPECT_EQ(row["closed_form"], row["inclusion_exclusion"]);
  }
}

TEST(CliAnalyze, BadInputIsExit2WithOneLine) {
  expect_bad_input("analyze neighbors --colors 3 --algo scanline", "unknown algorithm 'scanline'");
  expect_bad_input("analyze neighbors --colors 0", "--colors must be between 1 and 255");
  expect_bad_input("analyze neighbors --colors 3 --tilings 0", "--tilings must be at least 1");
  expect_bad_input("analyze neighbors --colors 3 --max-size 0", "--max-size must be between");
  expect_bad_input("analyze neighbors --colors 3 --algo direct --hash sha", "unknown hash 'sha'");
  expect_bad_input("analyze neighbors --algo halton", "--colors is required");
  expect_bad_input("analyze reduction --max-colors 40", "--max-colors");
}

TEST(CliTile, HelpWorksForTheNewCommands) {
  for (const char* cmd : {"tile", "analyze", "analyze neighbors", "analyze reduction"}) {
    CliResult r = run_cli(std::string(cmd) + " --help");
    EXPECT_EQ(r.code, 0) << cmd;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << cmd;
  }
}
