// tilekit points: the commands end to end (JSON, files, exit codes).
#include <gtest/gtest.h>

#include "../cli_runner.hpp"

using namespace tilekit::test;

TEST(PointsCli, TilesBuildsChecksStoresAndWritesASetThatGenerateReads) {
  TempDir d;
  const std::string db = d / "r.sqlite", set = d / "c.ptiles", pic = d / "t.svg";
  auto r = run_cli("points tiles --colors 2 --points 32 --json --quiet --db " + q(db) + " --out " + q(set) +
                   " --picture " + q(pic));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = r.json();
  EXPECT_EQ(j["tiles"], 16);
  EXPECT_GE(j["check"]["rho_across"].get<double>(), 0.75);
  EXPECT_TRUE(j["check"]["exhaustive"].get<bool>());
  EXPECT_GT(j["tileset_id"].get<int>(), 0);
  EXPECT_NE(slurp(pic).find("<circle"), std::string::npos);
  // From the file and from the database: the same points.
  const std::string a = d / "a.f32", b = d / "b.csv";
  r = run_cli("points generate --tiles " + q(set) + " --window 0,0,4,3 --density 32 --out " + q(a) +
              " --json --analyze");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.json()["points"], 4 * 3 * 32);
  EXPECT_GE(r.json()["radius"]["rho_across"].get<double>(), 0.75);
  EXPECT_EQ(slurp(a).size(), 4u * 3 * 32 * 8);
  r = run_cli("points generate --tiles db:" + std::to_string(j["tileset_id"].get<int>()) + " --db " + q(db) +
              " --window 0,0,4,3 --density 32 --out " + q(b) + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.json()["points"], 4 * 3 * 32);
  // analyze reads both formats and measures rho across the tile borders.
  r = run_cli("points analyze " + q(b) + " --window 0,0,4,3 --tile-size 1 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_GE(r.json()["rho_across"].get<double>(), 0.75);
  EXPECT_EQ(r.json()["points"], 384);
}

// A tile set written to a point file streams row by row: the same bytes as the points made in
// memory (--analyze keeps them there), in every format, and a window far larger than the memory
// limit still goes to the file with the memory of a few rows.
TEST(PointsCli, StreamedPointFilesEqualTheInMemoryOnesAndNeedOnlyRowsOfMemory) {
  TempDir d;
  const std::string set = d / "c.ptiles";
  ASSERT_EQ(run_cli("points tiles --colors 2 --points 32 --no-db --quiet --out " + q(set)).code, 0);
  for (const char* ext : {".f32", ".f64", ".csv"})
    for (const char* threads : {"1", "2"}) {
      const std::string streamed = d / (std::string("s") + threads + ext), kept = d / (std::string("m") + threads + ext);
      const std::string common = "points generate --tiles " + q(set) + " --window=-3.5,2,40.25,31 --density 32 " +
                                 "--seed 5 --threads " + threads + " --json --quiet --out ";
      auto r = run_cli(common + q(streamed));
      ASSERT_EQ(r.code, 0) << r.err;
      EXPECT_TRUE(r.json().value("streamed", false));
      r = run_cli(common + q(kept) + " --analyze");
      ASSERT_EQ(r.code, 0) << r.err;
      EXPECT_FALSE(r.json().contains("streamed"));
      EXPECT_EQ(slurp(streamed), slurp(kept)) << ext << " on " << threads << " thread(s)";
    }
  // 1e7 points (80 MB of float32) under a 64 MB limit: held in memory they would need 400 MB.
  const std::string big = d / "big.f32";
  const std::string cmd = "points generate --tiles " + q(set) + " --window 0,0,1000,1000 --density 10 --threads 1 " +
                          "--quiet --json --out ";
  EXPECT_EQ(run_cli_prefixed("env TILEKIT_MEMORY=64M ", cmd + q(d / "big.png")).code, 2);
  const auto r = run_cli_prefixed("env TILEKIT_MEMORY=64M ", cmd + q(big));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(big).size(), 8 * r.json()["points"].get<std::size_t>());
  EXPECT_NEAR(r.json()["points"].get<double>(), 1e7, 1e5);
}

