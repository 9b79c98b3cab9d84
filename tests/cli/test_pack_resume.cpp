// One engine for every search, end to end: `pack --resume FILE` alone continues the
// run the checkpoint describes, a contradicting flag is exit 2 naming it, imposed-group counts
// shard and thread like every other search, and the portfolio keeps checkpoints too.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "tests/cli_runner.hpp"

using namespace tilekit::test;
namespace fs = std::filesystem;

namespace {

struct Resume : ::testing::Test {
  TempDir dir;
  CliResult pack(const std::string& args) {
    return run_cli("pack --quiet --json --portfolio-stats " + (dir / "stats.json") + " " + args);
  }
};

TEST_F(Resume, CheckpointAloneContinuesTheRunItDescribes) {
  std::string ck = dir / "ck", db = dir / "r.sqlite";
  CliResult first = pack("--kind wang --colors 2 --mode count --impose 't=0,2:piv=1,0' --shard 1/2 --threads 1 --db " +
                         db + " --checkpoint " + ck);
  ASSERT_EQ(first.code, 0) << first.err;
  CliResult again = pack("--resume " + ck);  // no --kind, --colors, --mode, --impose, --shard
  ASSERT_EQ(again.code, 0) << again.err;
  auto j = again.json();
  EXPECT_EQ(j["solutions"], first.json()["solutions"]);
  EXPECT_EQ(j["kind"], "wang");
  EXPECT_EQ(j["mode"], "count");
  EXPECT_EQ(j["shard"], "1/2");
  EXPECT_EQ(j["group"]["spec"], "t=0,2:piv=1,0");
  EXPECT_EQ(j["db"], first.json()["db"]);  // the checkpoint remembers the database
  CliResult elsewhere = pack("--resume " + ck + " --db " + (dir / "other.sqlite"));
  ASSERT_EQ(elsewhere.code, 0) << elsewhere.err;
  EXPECT_NE(elsewhere.json()["db"], j["db"]);
  CliResult same_flags = pack("--resume " + ck + " --kind wang --colors 2 --mode count --shard 1/2");
  EXPECT_EQ(same_flags.code, 0) << same_flags.err;  // repeating the run's own flags is fine
}

TEST_F(Resume, FlagsThatContradictTheCheckpointAreExit2NamingTheDifference) {
  std::string ck = dir / "ck";
  ASSERT_EQ(pack("--kind wang --colors 2 --mode count --impose 't=0,2:pi=1,0' --db " + (dir / "r.sqlite") +
                 " --checkpoint " + ck)
                .code,
            0);
  struct Case {
    std::string args, flag;
  };
  for (const Case& c :
       {Case{"--mode all", "--mode"}, Case{"--impose 't=0,2:piv=1,0'", "--impose"}, Case{"--kind corner", "--kind"},
        Case{"--colors 3", "--colors"}, Case{"--shard 0/2", "--shard"}, Case{"--seed 5", "--seed"}}) {
    CliResult r = pack("--resume " + ck + " " + c.args);
    EXPECT_EQ(r.code, 2) << c.args;
    EXPECT_NE(r.err.find(c.flag + " is"), std::string::npos) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find("in the checkpoint"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

TEST_F(Resume, ImposedCountShardsSumToTheWholeOnTwoThreads) {
  for (const char* spec : {"t=0,2:piv=1,0", "t=2,2:pih=1,0"}) {
    CliResult whole = pack(std::string("--kind wang --colors 2 --mode count --threads 1 --impose ") + spec + " --db " +
                           (dir / "r.sqlite"));
    ASSERT_EQ(whole.code, 0) << whole.err;
    long sum = 0;
    for (int i = 0; i < 4; ++i) {
      CliResult r = pack(std::string("--kind wang --colors 2 --mode count --threads 2 --impose ") + spec + " --shard " +
                         std::to_string(i) + "/4 --db " + (dir / "r.sqlite"));
      ASSERT_EQ(r.code, 0) << r.err;
      EXPECT_EQ(r.json()["complete"], true);
      EXPECT_EQ(r.json()["threads"], 2);
      sum += r.json()["solutions"].get<long>();
    }
    EXPECT_EQ(sum, whole.json()["solutions"].get<long>()) << spec;
    EXPECT_GT(sum, 0);
  }
}

TEST_F(Resume, PortfolioRunsCheckpointAndResumeWithTheirBudgetAndStopOnSigtermWithExit3) {
  // C=5 corner by the portfolio on one thread: far more than 0.6 s (odd C would be answered by a
  // construction with --method auto).
  std::string ck = dir / "ck";
  CliResult a = pack("--kind corner --colors 5 --method search --threads 1 --time-limit 0.6 --checkpoint " + ck +
                     " --checkpoint-every 0.1 --db " + (dir / "r.sqlite"));
  if (a.code == 0) GTEST_SKIP() << "found a C=5 packing within 0.6 s";
  ASSERT_EQ(a.code, 1) << a.err;
  EXPECT_EQ(a.json()["timed_out"], true);
  ASSERT_TRUE(fs::exists(ck));
  CliResult b = pack("--resume " + ck + " --time-limit 0.6");
  if (b.code == 0) GTEST_SKIP() << "found a C=5 packing on resume";
  ASSERT_EQ(b.code, 1) << b.err;
  EXPECT_GT(b.json()["total_seconds"].get<double>(), a.json()["total_seconds"].get<double>() + 0.3);
  EXPECT_EQ(b.json()["formulation"], "portfolio");
  // SIGTERM: checkpoint, exit 3, and the portfolio state goes on from there.
  pid_t pid =
      spawn_tilekit({"pack", "--resume", ck, "--quiet", "--json", "--time-limit", "60"}, dir / "out", dir / "err");
  ASSERT_GT(pid, 0);
  EXPECT_TRUE(wait_until_catching(pid, SIGTERM, 60));  // the kill below ends it either way
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  kill(pid, SIGTERM);
  int code = wait_exit(pid);
  if (code == 0) GTEST_SKIP() << "found a C=5 packing before the signal";
  EXPECT_EQ(code, 3) << slurp(dir / "err");
  auto j = nlohmann::json::parse(slurp(dir / "out"));
  EXPECT_EQ(j["interrupted"], true);
  EXPECT_GT(j["total_seconds"].get<double>(), b.json()["total_seconds"].get<double>());
  CliResult contradiction = pack("--resume " + ck + " --plain");
  EXPECT_EQ(contradiction.code, 2);
  EXPECT_NE(contradiction.err.find("--plain"), std::string::npos) << contradiction.err;
}

}  // namespace
