// `tilekit cluster submit|status` without a Slurm: the scripts it writes (--dry-run) and the
// progress it reads, through the binary. The library's own tests are tests/cluster/; the
// real-Slurm run is tests/slurm/cluster-test.sh.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <regex>

#include "cluster/plan.hpp"
#include "tests/cli_runner.hpp"
#include "base/error.hpp"

namespace tilekit {
namespace {
using test::run_cli;
using test::TempDir;
using test::write_text;

TEST(ClusterSubmit, DryRunPrintsScriptsWithACommentOnEveryDirectiveAndWritesNothing) {
  TempDir d;
  auto r = run_cli("cluster submit --kind wang --colors 2 --shards 4 --cpus-per-task 3 --time 2:00:00 "
                   "--partition long --run-dir " + d / "run" + " --dry-run --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = r.json();
  EXPECT_TRUE(j["dry_run"].get<bool>());
  ASSERT_EQ(j["scripts"].size(), 3u);
  std::string array = j["scripts"][d / "run/pack-array.sbatch"];
  std::string merge = j["scripts"][d / "run/merge.sbatch"];
  std::string submit = j["scripts"][d / "run/submit.sh"];
  for (const char* directive : {"#SBATCH --array=0-3 ", "#SBATCH --cpus-per-task=3 ", "#SBATCH --time=2:00:00 ",
                                "#SBATCH --signal=B:USR1@120 ", "#SBATCH --requeue ", "#SBATCH --partition=long "})
    EXPECT_NE(array.find(directive), std::string::npos) << directive;
  EXPECT_NE(array.find("PACK_ARGS=(--kind wang --colors 2 --mode all)"), std::string::npos);
  EXPECT_NE(array.find("OMP_NUM_THREADS=${SLURM_CPUS_PER_TASK"), std::string::npos);
  EXPECT_NE(array.find("scontrol requeue"), std::string::npos);
  EXPECT_NE(merge.find("db merge"), std::string::npos);
  EXPECT_NE(submit.find("--dependency=afterok:"), std::string::npos);
  // Every #SBATCH line carries a comment saying what it is for.
  std::regex commented(R"(^#SBATCH --\S+ +# \S.*$)");
  int directives = 0;
  for (const std::string& text : {array, merge}) {
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
      if (line.rfind("#SBATCH", 0) == 0) {
        ++directives;
        EXPECT_TRUE(std::regex_match(line, commented)) << line;
      }
  }
  EXPECT_GE(directives, 15);
  // bash accepts all three, and nothing was written.
  for (const std::string& text : {array, merge, submit}) {
    write_text(d / "check.sh", text);
    EXPECT_EQ(std::system(("bash -n " + d / "check.sh").c_str()), 0);
  }
  EXPECT_FALSE(std::filesystem::exists(d / "run"));
}

TEST(ClusterSubmit, JobsRunTheTilekitOnPathElseThisOneAndTilekitFlagOverridesBoth) {
  namespace fs = std::filesystem;
  TempDir d;
  fs::create_directories(d / "bin");
  fs::create_directories(d / "plain/tilekit");  // a directory named tilekit is no binary
  write_text(d / "bin/tilekit", "#!/bin/sh\n");
  fs::create_directories(d / "noexec");
  write_text(d / "noexec/tilekit", "#!/bin/sh\n");
  fs::permissions(d / "bin/tilekit", fs::perms::owner_all);
  const std::string self = fs::canonical(TILEKIT_BINARY).string();
  const std::string installed = fs::canonical(d / "bin/tilekit").string();
  EXPECT_EQ(cluster::default_job_binary(d / "plain:" + d / "noexec:" + d / "bin:/usr/bin", TILEKIT_BINARY), installed);
  EXPECT_EQ(cluster::default_job_binary(d / "plain:" + d / "noexec", TILEKIT_BINARY), self);
  EXPECT_EQ(cluster::default_job_binary("", TILEKIT_BINARY), self);

  const std::string submit = "cluster submit --kind corner --colors 3 --shards 2 --dry-run --json --run-dir " + d / "r";
  auto on_path = test::run_cli_prefixed("env PATH=" + d / "bin" + ":/usr/bin:/bin ", submit);
  ASSERT_EQ(on_path.code, 0) << on_path.err;
  EXPECT_EQ(on_path.json()["tilekit"], installed);
  const std::string array = on_path.json()["scripts"][d / "r/pack-array.sbatch"];
  EXPECT_NE(array.find("TILEKIT=" + installed + "\n"), std::string::npos) << array;
  auto not_on_path = test::run_cli_prefixed("env PATH=/usr/bin:/bin ", submit);
  EXPECT_EQ(not_on_path.json()["tilekit"], self);
  auto flag = test::run_cli_prefixed("env PATH=" + d / "bin" + ":/usr/bin:/bin ", submit + " --tilekit " + self);
  EXPECT_EQ(flag.json()["tilekit"], self);
  auto bad = run_cli(submit + " --tilekit " + d / "noexec/tilekit");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("not an executable file"), std::string::npos) << bad.err;
}

TEST(ClusterSubmit, HumanDryRunNamesEachScript) {
  TempDir d;
  auto r = run_cli("cluster submit --kind corner --colors 3 --shards 2 --run-dir " + d / "r" + " --dry-run");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("==> " + d / "r/pack-array.sbatch <=="), std::string::npos);
  EXPECT_NE(r.out.find("#SBATCH --array=0-1"), std::string::npos);
}

TEST(ClusterSubmit, BadInputIsExitTwo) {
  TempDir d;
  std::string base = "cluster submit --kind wang --colors 2 --dry-run --run-dir " + d / "r";
  EXPECT_EQ(run_cli(base + " --shards 0").code, 2);
  EXPECT_EQ(run_cli(base + " --shards 2 --time soon").code, 2);
  EXPECT_EQ(run_cli(base + " --shards 2 --time 1 --signal-seconds 60").code, 2);
  EXPECT_EQ(run_cli(base + " --shards 2 --pack-arg=--db=x.sqlite").code, 2);
  EXPECT_EQ(run_cli("cluster submit --kind hex --colors 2 --shards 2 --dry-run").code, 2);
  EXPECT_EQ(run_cli("cluster submit --kind wang --colors 2 --shards 2 --dry-run --run-dir '" + d / "a b" + "'").code, 2);
}

TEST(ClusterSubmit, AnInfiniteOrHugeCheckpointIntervalIsExitTwoAndNothingIsWritten) {
  TempDir d;
  for (const char* every : {"inf", "1e308", "nan", "0"}) {
    auto r = run_cli("cluster submit --kind wang --colors 2 --shards 2 --run-dir " + d / "r" +
                     " --sbatch /bin/false --checkpoint-every " + every);
    EXPECT_EQ(r.code, 2) << every << ": " << r.err;
    EXPECT_NE(r.err.find("--checkpoint-every"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(d / "r")) << every;
  }
}

TEST(ClusterSubmit, WithoutSbatchItIsNotFoundAndSaysSo) {
  TempDir d;
  auto r = run_cli("cluster submit --kind wang --colors 2 --shards 2 --run-dir " + d / "r" +
                   " --sbatch /nonexistent/sbatch");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("not found"), std::string::npos) << r.err;
}

TEST(ClusterSubmit, RefusesARunDirectoryHoldingAnotherRun) {
  TempDir d;
  std::filesystem::create_directories(d / "r");
  write_text(d / "r/run.json", R"({"shards": 3, "pack_args": ["--kind","wang","--colors","2","--mode","all"]})");
  auto r = run_cli("cluster submit --kind wang --colors 2 --shards 4 --run-dir " + d / "r" + " --sbatch /bin/false");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("different run"), std::string::npos) << r.err;
}

