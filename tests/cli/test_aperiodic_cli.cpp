// End-to-end tests of `tilekit aperiodic convert | verify | table | smallest`.
#include <gtest/gtest.h>

#include <filesystem>

#include "results/results_db.hpp"
#include "tests/cli_runner.hpp"

using tilekit::test::run_cli;
using tilekit::test::TempDir;
using tilekit::test::write_text;

namespace {

// Six Wang tiles (n s w e) that tile only periodically, with period 2 (rows) x 3 (columns).
std::string periodic_2x3_file() {
  std::string text = "# a set built to be periodic: tile (i,j) encodes its position mod (2,3)\n";
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 3; ++j)
      text += std::to_string(i * 3 + j) + " " + std::to_string(((i + 1) % 2) * 3 + j) + " " + std::to_string(i * 3 + j) +
              " " + std::to_string(i * 3 + (j + 1) % 3) + "\n";
  return text;
}

}  // namespace

TEST(AperiodicConvertCli, DiagonalTranslationOfTheThreeReferenceSetsGives125_214_87) {
  int expected[] = {125, 214, 87};
  const char* names[] = {"culik-13", "kari-14", "ammann-gs-16"};
  for (int k = 0; k < 3; ++k) {
    auto r = run_cli(std::string("aperiodic convert ") + names[k] + " --method diagonal --json");
    ASSERT_EQ(r.code, 0) << r.err;
    auto j = r.json();
    EXPECT_EQ(j["tiles"], expected[k]);
    EXPECT_EQ(j["kind"], "corner");
    EXPECT_EQ(j["soundness"], "conjugate");
    EXPECT_EQ(j["method"], "diagonal");
  }
}

