// tilekit pack --kind window: de Bruijn tori end to end (first, count and all modes, the
// database, checkpoints, the stored tori, the agreement with --kind corner) and bad shapes
// (exit 2, one line naming the reason, nothing written).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "tests/cli_runner.hpp"

using namespace tilekit::test;

namespace {

CliResult pack_in(const TempDir& d, const std::string& args) {
  return run_cli("pack --quiet --json --db " + (d / "r.sqlite") + " " + args);
}

}  // namespace

TEST(PackWindow, FindsTheMustShowToriAndTheyValidate) {
  TempDir d;
  for (const char* shape : {"--window 2x3 --colors 2 --size 8x8", "--window 3x2 --colors 2 --size 8x8",
                            "--window 2x2 --colors 3 --size 9x9"}) {
    CliResult r = pack_in(d, std::string("--kind window --method search --threads 1 --out ") + (d / "t.json") + " " + shape);
    ASSERT_EQ(r.code, 0) << shape << ": " << r.err;
    auto j = r.json();
    EXPECT_EQ(j["kind"], "window");
    EXPECT_EQ(j["method"], "search");
    EXPECT_EQ(j["valid"], true);
    CliResult check = run_cli("check " + (d / "t.json") + " --json");
    ASSERT_EQ(check.code, 0) << check.err;
    EXPECT_EQ(check.json()["packing"], true) << shape;
  }
  // binary 3x3 windows on 16x32: the row-difference lift over the stored 2x3 torus
  CliResult b = pack_in(d, "--kind window --window 3x3 --colors 2 --size 16x32 --threads 1 --lift rows=" +
                            std::string(TILEKIT_SOURCE_DIR) + "/tilesets/data/window-2x3-2-16x4.json");
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_EQ(b.json()["valid"], true);
  EXPECT_EQ(b.json()["pegs"].size(), 16u);
}

TEST(PackWindow, StoredToriAnswerFirstModeAndCornerAgrees) {
  TempDir d;
  CliResult s = pack_in(d, "--kind window --window 3x3 --colors 2 --size 16x32");
  ASSERT_EQ(s.code, 0) << s.err;
  EXPECT_EQ(s.json()["method"], "construct");
  EXPECT_EQ(s.json()["construction"], "stored");
  // 2x2 windows default to the C^2 x C^2 torus and come from the corner constructions
  CliResult w = pack_in(d, "--kind window --window 2x2 --colors 5 --out " + (d / "w.json"));
  ASSERT_EQ(w.code, 0) << w.err;
  EXPECT_EQ(w.json()["construction"], "corner debruijn-triangular");
  CliResult c = pack_in(d, "--kind corner --colors 5 --method construct --out " + (d / "c.json"));
  ASSERT_EQ(c.code, 0) << c.err;
  ASSERT_EQ(run_cli("check " + (d / "c.json") + " --pegs-out " + (d / "cp.json")).code, 0);
  EXPECT_EQ(w.json()["pegs"], nlohmann::json::parse(slurp(d / "cp.json"))["pegs"]);  // the same symbols
  // counts agree: 32 binary 2x2 tori = the 32 corner packings of C = 2
  CliResult wc = pack_in(d, "--kind window --window 2x2 --colors 2 --mode count");
  CliResult cc = pack_in(d, "--kind corner --colors 2 --mode count");
  ASSERT_EQ(wc.code, 0) << wc.err;
  EXPECT_EQ(wc.json()["solutions"], 32);
  EXPECT_EQ(wc.json()["solutions"], cc.json()["solutions"]);
}

TEST(PackWindow, AllModeStoresEveryTorusAndDbShowGivesACheckableFile) {
  TempDir d;
  CliResult r = pack_in(d, "--kind window --window 1x2 --colors 3 --size 1x9 --mode all --threads 2");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.json()["solutions"], 216);
  EXPECT_EQ(r.json()["stored"], 216);
  CliResult list = run_cli("db list --kind window --json --db " + (d / "r.sqlite"));
  ASSERT_EQ(list.code, 0) << list.err;
  const auto rows = list.json()["rows"];
  ASSERT_FALSE(rows.empty());
  const std::string id = std::to_string(rows[0]["id"].get<int>());
  CliResult show = run_cli("db show " + id + " --json --db " + (d / "r.sqlite"));
  ASSERT_EQ(show.code, 0) << show.err;
  EXPECT_EQ(show.json()["window"], nlohmann::json::parse("[1,2]"));
  std::ofstream(d / "s.json") << show.out;
  CliResult check = run_cli("check " + (d / "s.json") + " --json");
  ASSERT_EQ(check.code, 0) << check.err;
  EXPECT_EQ(check.json()["packing"], true);
  // the database answers the next first-mode request
  CliResult again = pack_in(d, "--kind window --window 1x2 --colors 3 --size 1x9");
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_EQ(again.json()["method"], "db");
}

TEST(PackWindow, CountResumesFromItsCheckpointAlone) {
  TempDir d;
  const std::string ck = d / "ck";
  CliResult first = pack_in(d, "--kind window --window 1x2 --colors 3 --size 1x9 --mode count --checkpoint " + ck);
  ASSERT_EQ(first.code, 0) << first.err;
  CliResult resumed = pack_in(d, "--resume " + ck);
  ASSERT_EQ(resumed.code, 0) << resumed.err;
  EXPECT_EQ(resumed.json()["kind"], "window");
  EXPECT_EQ(resumed.json()["solutions"], 216);
  CliResult other = pack_in(d, "--window 2x1 --resume " + ck);
  EXPECT_EQ(other.code, 2);
  EXPECT_NE(other.err.find("--window"), std::string::npos);
}

TEST(PackWindow, BadShapesAreExit2NamingTheReason) {
  TempDir d;
  struct Case {
    const char* args;
    const char* reason;
  };
  for (const Case& c : {Case{"--window 3x3 --colors 2 --size 2x256", "larger than the 2x256 torus"},
                        Case{"--window 3x3 --colors 2 --size 16x16", "rows*cols = 512, not 256"},
                        Case{"--window 0x3 --colors 2 --size 1x8", "--window KxL"},
                        Case{"--window 3x0 --colors 2 --size 1x8", "--window KxL"},
                        Case{"--window 3x3 --colors 2", "needs --size RxS"},
                        Case{"--colors 2 --size 4x4", "needs --window KxL"}}) {
    CliResult r = pack_in(d, std::string("--kind window ") + c.args);
    EXPECT_EQ(r.code, 2) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.reason), std::string::npos) << c.args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(d / "r.sqlite"));  // nothing written
  CliResult corner = pack_in(d, "--kind corner --colors 2 --window 2x2");
  EXPECT_EQ(corner.code, 2);
}