TEST(ClusterStatus, ReadsEachShardsAttemptsResultAndTheMergedCount) {
  TempDir d;
  std::filesystem::create_directories(d / "r/shards");
  write_text(d / "r/run.json", R"({"shards": 3, "pack_args": ["--kind","wang","--colors","2"]})");
  write_text(d / "r/shards/shard-0.attempts",
             "{\"attempt\":0,\"exit\":3,\"resumed\":false}\n{\"attempt\":1,\"exit\":0,\"resumed\":true}\n");
  write_text(d / "r/shards/shard-0.done.json", R"({"solutions": 7, "complete": true})");
  write_text(d / "r/shards/shard-1.attempts", "{\"attempt\":0,\"exit\":3,\"resumed\":false}\n{\"attem");
  write_text(d / "r/shards/shard-1.ckpt", "x");
  write_text(d / "r/merged.json", R"({"solutions": 7, "distinct_solutions": 2})");
  auto r = run_cli("cluster status --run-dir " + d / "r" + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = r.json();
  EXPECT_EQ(j["done"], 1);
  EXPECT_EQ(j["checkpointed"], 1);
  EXPECT_EQ(j["pending"], 1);
  EXPECT_EQ(j["solutions_in_done_shards"], 7);
  EXPECT_EQ(j["merged_solutions"], 7);
  EXPECT_EQ(j["merged_orbits"], 2);
  auto s = j["per_shard"];
  EXPECT_EQ(s[0]["attempts"], 2);
  EXPECT_EQ(s[0]["checkpointed_exits"], 1);
  EXPECT_EQ(s[0]["last_exit"], 0);
  EXPECT_EQ(s[1]["attempts"], 1);  // the line cut short by a kill is skipped
  EXPECT_EQ(s[1]["state"], "checkpointed");
  EXPECT_TRUE(s[1]["progress"].contains("error"));  // "x" is not a checkpoint
  EXPECT_EQ(s[2]["state"], "pending");
}

TEST(ClusterStatus, ReadsProgressFromARealShardCheckpoint) {
  TempDir d;
  std::filesystem::create_directories(d / "r/shards");
  write_text(d / "r/run.json", R"({"shards": 4, "pack_args": ["--kind","wang","--colors","2","--mode","count"]})");
  auto pack = run_cli("pack --kind wang --colors 2 --mode count --method search --threads 1 --shard 1/4 --quiet "
                      "--checkpoint " + d / "r/shards/shard-1.ckpt --json");
  ASSERT_EQ(pack.code, 0) << pack.err;
  auto r = run_cli("cluster status --run-dir " + d / "r" + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto p = r.json()["per_shard"][1]["progress"];
  ASSERT_FALSE(p.contains("error")) << p.dump();
  EXPECT_EQ(p["subproblems"], pack.json()["subproblems"]);
  EXPECT_EQ(p["subproblems_done"], p["subproblems"]);  // the final checkpoint of a complete shard
  EXPECT_EQ(p["solutions"], pack.json()["solutions"]);
  EXPECT_GT(p["nodes"].get<std::uint64_t>(), 0u);
  EXPECT_EQ(r.json()["per_shard"][0]["progress"], nullptr);
}

TEST(ClusterStatus, AFifoAsAttemptsFileIsReportedNotWaitedOn) {
  TempDir d;
  std::filesystem::create_directories(d / "r/shards");
  write_text(d / "r/run.json", R"({"shards": 2, "pack_args": ["--kind","wang","--colors","2"]})");
  ASSERT_EQ(::mkfifo((d / "r/shards/shard-0.attempts").c_str(), 0600), 0);
  std::filesystem::create_symlink("/dev/urandom", d / "r/shards/shard-1.attempts");
  auto r = test::run_cli_prefixed("timeout 60 ", "cluster status --run-dir " + d / "r" + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  for (int i = 0; i < 2; ++i) {
    const auto s = r.json()["per_shard"][i];
    EXPECT_NE(s["attempts_error"].get<std::string>().find("not a regular file"), std::string::npos) << s.dump();
  }
  auto human = test::run_cli_prefixed("timeout 60 ", "cluster status --run-dir " + d / "r");
  ASSERT_EQ(human.code, 0) << human.err;
  EXPECT_NE(human.out.find("attempts unreadable"), std::string::npos) << human.out;
}

TEST(ClusterStatus, NoRunDirectoryIsNotFound) {
  TempDir d;
  EXPECT_EQ(run_cli("cluster status --run-dir " + d / "none").code, 1);
}

TEST(ClusterSubmit, MpiDryRunIsOneSrunJobInCountModeAndItsRefusalsAreExitTwo) {
  TempDir d;
  auto r = run_cli("cluster submit --mpi --nodes 2 --ntasks 4 --kind wang --colors 2 --time 10 --run-dir " + d / "run" +
                   " --dry-run --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = r.json();
  ASSERT_EQ(j["scripts"].size(), 2u);
  const std::string job = j["scripts"][d / "run/pack-mpi.sbatch"];
  for (const char* part : {"#SBATCH --nodes=2 ", "#SBATCH --ntasks=4 ", "PACK_ARGS=(--kind wang --colors 2 --mode count)",
                           "LAUNCHER=srun", "SRUN_MPI=pmix"})
    EXPECT_NE(job.find(part), std::string::npos) << part;
  EXPECT_FALSE(std::filesystem::exists(d / "run"));
  for (const std::string bad : {"--mpi --mode all", "--mpi --shards 2", "--mpi --ntasks 1 --nodes 2",
                                "--mpi --launcher ibrun", "--shards 2 --split-after -1", "--shards 2 --split-ways 1",
                                "--mpi --split-after 5", "--shards 2 --split-after 5 --mode first", ""}) {
    auto b = run_cli("cluster submit --kind wang --colors 2 " + bad + " --run-dir " + d / "run" + " --dry-run");
    EXPECT_EQ(b.code, 2) << bad << ": " << b.err;
    EXPECT_EQ(std::count(b.err.begin(), b.err.end(), '\n'), 1) << bad << ": " << b.err;
  }
}

TEST(ClusterSplit, ARunThatIsNotSplitIsExitTwoAndNoRunIsNotFound) {
  TempDir d;
  write_text(d / "run.json", R"({"shards": 2, "pack_args": ["--kind","wang","--colors","2"]})");
  auto r = run_cli("cluster split --run-dir " + d.path.string());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("not a split run"), std::string::npos) << r.err;
  EXPECT_EQ(run_cli("cluster split --run-dir " + d / "none").code, 1);
}

}  // namespace
}  // namespace tilekit
