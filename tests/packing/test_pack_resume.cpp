// Resuming `tilekit pack` as a library call: run_pack stopped by its time limit after a checkpoint
// and continued from the checkpoint alone (the request comes from the file) ends with exactly the
// uninterrupted result, in counts and in the solutions stored; a field that contradicts the
// checkpoint is an InputError naming its flag.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <set>

#include "base/error.hpp"
#include "base/parse.hpp"
#include "base/signals.hpp"
#include "packing/pack.hpp"
#include "results/results_db.hpp"
#include "tests/cli_runner.hpp"

using namespace tilekit;
using tilekit::test::TempDir;

namespace {

PackRequest quiet(PackRequest r) {
  r.run.progress = false;
  r.run.catch_signals = false;
  return r;
}

// Runs `first` in slices of `slice` seconds, each later slice from the checkpoint alone, until
// the search completes; returns the last outcome and the number of slices.
std::pair<PackOutcome, int> in_slices(PackRequest first, double slice, const std::string& checkpoint) {
  first.run.checkpoint_path = checkpoint;
  first.checkpoint_every = slice / 4;
  first.run.time_limit = slice;
  PackOutcome out = run_pack(quiet(first));
  int slices = 1;
  while (!out.result.complete && slices < 2000) {
    PackRequest again;  // only the file and the run's settings: kind, colours, mode, db from it
    again.run.resume_path = checkpoint;
    again.run.time_limit = slice;
    again.checkpoint_every = slice / 4;
    again.run.threads = 1 + slices % 2;  // the thread count may change between slices
    out = run_pack(quiet(again), {PackField::TimeLimit});
    ++slices;
  }
  return {out, slices};
}

// A subspace whose count takes about 0.1 CPU s: several 20 ms slices on any machine (each slice
// searches at least 20 ms, however long its resume and first checkpoint took: kLeastSearchSlice).
PackRequest c3_group(const TempDir& dir, const std::string& mode, const std::string& shard) {
  PackRequest r;
  r.kind = "wang", r.colours = 3, r.mode = mode, r.db = dir / (mode + ".sqlite");
  r.impose = "t=0,3:pi=1,2,0;t=3,0:piv=1,2,0";  // order 9: 2,755,620 packings in all
  r.run.shard = parse_shard(shard);
  return r;
}

std::set<std::string> stored_hashes(const std::string& path) {
  std::set<std::string> h;
  SolutionFilter all;
  all.limit = 0;
  for (const SolutionRecord& s : ResultsDb(path).list_solutions(all)) h.insert(s.solution_hash);
  return h;
}

}  // namespace

TEST(PackResume, TimeSlicedCountFromTheCheckpointAloneIsExact) {
  TempDir dir;
  const PackOutcome whole = run_pack(quiet(c3_group(dir, "count", "3/8")));
  ASSERT_TRUE(whole.result.complete);
  EXPECT_EQ(whole.result.solutions, 342720u);
  auto [out, slices] = in_slices(c3_group(dir, "count", "3/8"), 0.02, dir / "ck");
  EXPECT_GT(slices, 1);
  EXPECT_TRUE(out.result.complete);
  EXPECT_EQ(out.result.solutions, whole.result.solutions);
  EXPECT_EQ(out.request.kind, "wang");  // taken from the checkpoint
  EXPECT_EQ(out.request.mode, "count");
  EXPECT_EQ(out.request.impose, "t=0,3:pi=1,2,0;t=3,0:piv=1,2,0");
  EXPECT_EQ(shard_text(out.request.run.shard), "3/8");
  EXPECT_EQ(out.db_path, dir / "count.sqlite");
  EXPECT_EQ(out.checkpoint, dir / "ck");
  RecordProperty("slices", slices);
}

TEST(PackResume, AllModeInSlicesStoresExactlyTheUninterruptedSolutions) {
  TempDir sliced_dir, whole_dir;
  const PackOutcome whole = run_pack(quiet(c3_group(whole_dir, "all", "3/512")));
  ASSERT_TRUE(whole.result.complete);
  ASSERT_GT(whole.stored, 0u);
  auto [out, slices] = in_slices(c3_group(sliced_dir, "all", "3/512"), 0.02, sliced_dir / "ck");
  EXPECT_GT(slices, 1);
  EXPECT_TRUE(out.result.complete);
  EXPECT_EQ(out.result.solutions, whole.result.solutions);
  const std::set<std::string> sliced = stored_hashes(sliced_dir / "all.sqlite");
  EXPECT_EQ(sliced.size(), whole.stored);
  EXPECT_EQ(sliced, stored_hashes(whole_dir / "all.sqlite"));
  RecordProperty("slices", slices);
}

TEST(PackResume, AFieldThatContradictsTheCheckpointIsAnInputErrorNamingItsFlag) {
  TempDir dir;
  PackRequest r;
  r.kind = "wang", r.colours = 2, r.mode = "count", r.db = dir / "r.sqlite";
  r.run.checkpoint_path = dir / "ck";
  ASSERT_TRUE(run_pack(quiet(r)).result.complete);
  PackRequest again;
  again.run.resume_path = dir / "ck";
  again.mode = "all";
  try {
    run_pack(quiet(again), {PackField::Mode});
    ADD_FAILURE() << "a contradicting --mode was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("`mode` is \"all\" here but \"count\" in the checkpoint"), std::string::npos)
        << e.what();
  }
  // The same value, or a flag not given, is no contradiction.
  again.mode = "count";
  EXPECT_EQ(run_pack(quiet(again), {PackField::Mode}).result.solutions, 203520u);
}

// A signal that comes before the search has begun (Slurm's requeue right after the task starts)
// still leaves a checkpoint, and resuming from it gives the whole count: the subproblem split is
// never cut short, so there is always a list to checkpoint.
TEST(PackResume, ASignalBeforeTheSearchBeginsStillLeavesACheckpointToResumeFrom) {
  TempDir dir;
  PackRequest r = c3_group(dir, "count", "3/8");
  r.run.checkpoint_path = dir / "ck";
  r.run.progress = false;
  PackOutcome stopped;
  {
    SignalCatcher outer;  // run_pack's own catcher joins this one, so the flag stays set
    ASSERT_EQ(std::raise(SIGTERM), 0);
    ASSERT_EQ(SignalCatcher::caught(), SIGTERM);
    stopped = run_pack(r);
  }
  EXPECT_TRUE(stopped.interrupted);  // (its workers may still have finished before they saw the flag)
  ASSERT_TRUE(std::filesystem::exists(dir / "ck")) << "no checkpoint after a signal before the search";
  PackRequest again;
  again.run.resume_path = dir / "ck";
  const PackOutcome resumed = run_pack(quiet(again), {});
  EXPECT_TRUE(resumed.result.complete);
  EXPECT_EQ(resumed.result.solutions, 342720u);  // the uninterrupted count of this shard (above)
}
