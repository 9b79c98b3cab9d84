// Resuming `tilekit pack` as a library call: run_pack stopped by its time limit after a checkpoint
// and continued from the checkpoint alone (the request comes from the file) ends with exactly the
// uninterrupted result, in counts and in the solutions stored; a field that contradicts the
// checkpoint is an InputError naming its flag.
#include <gtest/gtest.h>

#include <set>

#include "base/error.hpp"
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
  first.run.checkpoint_every = slice / 4;
  first.run.time_limit = slice;
  PackOutcome out = run_pack(quiet(first));
  int slices = 1;
  while (!out.result.complete && slices < 2000) {
    PackRequest again;  // only the file and the run's settings: kind, colours, mode, db from it
    again.run.resume_path = checkpoint;
    again.run.time_limit = slice;
    again.run.checkpoint_every = slice / 4;
    again.run.threads = 1 + slices % 2;  // the thread count may change between slices
    out = run_pack(quiet(again), {"--resume", "--time-limit", "--checkpoint-every", "--threads"});
    ++slices;
  }
  return {out, slices};
}

}  // namespace

TEST(PackResume, TimeSlicedCountFromTheCheckpointAloneIsExact) {
  TempDir dir;
  PackRequest r;
  r.kind = "wang", r.colours = 2, r.mode = "count", r.db = dir / "r.sqlite";
  auto [out, slices] = in_slices(r, 0.004, dir / "ck");
  EXPECT_TRUE(out.result.complete);
  EXPECT_EQ(out.result.solutions, 203520u);
  EXPECT_EQ(out.result.orbits, 538u);
  EXPECT_EQ(out.request.kind, "wang");  // taken from the checkpoint
  EXPECT_EQ(out.request.mode, "count");
  EXPECT_EQ(out.db_path, dir / "r.sqlite");
  EXPECT_EQ(out.checkpoint, dir / "ck");
  std::cout << "slices: " << slices << "\n";
}

TEST(PackResume, AllModeInSlicesStoresExactlyTheUninterruptedSolutions) {
  TempDir dir;
  PackRequest r;
  r.kind = "wang", r.colours = 2, r.mode = "all", r.db = dir / "sliced.sqlite";
  r.impose = "t=0,2:pi=1,0";  // 1536 packings (solver/README.md)
  auto [out, slices] = in_slices(r, 0.002, dir / "ck");
  EXPECT_TRUE(out.result.complete);
  EXPECT_EQ(out.result.solutions, 1536u);
  EXPECT_EQ(out.request.impose, r.impose);

  PackRequest whole = quiet(r);
  whole.db = dir / "whole.sqlite";
  EXPECT_EQ(run_pack(whole).stored, 1536u);
  auto hashes = [](const std::string& path) {
    std::set<std::string> h;
    SolutionFilter all;
    all.limit = 0;
    for (const SolutionRecord& s : ResultsDb(path).list_solutions(all)) h.insert(s.solution_hash);
    return h;
  };
  const std::set<std::string> sliced = hashes(dir / "sliced.sqlite");
  EXPECT_EQ(sliced.size(), 1536u);
  EXPECT_EQ(sliced, hashes(dir / "whole.sqlite"));
  std::cout << "slices: " << slices << "\n";
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
    run_pack(quiet(again), {"--resume", "--mode"});
    ADD_FAILURE() << "a contradicting --mode was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--mode is \"all\" here but \"count\" in the checkpoint"), std::string::npos)
        << e.what();
  }
  // The same value, or a flag not given, is no contradiction.
  again.mode = "count";
  EXPECT_EQ(run_pack(quiet(again), {"--resume", "--mode"}).result.solutions, 203520u);
}
