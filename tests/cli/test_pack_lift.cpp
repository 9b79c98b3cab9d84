// tilekit pack --lift: colour-quotient lift searches end to end, by the engine and by
// cadical, with checkpoints, shards and signals like every other search, and bad specs.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "tests/cli_runner.hpp"

using namespace tilekit::test;

namespace {

CliResult pack(const TempDir& d, const std::string& args) {
  return run_cli("pack --quiet --json --db " + (d / "r.sqlite") + " " + args);
}

}  // namespace

TEST(PackLift, FindsAFourColourCornerPackingOverTheTwoColourOneAndItValidates) {
  TempDir d;
  CliResult r = pack(d, "--kind corner --colors 4 --lift 2 --threads 1 --out " + (d / "p.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = r.json();
  EXPECT_EQ(j["method"], "search");
  EXPECT_EQ(j["formulation"], "lift");
  EXPECT_EQ(j["valid"], true);
  EXPECT_EQ(j["solutions"], 1);
  CliResult check = run_cli("check " + (d / "p.json") + " --json");
  ASSERT_EQ(check.code, 0) << check.err;
  EXPECT_EQ(check.json()["packing"], true);
}

TEST(PackLift, CadicalFindsAFourColourWangPacking) {
  if (std::system("command -v cadical >/dev/null 2>&1") != 0) GTEST_SKIP() << "cadical not installed";
  TempDir d;
  CliResult r = pack(d, "--kind wang --colors 4 --lift 2 --formulation sat");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.json()["formulation"], "sat");
  EXPECT_EQ(r.json()["valid"], true);
}

TEST(PackLift, CountsCheckpointsAndShardsLikeThePlainEngine) {
  // m = 1: the lift subspace of C = 2 is every packing (32 corner, 203,520 Wang).
  TempDir d;
  CliResult whole = pack(d, "--kind corner --colors 2 --lift 1 --mode count --checkpoint " + (d / "ck"));
  ASSERT_EQ(whole.code, 0) << whole.err;
  EXPECT_EQ(whole.json()["solutions"], 32);
  EXPECT_EQ(whole.json()["complete"], true);
  CliResult resumed = pack(d, "--kind corner --colors 2 --lift 1 --mode count --resume " + (d / "ck"));
  ASSERT_EQ(resumed.code, 0) << resumed.err;
  EXPECT_EQ(resumed.json()["solutions"], 32);
  // Without --lift the checkpoint's request supplies it: still the lift search, not the plain one.
  CliResult implied = pack(d, "--kind corner --colors 2 --mode count --resume " + (d / "ck"));
  ASSERT_EQ(implied.code, 0) << implied.err;
  EXPECT_EQ(implied.json()["formulation"], "lift");
  std::uint64_t sum = 0;
  for (int i = 0; i < 3; ++i) {
    CliResult s =
        pack(d, "--kind wang --colors 2 --lift 1 --mode count --threads 2 --shard " + std::to_string(i) + "/3");
    ASSERT_EQ(s.code, 0) << s.err;
    sum += s.json()["solutions"].get<std::uint64_t>();
  }
  EXPECT_EQ(sum, 203520u);
}

TEST(PackLift, SigtermWritesACheckpointAndExits3) {
  TempDir d;
  const std::string ck = d / "ck";
  // C=8 over C=4 by the engine: far from done within the test.
  pid_t pid = spawn_tilekit({"pack", "--kind", "corner", "--colors", "8", "--lift", "4", "--threads", "1", "--quiet",
                             "--json", "--checkpoint", ck, "--db", d / "r.sqlite"},
                            d / "out", d / "err");
  ASSERT_GT(pid, 0);
  EXPECT_TRUE(wait_until_catching(pid, SIGTERM, 60));  // the kill below ends it either way
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  kill(pid, SIGTERM);
  EXPECT_EQ(wait_exit(pid), 3) << slurp(d / "err");
  EXPECT_NE(slurp(d / "err").find("checkpoint written to " + ck), std::string::npos) << slurp(d / "err");
  // --resume FILE alone continues the lift search the checkpoint describes (kind, C, lift, mode).
  CliResult resumed = run_cli("pack --quiet --json --threads 1 --time-limit 0.5 --resume " + ck);
  EXPECT_EQ(resumed.code, 1) << resumed.err;  // continues, then stops at the time limit without a packing
  EXPECT_EQ(resumed.json()["formulation"], "lift");
  EXPECT_EQ(resumed.json()["colors"], 8);
  EXPECT_GT(resumed.json()["total_seconds"].get<double>(), resumed.json()["seconds"].get<double>());
  // A flag contradicting the checkpoint is exit 2 naming it.
  CliResult other = run_cli("pack --quiet --json --lift 2 --resume " + ck);
  EXPECT_EQ(other.code, 2);
  EXPECT_NE(other.err.find("--lift"), std::string::npos) << other.err;
}

TEST(PackLift, BadSpecsAreExit2WithOneLine) {
  TempDir d;
  for (const char* args :
       {"--kind corner --colors 4 --lift 3", "--kind corner --colors 4 --lift x", "--kind corner --colors 4 --lift 4",
        "--kind corner --colors 4 --lift 2,q=1", "--kind corner --colors 4 --lift 2 --impose t=0,8:pi=1,0,3,2",
        "--kind corner --colors 4 --lift 2 --formulation cellz",
        "--kind corner --colors 4 --lift m=2,base=/nonexistent.json", "--set complete-corner-2 --size 2x8 --lift 1"}) {
    CliResult r = pack(d, args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find("--lift"), std::string::npos) << args << "\n" << r.err;
  }
}

// The base file of a lift is stored absolute, so `pack --resume F` works from another directory;
// and base=FILE runs to the end of the spec, so a path with a comma can be given.
TEST(PackLift, ABaseWithACommaResumesFromAnotherDirectory) {
  TempDir d;
  const std::string dir = d / "a,b";
  std::filesystem::create_directories(dir);
  ASSERT_EQ(run_cli("pack --kind corner --colors 2 --quiet --out " + q(dir + "/base.json")).code, 0);
  const std::string ck = d / "lift.ckpt";
  CliResult first = run_cli_prefixed("cd " + q(d.path.string()) + " && ",
                                     "pack --kind corner --colors 4 --lift m=2,base=a,b/base.json --threads 1 --quiet "
                                     "--json --checkpoint " + q(ck) + " --db " + q(d / "r.sqlite"));
  ASSERT_EQ(first.code, 0) << first.err;
  EXPECT_EQ(first.json()["valid"], true);
  ASSERT_TRUE(std::filesystem::exists(ck));
  CliResult resumed = run_cli_prefixed("cd / && ", "pack --resume " + q(ck) + " --quiet --json --db " + q(d / "r2.sqlite"));
  ASSERT_EQ(resumed.code, 0) << resumed.err;
  EXPECT_EQ(resumed.json()["formulation"], "lift");
}
