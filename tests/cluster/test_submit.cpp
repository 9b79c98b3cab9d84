// Submitting a plan without Slurm: a fake sbatch (a shell script that logs its arguments and
// prints a job id) stands in for the real one.
#include <gtest/gtest.h>

#include <filesystem>

#include "base/error.hpp"
#include "base/json_input.hpp"
#include "cluster/job_scripts.hpp"
#include "cli/shard_words.hpp"
#include "cluster/plan.hpp"
#include "cluster/run_directory.hpp"
#include "cluster/submit.hpp"
#include "tests/cli_runner.hpp"

namespace tilekit {
namespace {
namespace fs = std::filesystem;
using test::slurp;
using test::TempDir;
using test::write_text;

bool has_text(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// An sbatch that appends its arguments to LOG and prints job ids 100, 101, ... (as "ID;cluster").
std::string fake_sbatch(const TempDir& d) {
  const std::string path = d / "sbatch", log = d / "sbatch.log", next = d / "next-id";
  write_text(next, "100");
  write_text(path, "#!/bin/bash\necho \"$*\" >>" + log + "\nid=$(cat " + next + ")\necho $((id + 1)) >" + next +
                       "\necho \"$id;cluster\"\n");
  fs::permissions(path, fs::perms::owner_all);
  return path;
}

cluster::ClusterPlan plan_in(const std::string& run_dir, int shards = 2) {
  cluster::SubmitRequest r;
  r.words = cli::pack_shard_words();
  r.kind = "corner";
  r.colors = 3;
  r.run_dir = run_dir;
  r.tilekit = TILEKIT_BINARY;
  r.settings.shards = shards;
  return cluster::make_plan(r);
}

TEST(ClusterSubmitRun, WritesTheRunDirectoryAndQueuesTheMergeAfterTheArray) {
  TempDir d;
  const cluster::ClusterPlan p = plan_in(d / "run");
  const cluster::Submission s = cluster::submit_run(p, fake_sbatch(d));
  EXPECT_EQ(s.array_job, "100");
  EXPECT_EQ(s.merge_job, "101");
  EXPECT_EQ(s.submissions, 1u);
  EXPECT_EQ(slurp(d / "sbatch.log"), "--parsable " + d / "run/pack-array.sbatch\n" +
                                         "--parsable --dependency=afterok:100 " + d / "run/merge.sbatch\n");
  for (const auto& script : cluster::job_scripts(p)) {
    EXPECT_EQ(slurp(d / "run/" + script.name), script.text);
    EXPECT_NE(fs::status(d / "run/" + script.name).permissions() & fs::perms::owner_exec, fs::perms::none);
  }
  EXPECT_TRUE(fs::is_directory(d / "run/shards"));
  EXPECT_TRUE(fs::is_directory(d / "run/logs"));
  const auto run = cluster::read_run_file(d / "run/run.json");
  ASSERT_TRUE(run);
  EXPECT_EQ(run->shards, 2);
  EXPECT_EQ(run->pack_args, p.pack_args);
  EXPECT_TRUE(run->pack);
  ASSERT_EQ(run->submissions.size(), 1u);
  EXPECT_EQ(run->submissions[0]["array_job"], "100");
  EXPECT_EQ(run->submissions[0]["merge_job"], "101");
  EXPECT_EQ(run->doc["checkpoint_every"], 300);
}

TEST(ClusterSubmitRun, TheSameRunAgainResumesItAndAnotherRunIsRefused) {
  TempDir d;
  const std::string sbatch = fake_sbatch(d);
  cluster::submit_run(plan_in(d / "run"), sbatch);
  const cluster::Submission again = cluster::submit_run(plan_in(d / "run"), sbatch);
  EXPECT_EQ(again.array_job, "102");
  EXPECT_EQ(again.submissions, 2u);
  EXPECT_EQ(cluster::read_run_file(d / "run/run.json")->submissions.size(), 2u);
  try {
    cluster::submit_run(plan_in(d / "run", 3), sbatch);
    ADD_FAILURE() << "a run of 3 shards was queued in a run directory of 2";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("different run"), std::string::npos) << e.what();
  }
  EXPECT_EQ(cluster::read_run_file(d / "run/run.json")->shards, 2);
}

TEST(ClusterSubmitRun, ADirectoryHoldingSomethingElseIsRefusedUntouched) {
  TempDir d;
  fs::create_directories(d / "run");
  write_text(d / "run/notes.txt", "mine");
  EXPECT_THROW(cluster::submit_run(plan_in(d / "run"), fake_sbatch(d)), InputError);
  EXPECT_FALSE(fs::exists(d / "run/run.json"));
  EXPECT_FALSE(fs::exists(d / "sbatch.log"));
}

TEST(ClusterSubmitRun, SbatchMissingIsNotFoundAndOneThatPrintsNoJobIdIsBadInput) {
  TempDir d;
  EXPECT_THROW(cluster::submit_run(plan_in(d / "a"), d / "no-sbatch"), NotFound);
  write_text(d / "odd", "#!/bin/sh\necho 'Submitted batch job 12'\n");
  fs::permissions(d / "odd", fs::perms::owner_all);
  EXPECT_THROW(cluster::submit_run(plan_in(d / "b"), d / "odd"), InputError);
  EXPECT_THROW(cluster::submit_run(plan_in(d / "c"), "/bin/false"), InputError);
  // A failed first submission leaves nothing: no run directory, or an empty one left empty.
  for (const char* run : {"a", "b", "c"}) EXPECT_FALSE(fs::exists(d / run)) << run;
  fs::create_directories(d / "empty");
  EXPECT_THROW(cluster::submit_run(plan_in(d / "empty"), "/bin/false"), InputError);
  EXPECT_TRUE(fs::exists(d / "empty"));
  EXPECT_TRUE(fs::is_empty(d / "empty"));
  // A resubmission of a queued run that fails keeps the run's files.
  cluster::submit_run(plan_in(d / "queued"), fake_sbatch(d));
  EXPECT_THROW(cluster::submit_run(plan_in(d / "queued"), "/bin/false"), InputError);
  EXPECT_TRUE(fs::exists(d / "queued/run.json"));
  EXPECT_TRUE(fs::exists(d / "queued/pack-array.sbatch"));
}

TEST(ClusterSubmitRun, MpiRunQueuesOneJobAndResumesOnOtherRanksButNotAsAnArray) {
  TempDir d;
  const std::string sbatch = fake_sbatch(d);
  cluster::SubmitRequest r;
  r.words = cli::pack_shard_words();
  r.kind = "wang";
  r.colors = 2;
  r.mode = "count";
  r.run_dir = d / "run";
  r.tilekit = TILEKIT_BINARY;
  r.settings.mpi = true;
  r.settings.ntasks = 4;
  const cluster::Submission s = cluster::submit_run(cluster::make_plan(r), sbatch);
  EXPECT_EQ(s.array_job, "100");
  EXPECT_EQ(s.merge_job, "");
  EXPECT_EQ(slurp(d / "sbatch.log"), "--parsable " + d / "run/pack-mpi.sbatch\n");
  EXPECT_FALSE(fs::exists(d / "run/merge.sbatch"));
  auto run = cluster::read_run_file(d / "run/run.json");
  ASSERT_TRUE(run);
  EXPECT_EQ(run->mpi_ranks, 4);
  EXPECT_EQ(run->submissions[0]["mpi_job"], "100");
  r.settings.ntasks = 1;  // the same run on another number of ranks resumes it
  EXPECT_EQ(cluster::submit_run(cluster::make_plan(r), sbatch).submissions, 2u);
  EXPECT_EQ(cluster::read_run_file(d / "run/run.json")->mpi_ranks, 1);
  EXPECT_TRUE(has_text(slurp(d / "run/pack-mpi.sbatch"), "#SBATCH --ntasks=1 "));
  r.settings.mpi = false;  // an array in an MPI run's directory: refused
  r.settings.shards = 1;
  try {
    cluster::submit_run(cluster::make_plan(r), sbatch);
    ADD_FAILURE() << "an array was queued in an MPI run's directory";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("an MPI run"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tilekit
