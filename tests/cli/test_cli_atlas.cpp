#include <gtest/gtest.h>

#include "tests/cli_runner.hpp"

using namespace tilekit::test;

TEST(CliAtlas, HelpWorksForEveryAtlasCommand) {
  for (const char* cmd : {"atlas", "atlas lookup", "atlas build"}) {
    CliResult r = run_cli(std::string(cmd) + " --help");
    EXPECT_EQ(r.code, 0) << cmd << ": " << r.err;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << cmd;
  }
}

TEST(CliAtlas, LookupJsonHasTheContractFieldsAndAnInverse) {
  TempDir d;
  CliResult r = run_cli("atlas lookup --kind corner --colors 3 --db " + q(d / "none.sqlite"));
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = r.json();
  for (const char* k : {"kind", "colors", "rows", "cols", "cells", "positions", "source"}) EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["source"], "construct");
  EXPECT_EQ(j["rows"], 9);
  ASSERT_EQ(j["positions"].size(), 81u);
  for (int t = 0; t < 81; ++t) {
    const int row = j["positions"][t][0], col = j["positions"][t][1];
    EXPECT_EQ(j["cells"][row][col], t);
  }
  // The lookup JSON is a tiling file: the independent validator accepts it as a packing.
  write_text(d / "p.json", r.out);
  CliResult check = run_cli("check " + q(d / "p.json") + " --json");
  ASSERT_EQ(check.code, 0) << check.err;
  EXPECT_EQ(check.json()["packing"], true);
}

TEST(CliAtlas, PowersOfTwoAnswerFromThePackingsTheLiftSearchFound) {
  TempDir d;
  for (const char* c : {"8", "16"}) {
    CliResult r = run_cli(std::string("atlas lookup --kind corner --colors ") + c + " --db " + q(d / "r.sqlite"));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.json()["source"], "construct");
    EXPECT_EQ(r.json()["how"], "stored");
    write_text(d / "p.json", r.out);
    CliResult check = run_cli("check " + q(d / "p.json") + " --json");
    ASSERT_EQ(check.code, 0) << check.err;
    EXPECT_EQ(check.json()["packing"], true) << c;
  }
  EXPECT_EQ(run_cli("atlas lookup --kind corner --colors 0 --no-db").code, 2);
  EXPECT_EQ(run_cli("atlas lookup --kind hex --colors 3 --no-db").code, 2);
}

TEST(CliAtlas, AStoredPackingIsFoundInTheDatabase) {
  TempDir d;
  // Store a different C=3 packing than the construction (its rows rotated by one).
  CliResult c = run_cli("atlas lookup --kind corner --colors 3 --no-db");
  auto j = c.json();
  auto rows = j["cells"];
  for (std::size_t r = 0; r < rows.size(); ++r) j["cells"][r] = rows[(r + 1) % rows.size()];
  write_text(d / "shifted.json", j.dump());
  ASSERT_EQ(run_cli("db add " + q(d / "shifted.json") + " --db " + q(d / "r.sqlite")).code, 0);
  CliResult hit = run_cli("atlas lookup --kind corner --colors 3 --db " + q(d / "r.sqlite"));
  ASSERT_EQ(hit.code, 0) << hit.err;
  EXPECT_EQ(hit.json()["source"], "db");
  EXPECT_EQ(hit.json()["cells"], j["cells"]);
  EXPECT_EQ(run_cli("atlas lookup --kind corner --colors 3 --no-db --db " + q(d / "r.sqlite")).json()["source"],
            "construct");
}

TEST(CliAtlas, CHeaderAndGlslGoToFilesOrIntoJson) {
  TempDir d;
  CliResult h = run_cli("atlas lookup --kind wang --colors 2 --no-db --format c --out " + q(d / "a.h") + " --json");
  ASSERT_EQ(h.code, 0) << h.err;
  EXPECT_EQ(h.json()["out"], d / "a.h");
  EXPECT_NE(slurp(d / "a.h").find("tilekit_wang_2_positions[16][2]"), std::string::npos);
  CliResult g = run_cli("atlas lookup --kind corner --colors 5 --no-db --format glsl --json");
  ASSERT_EQ(g.code, 0) << g.err;
  EXPECT_NE(g.json()["text"].get<std::string>().find("vec2 tk_atlas_coord(vec2 uv)"), std::string::npos);
  EXPECT_EQ(g.json()["closed_form"], true);
}

TEST(CliAtlas, BuildWritesAContinuousAtlasPng) {
  TempDir d;
  CliResult r = run_cli("atlas build --kind corner --colors 3 --no-db --tile-size 16 --out " + q(d / "a.png") + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = r.json();
  EXPECT_EQ(j["width"], 144);
  EXPECT_LE(j["seam_jump"].get<int>(), j["interior_jump"].get<int>() + 2);
  EXPECT_EQ(slurp(d / "a.png").substr(1, 3), "PNG");
  EXPECT_EQ(run_cli("atlas build --kind corner --colors 3 --no-db --tiles " + q(d / "nope") + " --out " + q(d / "b.png")).code, 2);
  EXPECT_FALSE(std::filesystem::exists(d / "b.png"));
}
