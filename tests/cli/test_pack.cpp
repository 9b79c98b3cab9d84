// tilekit pack end to end: counts, first packings checked by `tilekit check`, JSON output,
// and bad input (exit 2 with one clear line).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "tests/cli_runner.hpp"

using namespace tilekit::test;

namespace {
// `tilekit pack ARGS` writing to a database of its own, never the user's default one.
CliResult pack(const std::string& args) {
  static TempDir db_dir;
  ::setenv("TILEKIT_PORTFOLIO_STATS", (db_dir / "portfolio.json").c_str(), 1);  // not the user's file
  return run_cli("pack --db " + (db_dir / "results.sqlite") + " " + args);
}
}  // namespace

TEST(PackCli, HelpListsTheContractOptions) {
  CliResult r = run_cli("pack --help");
  ASSERT_EQ(r.code, 0);
  for (const char* opt : {"--kind", "--colors", "--method", "--mode", "--threads", "--seed", "--checkpoint",
                          "--checkpoint-every", "--resume", "--db", "--shard", "--time-limit", "--json"})
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
}

TEST(PackCli, CountsTwoColourPackingsWithOneAndTwoThreads) {
  for (const char* threads : {"1", "2"}) {
    CliResult w =
        pack(std::string("--kind wang --colors 2 --mode count --method search --quiet --json --threads ") + threads);
    ASSERT_EQ(w.code, 0) << w.err;
    auto j = w.json();
    EXPECT_EQ(j["solutions"], 203520);
    EXPECT_EQ(j["complete"], true);
    EXPECT_EQ(j["method"], "search");
    EXPECT_EQ(j["threads"], std::stoi(threads));
    CliResult c = pack(std::string("--kind corner --colors 2 --mode count --quiet --json --threads ") + threads);
    ASSERT_EQ(c.code, 0) << c.err;
    EXPECT_EQ(c.json()["solutions"], 32);
    EXPECT_EQ(c.json()["orbits"], 1);
  }
}

TEST(PackCli, FirstPackingsOfThreeColoursPassTheIndependentCheck) {
  TempDir d;
  for (const char* kind : {"corner", "wang"}) {
    std::string out = d / (std::string(kind) + ".json");
    CliResult r =
        pack(std::string("--method search --quiet --json --threads 2 --colors 3 --kind ") + kind + " --out " + out);
    ASSERT_EQ(r.code, 0) << r.err;
    auto j = r.json();
    EXPECT_EQ(j["valid"], true);
    EXPECT_EQ(j["cells"].size(), 9u);
    CliResult c = run_cli("check " + out + " --set complete-" + kind + "-3 --json");
    ASSERT_EQ(c.code, 0) << c.err;
    EXPECT_EQ(c.json()["packing"], true);
  }
}

TEST(PackCli, PacksAnyTileSetWhoseSizeIsTheTorusArea) {
  CliResult r = pack("--set complete-wang-2x3 --size 4x9 --quiet --json --threads 1");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.json()["rows"], 4);
  EXPECT_EQ(r.json()["cols"], 9);
  EXPECT_EQ(r.json()["valid"], true);
  CliResult bad = pack("--set complete-wang-2x3 --size 5x7 --quiet");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("rows*cols"), std::string::npos) << bad.err;
}

TEST(PackCli, BadFlagsAreExit2WithAClearMessage) {
  struct Case {
    const char* args;
    const char* message;
  };
  for (Case c :
       {Case{"--kind wang --colors 0",
             "--colors must be between 1 and 64 for a packing or atlas of the complete set, got 0"},
        Case{"--kind wang --colors 2 --threads 5000", "--threads must be between 0 (every core) and 4096, got 5000"},
        Case{"--kind hexagon --colors 2", "unknown tile kind 'hexagon' (corner, wang or window)"},
        Case{"--kind wang --colors 2 --mode most", "unknown mode 'most'"},
        Case{"--kind wang --colors 2 --shard 4/4", "--shard must be I/N with 0 <= I < N <= 1000000, got '4/4'"},
        Case{"--kind wang --colors 2 --formulation pegs", "pegs formulation is for corner tiles"},
        Case{"--colors 2", "pack needs --kind"}}) {
    CliResult r = pack(std::string("--quiet ") + c.args);
    EXPECT_EQ(r.code, 2) << c.args;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(r.out.empty());
  }
}