TEST(PointsCli, BadInputIsExitCodeTwoWithOneLine) {
  TempDir d;
  EXPECT_EQ(run_cli("points generate --method corner --colors 2 --points 32 --window 0,0,x,1 --density 4").code, 2);
  EXPECT_EQ(run_cli("points generate --method nosuch --window 0,0,1,1 --density 4").code, 2);
  EXPECT_EQ(run_cli("points generate --method white --window 0,0,1,1 --density -4").code, 2);
  EXPECT_EQ(run_cli("points tiles --points 4 --no-db --quiet").code, 2);
  EXPECT_EQ(run_cli("points tiles --rho 1.5 --no-db --quiet").code, 2);
  write_text(d / "bad.ptiles", "TILEKIT-POINT-TILES 1\nmethod corner\n");
  const auto r = run_cli("points generate --tiles " + q(d / "bad.ptiles") + " --window 0,0,1,1 --density 4");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("bad.ptiles"), std::string::npos);
  // A point tile-set file from a newer format version: exit 2 naming the version.
  std::string v1 = slurp(std::string(TILEKIT_SOURCE_DIR) + "/points/data/corner-c2-n32-v1.ptiles");
  write_text(d / "v9.ptiles", "TILEKIT-POINT-TILES 9" + v1.substr(v1.find('\n')));
  const auto newer = run_cli("points generate --tiles " + q(d / "v9.ptiles") + " --window 0,0,1,1 --density 32");
  EXPECT_EQ(newer.code, 2);
  EXPECT_NE(newer.err.find("format version 9 is newer"), std::string::npos) << newer.err;
  EXPECT_EQ(run_cli("points tiles --method dual --edge-colors 2 --no-db --quiet").code, 2);
  EXPECT_EQ(run_cli("points analyze " + q(d / "missing.f32")).code, 2);
  write_text(d / "odd.f32", "123");
  EXPECT_EQ(run_cli("points analyze " + q(d / "odd.f32")).code, 2);
  EXPECT_EQ(run_cli("points generate --method white --window 0,0,1,1 --density 4 --out " + q(d / "x.txt")).code, 2);
}

TEST(PointsCli, SpectrumComparesMethodsAndDrawsPlots) {
  TempDir d;
  const auto r =
      run_cli("points spectrum --method white --compare grid --sets 2 --set-points 1024 --json --quiet --plot " +
              q(d / "p.svg") + " --image " + q(d / "s.png"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = r.json();
  EXPECT_EQ(j["method"], "white");
  EXPECT_NEAR(j["mean_anisotropy_db"].get<double>(), -3.0, 1.0);  // K = 2: 10 log10(1/2)
  EXPECT_EQ(j["compare"][0]["method"], "grid");
  EXPECT_NE(slurp(d / "p.svg").find("<line"), std::string::npos);
  EXPECT_EQ(slurp(d / "s.png").substr(1, 3), "PNG");
}

TEST(PointsCli, ZonePlateRecursiveAndObjects) {
  TempDir d;
  auto r = run_cli("points zoneplate --method jitter --out " + q(d / "z.png") + " --json --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_LT(r.json()["rms_inner"].get<double>(), 0.2);
  r = run_cli("points recursive --points 64 --out " + q(d / "k.rtiles") + " --no-db --json --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.json()["types"], 8);
  r = run_cli("points generate --method recursive --tiles " + q(d / "k.rtiles") +
              " --window 0,0,2,2 --density 500 --density-expr '500 * x' --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NEAR(r.json()["points"].get<double>(), 2000, 200);  // integral of 500 x over [0,2]^2
  r = run_cli(
      "points objects --colors 2 --points 32 --window 0,0,10,10 --density 40 --objects a:1,b:3 --json --quiet "
      "--out " +
      q(d / "o.csv") + " --texture " + q(d / "t.png") + " --px 64");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NEAR(r.json()["points"].get<double>(), 4000, 40);
  EXPECT_NE(slurp(d / "o.csv").find("x,y,object"), std::string::npos);
}
