// run_pack (packing/pack.hpp) as a library call, without the binary: exact counts, which source
// answers a first-mode request under each --method, what is stored, and bad requests refused
// before the database is touched.
#include <gtest/gtest.h>

#include <filesystem>

#include "base/error.hpp"
#include "packing/pack.hpp"
#include "results/results_db.hpp"
#include "tests/cli_runner.hpp"
#include "tilesets/validator.hpp"

using namespace tilekit;
using tilekit::test::TempDir;

namespace {

// A request that stays inside `dir`: its own database and portfolio statistics, no progress
// output, no signal handlers.
PackRequest request(const TempDir& dir, const std::string& kind, std::int64_t colours, const std::string& mode) {
  PackRequest r;
  r.kind = kind;
  r.colours = colours;
  r.mode = mode;
  r.db = dir / "r.sqlite";
  r.portfolio_stats = dir / "stats.json";
  r.run.progress = false;
  r.run.catch_signals = false;
  return r;
}

std::uint64_t stored_solutions(const std::string& db) { return ResultsDb(db).stats().solutions; }

}  // namespace

TEST(RunPack, CountsTheTwoColourPackingsExactly) {
  TempDir dir;
  for (auto [kind, solutions, orbits] : {std::tuple{"corner", 32u, 1u}, {"wang", 203520u, 538u}}) {
    PackOutcome out = run_pack(request(dir, kind, 2, "count"));
    EXPECT_EQ(out.method, "search");
    EXPECT_TRUE(out.result.complete) << kind;
    EXPECT_EQ(out.result.solutions, solutions) << kind;
    EXPECT_EQ(out.result.orbits, orbits) << kind;
    EXPECT_EQ(out.stored, 0u);  // a count stores its run, not its solutions
  }
  ResultsDb db(dir / "r.sqlite");
  EXPECT_EQ(db.stats().runs, 2u);
  EXPECT_EQ(db.stats().solutions, 0u);
  EXPECT_EQ(db.list_runs().front().status, "complete");
}

TEST(RunPack, AutoAnswersByConstructionThenFromTheDatabase) {
  TempDir dir;
  PackOutcome first = run_pack(request(dir, "corner", 3, "first"));
  EXPECT_EQ(first.method, "construct");
  EXPECT_FALSE(first.construction.empty());
  ASSERT_EQ(first.result.found.size(), 1u);
  EXPECT_TRUE(validate(first.result.found[0]).packing);
  EXPECT_EQ(first.stored, 1u);
  EXPECT_TRUE(first.orbit_size.has_value());

  PackOutcome second = run_pack(request(dir, "corner", 3, "first"));
  EXPECT_EQ(second.method, "db");
  EXPECT_EQ(second.stored, 0u);
  ASSERT_EQ(second.result.found.size(), 1u);
  EXPECT_EQ(second.result.found[0].cells, first.result.found[0].cells);
  EXPECT_EQ(stored_solutions(dir / "r.sqlite"), 1u);
}

TEST(RunPack, MethodSearchNeverConstructsAndItsPackingValidates) {
  TempDir dir;
  PackRequest r = request(dir, "corner", 3, "first");
  r.method = "search";
  r.run.threads = 2;
  PackOutcome out = run_pack(r);
  EXPECT_EQ(out.method, "search");
  ASSERT_EQ(out.result.found.size(), 1u);
  EXPECT_TRUE(validate(out.result.found[0]).packing);
  EXPECT_TRUE(out.portfolio.is_object());  // a first-mode search of a complete set: the portfolio
  EXPECT_EQ(out.stored, 1u);
  EXPECT_TRUE(out.not_found.empty());
  EXPECT_TRUE(std::filesystem::exists(dir / "stats.json"));
}

TEST(RunPack, AllModeUnderAGroupStoresEverySolutionOnceWithItsGroup) {
  TempDir dir;
  PackRequest r = request(dir, "wang", 2, "all");
  r.impose = "t=0,2:pih=1,0;t=2,0:piv=1,0";  // 64 packings of the 203,520 (solver/README.md)
  PackOutcome out = run_pack(r);
  EXPECT_TRUE(out.result.complete);
  EXPECT_EQ(out.result.solutions, 64u);
  EXPECT_EQ(out.stored, 64u);
  EXPECT_EQ(out.group["spec"], r.impose);
  PackOutcome again = run_pack(r);
  EXPECT_EQ(again.result.solutions, 64u);
  EXPECT_EQ(again.stored, 0u);  // unique by hash
  ResultsDb db(dir / "r.sqlite");
  EXPECT_EQ(db.stats().solutions, 64u);
  for (const SolutionRecord& s : db.list_solutions({}, true)) {
    EXPECT_TRUE(s.validated);
    EXPECT_TRUE(validate(s.tiling).packing);
    EXPECT_EQ(s.group["spec"], r.impose);
  }
}

TEST(RunPack, AnExhaustedSubspaceIsNotFoundWithTheReason) {
  TempDir dir;
  PackRequest r = request(dir, "corner", 2, "first");
  r.impose = "t=0,2:pi=1,0";  // no two-colour corner packing is invariant under it
  PackOutcome out = run_pack(r);
  EXPECT_TRUE(out.result.found.empty());
  EXPECT_TRUE(out.result.complete);
  EXPECT_NE(out.not_found.find("invariant under the imposed group"), std::string::npos) << out.not_found;
}

TEST(RunPack, BadRequestsAreInputErrorsAndTouchNoDatabase) {
  TempDir dir;
  auto refused = [&](PackRequest r, const std::string& words) {
    try {
      run_pack(r);
      ADD_FAILURE() << "accepted; wanted: " << words;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "r.sqlite")) << words;
  };
  PackRequest r = request(dir, "corner", 3, "first");
  PackRequest bad = r;
  bad.mode = "some";
  refused(bad, "unknown mode 'some'");
  bad = r, bad.kind = "hex";
  refused(bad, "unknown tile kind 'hex'");
  bad = r, bad.method = "construct", bad.mode = "count";
  refused(bad, "`method` construct gives one packing");
  bad = r, bad.impose = "t=0,9:pi=1,2,0", bad.plain = true;
  refused(bad, "`impose` and `plain` exclude each other");
  bad = r, bad.impose = "t=banana";
  refused(bad, "t=banana");
  bad = r, bad.kind.clear(), bad.set = "complete-corner-2", bad.size = "3x5";
  refused(bad, "needs rows*cols = 16");
  bad = r, bad.checkpoint_every = -5;
  refused(bad, "`checkpoint_every` must be >= 0");
}
