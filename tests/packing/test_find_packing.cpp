// find_packing (packing/find_packing.hpp) as a library call: the database first (its packing
// re-checked by the independent validator), then a construction, then the caller's search, each
// only when the one before has none, and every answer a packing the validator accepts.
#include <gtest/gtest.h>

#include "base/error.hpp"
#include "packing/find_packing.hpp"
#include "results/results_db.hpp"
#include "tests/cli_runner.hpp"
#include "tilesets/constructions.hpp"
#include "tilesets/validator.hpp"

using namespace tilekit;
using tilekit::test::TempDir;

namespace {

// Stores `t` as a solution of a run of its own.
std::int64_t store(ResultsDb& db, const Tiling& t) {
  RunRecord run;
  run.command = "test";
  run.status = "complete";
  SolutionRecord s;
  s.tiling = t;
  s.method = "test";
  s.validated = true;  // what the row claims; find_packing checks it again
  std::vector<SolutionRecord> batch{s};
  db.add_run_with_solutions(run, batch);
  return db.list_solutions({}, false).front().id;
}

}  // namespace

TEST(FindPacking, WithNoSourceThereIsNoPacking) {
  PackingSources none;
  none.construct = false;
  EXPECT_FALSE(find_packing(TileKind::Corner, 3, none).has_value());
}

TEST(FindPacking, ConstructionsAnswerForWangAndCornerAndValidate) {
  PackingSources src;
  for (auto [kind, colours] : {std::pair{TileKind::Wang, 3u}, {TileKind::Corner, 3u}, {TileKind::Corner, 6u}}) {
    auto found = find_packing(kind, colours, src);
    ASSERT_TRUE(found) << colours;
    EXPECT_EQ(found->source, "construct");
    EXPECT_FALSE(found->how.empty());
    EXPECT_EQ(found->tiling.rows, int(colours * colours));
    EXPECT_TRUE(validate(found->tiling).packing) << found->how;
  }
}

TEST(FindPacking, TheSearchRunsOnlyWhenNothingElseAnswers) {
  int searches = 0;
  PackingSources src;
  src.search = [&]() -> std::optional<FoundPacking> {
    ++searches;
    return FoundPacking{construct_packing(TileKind::Corner, 3)->tiling, "search", "test search", false, 0};
  };
  EXPECT_EQ(find_packing(TileKind::Corner, 3, src)->source, "construct");
  EXPECT_EQ(searches, 0);
  src.construct = false;
  auto found = find_packing(TileKind::Corner, 3, src);
  EXPECT_EQ(searches, 1);
  ASSERT_TRUE(found);
  EXPECT_EQ(found->source, "search");
  EXPECT_EQ(found->how, "test search");
  src.search = [&]() -> std::optional<FoundPacking> {
    ++searches;
    return std::nullopt;
  };
  EXPECT_FALSE(find_packing(TileKind::Corner, 3, src).has_value());
  EXPECT_EQ(searches, 2);
}

TEST(FindPacking, AStoredPackingAnswersFirstAndAStoredNonPackingIsPassedOver) {
  TempDir dir;
  ResultsDb db(dir / "r.sqlite");
  PackingSources src;
  src.db = &db;
  EXPECT_EQ(find_packing(TileKind::Corner, 3, src)->source, "construct");  // empty database

  // A stored 9x9 torus that is not a packing (one tile everywhere) is not an answer.
  const Tiling good = construct_packing(TileKind::Corner, 3)->tiling;
  Tiling bad = good;
  std::fill(bad.cells.begin(), bad.cells.end(), good.cells.front());
  store(db, bad);
  EXPECT_EQ(find_packing(TileKind::Corner, 3, src)->source, "construct");

  // A stored packing (here the construction's own) answers, with its row id.
  TempDir dir2;
  ResultsDb db2(dir2 / "r.sqlite");
  const std::int64_t id = store(db2, good);
  src.db = &db2;
  auto found = find_packing(TileKind::Corner, 3, src);
  ASSERT_TRUE(found);
  EXPECT_EQ(found->source, "db");
  EXPECT_EQ(found->solution_id, id);
  EXPECT_EQ(found->tiling.cells, good.cells);
  EXPECT_FALSE(find_packing(TileKind::Wang, 3, src)->source == "db");  // other kind: not stored
}

TEST(FindPacking, ColourCountsOutsideOneTo255AreInputErrors) {
  PackingSources src;
  EXPECT_THROW(find_packing(TileKind::Corner, 0, src), InputError);
  EXPECT_THROW(find_packing(TileKind::Wang, 256, src), InputError);
}
