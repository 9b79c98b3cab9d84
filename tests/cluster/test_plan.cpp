// The plan of a cluster run: what make_plan() makes of a request, and what it refuses before
// anything is written (exit 2 in the CLI), e.g. a checkpoint interval of inf or 1e308. A refusal
// names the request field at fault between backquotes; the CLI words it as the flag.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "base/error.hpp"
#include "base/parse.hpp"
#include "cli/shard_words.hpp"
#include "cluster/plan.hpp"
#include "cluster/slurm_time.hpp"
#include "tests/build_paths.hpp"
#include "tests/cli_runner.hpp"

namespace tilekit {
namespace {
namespace fs = std::filesystem;
using test::TempDir;
using test::write_text;

cluster::SubmitRequest wang2(const std::string& run_dir) {
  cluster::SubmitRequest r;
  r.words = cli::pack_shard_words();
  r.kind = "wang";
  r.colors = 2;
  r.run_dir = run_dir;
  r.tilekit = TILEKIT_BINARY;
  return r;
}

std::string refusal(const cluster::SubmitRequest& r) {
  try {
    cluster::make_plan(r);
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(ClusterSlurmTime, ParsesEverySbatchFormat) {
  EXPECT_EQ(cluster::parse_slurm_time("90"), 90 * 60);
  EXPECT_EQ(cluster::parse_slurm_time("1:30"), 90);
  EXPECT_EQ(cluster::parse_slurm_time("2:00:05"), 7205);
  EXPECT_EQ(cluster::parse_slurm_time("2-12"), 2 * 86400 + 12 * 3600);
  EXPECT_EQ(cluster::parse_slurm_time("1-0:30"), 86400 + 1800);
  EXPECT_EQ(cluster::parse_slurm_time("1-00:00:07"), 86407);
  EXPECT_EQ(cluster::parse_slurm_time("999999999-0"), 999999999L * 86400);
  for (const char* bad :
       {"", "x", "0", "1:2:3:4", "-5", "UNLIMITED", "1-", "1h", "99999999999999999999", "1-99999999999999999999"})
    EXPECT_THROW(cluster::parse_slurm_time(bad), InputError) << bad;
}

TEST(ClusterSlurmTime, SignalLeadIsTwoMinutesAtMostHalfTheLimit) {
  EXPECT_EQ(cluster::default_signal_seconds(3600), 120);
  EXPECT_EQ(cluster::default_signal_seconds(60), 30);
  EXPECT_EQ(cluster::default_signal_seconds(1), 1);
}

TEST(ClusterPlan, PackRunGetsItsArgumentsNameDirectoryAndDefaults) {
  TempDir d;
  cluster::SubmitRequest r = wang2(d / "run/");
  r.mode = "count";
  r.method = "search";
  r.seed = "7";
  r.shard_args = {"--max-depth=3"};
  r.settings.shards = 4;
  r.settings.time = "2:00:00";
  const cluster::ClusterPlan p = cluster::make_plan(r);
  EXPECT_EQ(p.command, std::vector<std::string>{"pack"});
  EXPECT_EQ(p.pack_args, (std::vector<std::string>{"--kind", "wang", "--colors", "2", "--method", "search", "--mode",
                                                   "count", "--seed", "7", "--max-depth=3"}));
  EXPECT_EQ(p.run_dir, d / "run");  // absolute, no trailing slash
  EXPECT_EQ(p.job_name, "tk-wang2");
  EXPECT_EQ(p.merge_time, "2:00:00");
  EXPECT_EQ(p.signal_seconds, 120);
  EXPECT_EQ(p.shards, 4);
  EXPECT_EQ(p.tilekit, fs::absolute(TILEKIT_BINARY).string());
}

TEST(ClusterPlan, DefaultRunDirectoryIsNamedAfterTheRunInTheWorkingDirectory) {
  cluster::SubmitRequest r = wang2("");
  r.mode = "first";
  EXPECT_EQ(cluster::make_plan(r).run_dir, (fs::current_path() / "tilekit-run-wang2-first").string());
  cluster::SubmitRequest e;
  e.command = "enumerate";
  e.tilekit = TILEKIT_BINARY;
  const cluster::ClusterPlan p = cluster::make_plan(e);
  EXPECT_EQ(p.run_dir, (fs::current_path() / "tilekit-run-enumerate").string());
  EXPECT_EQ(p.command, (std::vector<std::string>{"aperiodic", "enumerate"}));
  EXPECT_TRUE(p.pack_args.empty());
  EXPECT_EQ(p.job_name, "tk-enumerate");
}

TEST(ClusterPlan, SignalLeadAndMergeTimeFollowTheWallTimeUnlessGiven) {
  TempDir d;
  cluster::SubmitRequest r = wang2(d / "r");
  r.settings.time = "1";
  EXPECT_EQ(cluster::make_plan(r).signal_seconds, 30);
  r.signal_seconds = 10;
  r.merge_time = "5:00";
  const cluster::ClusterPlan p = cluster::make_plan(r);
  EXPECT_EQ(p.signal_seconds, 10);
  EXPECT_EQ(p.merge_time, "5:00");
}

TEST(ClusterPlan, RefusesACheckpointIntervalThatIsNotAPositiveFiniteNumberOfSecondsUpToAYear) {
  TempDir d;
  cluster::SubmitRequest r = wang2(d / "r");
  for (double bad :
       {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
        std::numeric_limits<double>::quiet_NaN(), 1e308, cluster::kMaxCheckpointSeconds * 1.0001, 0.0, -1.0}) {
    r.settings.checkpoint_every = bad;
    EXPECT_NE(refusal(r).find("`checkpoint_every`"), std::string::npos) << bad;
  }
  for (double good : {0.25, 300.0, cluster::kMaxCheckpointSeconds}) {
    r.settings.checkpoint_every = good;
    EXPECT_EQ(refusal(r), "accepted") << good;
  }
  EXPECT_FALSE(fs::exists(d / "r"));  // planning writes nothing
}

TEST(ClusterPlan, RefusesEveryValueTheScriptsCouldNotRunWith) {
  TempDir d;
  const cluster::SubmitRequest ok = wang2(d / "r");
  ASSERT_EQ(refusal(ok), "accepted");
  std::vector<std::pair<std::string, std::function<void(cluster::SubmitRequest&)>>> cases = {
      {"`shards`", [](auto& r) { r.settings.shards = 0; }},
      {"`shards`", [](auto& r) { r.settings.shards = int(kMaxShards) + 1; }},
      {"`cpus_per_task`", [](auto& r) { r.settings.cpus_per_task = 0; }},
      {"`max_requeues`", [](auto& r) { r.settings.max_requeues = -1; }},
      {"`time`", [](auto& r) { r.settings.time = "soon"; }},
      {"`time`", [](auto& r) { r.settings.time = "99999999999999999999"; }},
      {"`merge_time`", [](auto& r) { r.merge_time = "0"; }},
      {"`signal_seconds`", [](auto& r) { r.settings.time = "1", r.signal_seconds = 60; }},
      {"`run_dir`", [&](auto& r) { r.run_dir = d / "a b"; }},
      {"`partition`", [](auto& r) { r.settings.partition = "long%x"; }},
      {"`job_name`", [](auto& r) { r.job_name = "it's"; }},
      {"`sbatch_args`", [](auto& r) { r.settings.sbatch_args = {"account=x"}; }},
      {"`sbatch_args`", [](auto& r) { r.settings.sbatch_args = {"--account=x --qos=y"}; }},
      {"`shard_args` --db=x.sqlite", [](auto& r) { r.shard_args = {"--db=x.sqlite"}; }},
      {"`shard_args` --shard", [](auto& r) { r.shard_args = {"--shard"}; }},
      {"`shard_args`", [](auto& r) { r.shard_args.assign(cluster::kMaxShardArgs, "--quiet"); }},
      {"`shard_args`", [](auto& r) { r.shard_args = {"--x=" + std::string(cluster::kMaxShardArgBytes, 'y')}; }},
      {"`kind`", [](auto& r) { r.kind = "hex"; }},
      {"`kind` window", [](auto& r) { r.kind = "window"; }},
      {"`colors`", [](auto& r) { r.colors = 0; }},
      {"`command`", [](auto& r) { r.command = "solve"; }},
      {"`command` enumerate", [](auto& r) { r.command = "enumerate"; }},  // with --kind and --colors
      {"`tilekit`", [&](auto& r) { r.tilekit = d / "none"; }},
  };
  for (auto& [what, change] : cases) {
    cluster::SubmitRequest r = ok;
    change(r);
    EXPECT_NE(refusal(r).find(what), std::string::npos) << what << ": " << refusal(r);
  }
  EXPECT_FALSE(fs::exists(d / "r"));
}

TEST(ClusterPlan, JobsRunTheTilekitOnPathElseThisOne) {
  TempDir d;
  fs::create_directories(d / "bin");
  fs::create_directories(d / "plain/tilekit");  // a directory named tilekit is no binary
  fs::create_directories(d / "noexec");
  write_text(d / "bin/tilekit", "#!/bin/sh\n");
  write_text(d / "noexec/tilekit", "#!/bin/sh\n");
  fs::permissions(d / "bin/tilekit", fs::perms::owner_all);
  const std::string self = fs::canonical(TILEKIT_BINARY).string();
  const std::string installed = fs::canonical(d / "bin/tilekit").string();
  cluster::SubmitRequest r = wang2(d / "r");
  r.tilekit.clear();
  EXPECT_EQ(cluster::make_plan(r, {d / "plain:" + d / "noexec:" + d / "bin", TILEKIT_BINARY}).tilekit, installed);
  EXPECT_EQ(cluster::make_plan(r, {d / "plain::" + d / "noexec", TILEKIT_BINARY}).tilekit, self);
  EXPECT_EQ(cluster::make_plan(r, {"", TILEKIT_BINARY}).tilekit, self);
}

TEST(ClusterPlan, MpiRunIsOneCountJobOfRanksAndRefusesWhatPackMpiCannotRun) {
  TempDir d;
  cluster::SubmitRequest r = wang2(d / "r");
  r.mode = "count";
  r.settings.mpi = true;
  r.settings.nodes = 2;
  cluster::ClusterPlan p = cluster::make_plan(r);
  EXPECT_EQ(p.ntasks, 2);  // default: one rank per node
  EXPECT_EQ(p.shards, 1);
  EXPECT_EQ(p.launcher, "srun");
  EXPECT_EQ(p.srun_mpi, "pmix");
  EXPECT_EQ(p.pack_args, (std::vector<std::string>{"--kind", "wang", "--colors", "2", "--mode", "count"}));
  const cluster::SubmitRequest ok = r;
  std::vector<std::pair<std::string, std::function<void(cluster::SubmitRequest&)>>> cases = {
      {"`mode` all", [](auto& r) { r.mode = "all"; }},
      {"`shards` must be 1", [](auto& r) { r.settings.shards = 4; }},
      {"`nodes`", [](auto& r) { r.settings.nodes = 0; }},
      {"`ntasks`", [](auto& r) { r.settings.ntasks = 1; }},  // fewer ranks than nodes
      {"`launcher`", [](auto& r) { r.settings.launcher = "ibrun"; }},
      {"`srun_mpi`", [](auto& r) { r.settings.srun_mpi = "pmix --x"; }},
      {"`srun_mpi`", [](auto& r) { r.settings.srun_mpi = ""; }},
      {"`shard_args` --mpi", [](auto& r) { r.shard_args = {"--mpi"}; }},
      {"`command` enumerate has no MPI run",
       [](auto& r) { r.command = "enumerate", r.kind = "", r.colors = 0, r.mode = "all"; }},
  };
  for (auto& [what, change] : cases) {
    cluster::SubmitRequest bad = ok;
    change(bad);
    EXPECT_NE(refusal(bad).find(what), std::string::npos) << what << ": " << refusal(bad);
  }
}

}  // namespace
}  // namespace tilekit