TEST(AperiodicConvertCli, RotationReportsWhiteAndBlackAndPruningReportsCounts) {
  auto r = run_cli("aperiodic convert kari-14 --method rotation --prune 2 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = r.json();
  EXPECT_EQ(j["white"], 14);
  EXPECT_EQ(j["black"], 80);
  EXPECT_EQ(j["pruned"]["before"], 94);
  EXPECT_LT(j["pruned"]["after"].get<int>(), 94);
  EXPECT_EQ(j["tiles"], j["pruned"]["after"]);
}

TEST(AperiodicConvertCli, WritesTheResultAndTheDatabaseRows) {
  TempDir d;
  auto r = run_cli("aperiodic convert ammann-gs-16 --method horizontal --out " + d / "h.tiles" + " --db " + d / "r.db" +
                   " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.json()["soundness"], "unverified");
  auto show = run_cli("tileset show " + d / "h.tiles" + " --json");
  ASSERT_EQ(show.code, 0) << show.err;
  EXPECT_EQ(show.json()["tiles"], 44);  // thesis Fig. 8.6
  EXPECT_EQ(show.json()["kind"], "corner");
  tilekit::ResultsDb db(d / "r.db", false);
  auto stats = db.stats();
  EXPECT_EQ(stats.conversions, 1u);
  EXPECT_EQ(stats.tilesets, 2u);
}

TEST(AperiodicConvertCli, VerifyRelabelsAPeriodicResultAndStoresTheLabel) {
  TempDir d;
  auto r = run_cli("aperiodic convert ammann-gs-16 --method horizontal --verify 4 --db " + d / "r.db" + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = r.json();
  EXPECT_EQ(j["soundness"], "periodic");  // the thesis' Fig. 8.6 set
  EXPECT_EQ(j["verify"]["verdict"], "periodic");
  tilekit::ResultsDb db(d / "r.db", false);
  auto conv = db.list_conversions();
  ASSERT_EQ(conv.size(), 1u);
  EXPECT_EQ(conv[0].soundness, "periodic");
  auto ok = run_cli("aperiodic convert kari-14 --method vertical --verify 4 --time-limit 1 --json");
  ASSERT_EQ(ok.code, 0) << ok.err;
  EXPECT_EQ(ok.json()["soundness"], "conjugate");
}

TEST(AperiodicCli, BadInputExitsWithCode2AndAClearMessage) {
  TempDir d;
  write_text(d / "empty.tiles", "# no tiles\n");
  write_text(d / "declared.tiles", "# colours: 2\n0 1 0 1\n0 1 2 1\n");
  write_text(d / "short.tiles", "0 1 0 1\n0 1 1\n");
  auto empty = run_cli("aperiodic convert " + d / "empty.tiles" + " --method diagonal --out " + d / "o.tiles");
  EXPECT_EQ(empty.code, 2);
  EXPECT_NE(empty.err.find("no tiles"), std::string::npos) << empty.err;
  EXPECT_FALSE(std::filesystem::exists(d / "o.tiles"));
  EXPECT_EQ(run_cli("aperiodic verify " + d / "empty.tiles").code, 2);
  auto declared = run_cli("aperiodic convert " + d / "declared.tiles" + " --method rotation");
  EXPECT_EQ(declared.code, 2);
  EXPECT_NE(declared.err.find("out of range"), std::string::npos) << declared.err;
  EXPECT_EQ(run_cli("aperiodic verify " + d / "short.tiles").code, 2);
  EXPECT_EQ(run_cli("aperiodic convert complete-corner-2 --method diagonal").code, 2);
  EXPECT_EQ(run_cli("aperiodic convert culik-13 --method sideways").code, 2);
  EXPECT_EQ(run_cli("aperiodic verify culik-13 --max-period 0").code, 2);
  EXPECT_EQ(run_cli("aperiodic verify culik-13 --route sideways").code, 2);
  EXPECT_EQ(run_cli("aperiodic verify culik-13 --time-limit -1").code, 2);
  auto torus_ck = run_cli("aperiodic verify culik-13 --route torus --checkpoint " + d / "v.ckpt");
  EXPECT_EQ(torus_ck.code, 2);
  EXPECT_NE(torus_ck.err.find("torus route keeps no checkpoint"), std::string::npos) << torus_ck.err;
  EXPECT_FALSE(std::filesystem::exists(d / "v.ckpt"));
}

TEST(AperiodicVerifyCli, FindsThePeriodOfASetBuiltToBePeriodic) {
  TempDir d;
  write_text(d / "p.tiles", periodic_2x3_file());
  auto r = run_cli("aperiodic verify " + d / "p.tiles" + " --max-period 4 --db " + d / "r.db" + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = r.json();
  EXPECT_EQ(j["verdict"], "periodic");
  EXPECT_EQ(j["period"], nlohmann::json::array({2, 3}));
  // The witness uses tile numbers of `tileset show`: check it matches, wrap-around included.
  auto list = run_cli("tileset show " + d / "p.tiles" + " --json").json()["list"];  // n s w e
  auto w = j["witness"];
  ASSERT_EQ(w.size(), 2u);
  ASSERT_EQ(w[0].size(), 3u);
  for (int r0 = 0; r0 < 2; ++r0)
    for (int c = 0; c < 3; ++c) {
      auto t = list[w[r0][c].get<int>()], right = list[w[r0][(c + 1) % 3].get<int>()], below = list[w[(r0 + 1) % 2][c].get<int>()];
      EXPECT_EQ(t[3], right[2]);  // e == w
      EXPECT_EQ(t[1], below[0]);  // s == n
    }
  tilekit::ResultsDb db(d / "r.db", false);
  EXPECT_EQ(db.stats().solutions, 1u);
  EXPECT_EQ(db.stats().runs, 1u);
}

TEST(AperiodicVerifyCli, Culik13HasNoPeriodUpToEightAndTheFilterSaysWhy) {
  auto r = run_cli("aperiodic verify culik-13 --route torus --max-period 8 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = r.json();
  EXPECT_EQ(j["verdict"], "no-period-up-to 8");
  EXPECT_EQ(j["period"], nullptr);
  EXPECT_EQ(j["shapes_excluded"].get<int>() + j["shapes_searched"].get<int>(), 64);
}

TEST(AperiodicVerifyCli, ASetThatTilesNoSquareIsFiniteByBothRoutes) {
  TempDir d;
  write_text(d / "row.tiles", "0 1 0 0\n");  // n=0, s=1: rows never stack
  auto r = run_cli("aperiodic verify " + d / "row.tiles" + " --route torus --max-period 3 --max-square 4 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.json()["verdict"], "finite");
  EXPECT_EQ(r.json()["route"], "torus");
  EXPECT_EQ(r.json()["largest_square"], 1);
  auto t = run_cli("aperiodic verify " + d / "row.tiles" + " --json");
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_EQ(t.json()["verdict"], "finite");
  EXPECT_EQ(t.json()["route"], "transducer");
  EXPECT_EQ(t.json()["k"], 1);
  EXPECT_GE(t.json()["square_bound"].get<int>(), 1);
  // Pruning alone removes its only tile (no tile above it can match): finite as well.
  auto pruned = run_cli("aperiodic verify " + d / "row.tiles" + " --prune 1 --json");
  ASSERT_EQ(pruned.code, 0) << pruned.err;
  EXPECT_EQ(pruned.json()["verdict"], "finite");
  EXPECT_EQ(pruned.json()["pruned"]["after"], 0);
}

TEST(AperiodicTableCli, ReproducesTable81AndExplainsEveryDifference) {
  auto r = run_cli("aperiodic table --max-period 6 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = r.json();
  auto t81 = j["tables"][0];
  EXPECT_EQ(t81["id"], "8.1");
  EXPECT_EQ(t81["cells"][0][0]["text"], "125/13");
  EXPECT_EQ(t81["cells"][1][3]["text"], "94(14+80)/9");
  EXPECT_EQ(t81["cells"][2][1]["text"], "44/6");
  EXPECT_EQ(t81["cells"][3][0]["text"], "missing");  // the thesis' 24/24 set
  EXPECT_EQ(j["unexplained"], 0);
  EXPECT_LT(j["seconds"].get<double>(), 30.0);
  // Table 8.3, last row: kari-14 reaches 1,213,029 corner tiles as in the thesis.
  EXPECT_EQ(j["tables"][2]["cells"][7][1]["ours"]["tiles"], 1213029);
  bool fig86_periodic = false;
  for (auto& c : j["verification"])
    if (c["source"] == "ammann-gs-16" && c["method"] == "horizontal") fig86_periodic = c["status"] == "false";
  EXPECT_TRUE(fig86_periodic);  // the thesis' 44-tile set tiles periodically
  EXPECT_LT(j["smallest"]["tiles"].get<int>(), 44);
}

TEST(AperiodicSmallestCli, GivesASoundChainAndWritesTheSet) {
  TempDir d;
  auto r = run_cli("aperiodic smallest --max-period 6 --out " + d / "s.tiles" + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = r.json();
  EXPECT_GE(j["chain"].size(), 2u);
  EXPECT_EQ(j["chain"][0]["label"], "published");
  for (std::size_t i = 1; i < j["chain"].size(); ++i) {
    const std::string label = j["chain"][i]["label"];
    EXPECT_TRUE(label == "conjugate" || label == "lifts" || label == "prune") << label;
  }
  // The chain the recorded enumeration found (aperiodic/data/smallest-chain.json), below Nurmi's 30.
  EXPECT_LE(j["tiles"].get<int>(), 29);
  EXPECT_EQ(j["set"], j["chain"].back()["set"]);
  EXPECT_EQ(j["found_by"]["command"].get<std::string>().rfind("tilekit aperiodic enumerate", 0), 0u);
  EXPECT_NE(j["verify"]["verdict"], "periodic");
  EXPECT_NE(j["verify"]["verdict"], "finite");
  EXPECT_EQ(run_cli("tileset show " + d / "s.tiles" + " --json").json()["tiles"], j["tiles"]);
}

TEST(AperiodicCli, EverySubcommandHasHelp) {
  for (const char* c : {"convert", "verify", "table", "smallest"}) {
    auto r = run_cli(std::string("aperiodic ") + c + " --help");
    EXPECT_EQ(r.code, 0) << c;
    EXPECT_NE(r.out.find("--json"), std::string::npos) << c;
  }
}