TEST(PackCli, CorruptOrMismatchedCheckpointsAreExit2) {
  TempDir d;
  std::string ck = d / "ck";
  CliResult r = pack("--kind wang --colors 2 --mode count --quiet --checkpoint " + ck);
  ASSERT_EQ(r.code, 0) << r.err;
  std::string text = slurp(ck);
  ASSERT_FALSE(text.empty());
  CliResult again = pack("--kind wang --colors 2 --mode count --quiet --json --resume " + ck);
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_EQ(again.json()["solutions"], 203520);  // a finished checkpoint resumes to the same result
  CliResult mism = pack("--kind wang --colors 2 --mode count --seed 7 --quiet --resume " + ck);
  EXPECT_EQ(mism.code, 2);
  // The checkpoint holds the run's request; a flag that contradicts it is named.
  EXPECT_NE(mism.err.find("--seed is 7 here but 0 in the checkpoint"), std::string::npos) << mism.err;
  CliResult other = pack("--kind corner --colors 2 --mode count --quiet --resume " + ck);
  EXPECT_EQ(other.code, 2);
  EXPECT_NE(other.err.find("kind"), std::string::npos) << other.err;
  text[text.size() / 2] ^= 0x20;
  write_text(d / "bad", text);
  CliResult corrupt = pack("--kind wang --colors 2 --mode count --quiet --resume " + (d / "bad"));
  EXPECT_EQ(corrupt.code, 2);
  EXPECT_NE(corrupt.err.find("corrupt"), std::string::npos) << corrupt.err;
  write_text(d / "short", slurp(ck).substr(0, 40));
  CliResult truncated = pack("--kind wang --colors 2 --mode count --quiet --resume " + (d / "short"));
  EXPECT_EQ(truncated.code, 2);
  EXPECT_NE(truncated.err.find("truncated"), std::string::npos) << truncated.err;
}

TEST(PackCli, ShardsZeroToThreeOfFourSumToTheWhole) {
  long sum = 0;
  for (int i = 0; i < 4; ++i) {
    CliResult r = pack("--kind wang --colors 2 --mode count --quiet --json --shard " + std::to_string(i) + "/4");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.json()["shard"], std::to_string(i) + "/4");
    sum += r.json()["solutions"].get<long>();
  }
  EXPECT_EQ(sum, 203520);
}

TEST(PackCli, MethodsSayWhichAnsweredAndEachPackingValidates) {
  TempDir d;
  ::setenv("TILEKIT_PORTFOLIO_STATS", (d / "portfolio.json").c_str(), 1);
  std::string db = "--db " + (d / "r.sqlite") + " --quiet --json --kind corner --colors 3";
  CliResult c = run_cli("pack --method construct " + db);
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_EQ(c.json()["method"], "construct");
  EXPECT_EQ(c.json()["valid"], true);
  CliResult a = run_cli("pack --method auto " + db);  // the database now holds one
  ASSERT_EQ(a.code, 0) << a.err;
  EXPECT_EQ(a.json()["method"], "db");
  EXPECT_EQ(a.json()["cells"], c.json()["cells"]);
  CliResult s = run_cli("pack --method search --threads 2 " + db);
  ASSERT_EQ(s.code, 0) << s.err;
  EXPECT_EQ(s.json()["method"], "search");
  EXPECT_EQ(s.json()["valid"], true);
  CliResult w = run_cli("pack --method auto --quiet --json --kind wang --colors 5 --db " + (d / "w.sqlite"));
  ASSERT_EQ(w.code, 0) << w.err;
  EXPECT_EQ(w.json()["method"], "construct");
  EXPECT_EQ(w.json()["valid"], true);
  EXPECT_EQ(w.json()["cells"].size(), 25u);
  CliResult bad =
      run_cli("pack --method construct --mode count --kind wang --colors 2 --quiet --db " + (d / "r.sqlite"));
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--mode first"), std::string::npos) << bad.err;
}

TEST(PackCli, ImposedGroupFindsAFourColourWangPackingThatValidates) {
  TempDir d;
  std::string out = d / "w4.json";
  CliResult r =
      pack("--kind wang --colors 4 --impose t=0,8:pi=1,0,3,2 --threads 2 --time-limit 120 --quiet --json --out " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = r.json();
  EXPECT_EQ(j["method"], "search");
  EXPECT_EQ(j["valid"], true);
  EXPECT_FALSE(j["group"].is_null());
  CliResult c = run_cli("check " + out + " --set complete-wang-4 --json");
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_EQ(c.json()["packing"], true);
  CliResult bad = pack("--kind wang --colors 4 --impose t=banana --quiet");
  EXPECT_EQ(bad.code, 2);
  // Imposed groups run in the one engine, so they take checkpoints.
  CliResult mixed = pack("--kind wang --colors 2 --impose t=0,2:pi=1,0 --checkpoint " + (d / "ck") + " --quiet --json");
  EXPECT_EQ(mixed.code, 0) << mixed.err;
  EXPECT_EQ(mixed.json()["checkpoint"], d / "ck");
  EXPECT_TRUE(std::filesystem::exists(d / "ck"));
}
