// The imposed-group portfolio (issue 7): candidate groups, first-found-wins on 2 threads, and
// statistics that persist and order the next run.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "../cli_runner.hpp"
#include "solver/impose_portfolio.hpp"
#include "base/error.hpp"
#include "tilesets/validator.hpp"

namespace tilekit {
namespace {

TEST(ImposePortfolio, CandidateGroupsAreValidAndIncludeTheKnownWinners) {
  auto corner = candidate_groups(TileKind::Corner, 4);
  auto wang = candidate_groups(TileKind::Wang, 4);
  EXPECT_NE(std::find(corner.begin(), corner.end(), "t=0,4:pi=1,2,3,0"), corner.end());
  EXPECT_NE(std::find(wang.begin(), wang.end(), "t=0,8:pi=1,0,3,2"), wang.end());
  // Products of two generators: the Klein four-group on 4 colours.
  EXPECT_NE(std::find(corner.begin(), corner.end(), "t=0,8:pi=1,0,3,2;t=8,0:pi=2,3,0,1"), corner.end());
  for (const auto& spec : corner) EXPECT_NO_THROW(build_group(complete_packing_problem(TileKind::Corner, 4), spec)) << spec;
  for (const auto& spec : wang) EXPECT_NO_THROW(build_group(complete_packing_problem(TileKind::Wang, 4), spec)) << spec;
  // Odd C: only C-cycles (a fixed-point-free permutation of order k needs k | C).
  for (const auto& spec : candidate_groups(TileKind::Corner, 5)) EXPECT_NE(spec.find("pi=1,2,3,4,0"), std::string::npos);
}

void expect_portfolio_finds(TileKind kind, const std::string& stats) {
  SearchOptions o;
  o.threads = 2;
  o.seed = 1;
  o.time_limit = 120;
  PortfolioOptions p;
  p.stats_path = stats;
  PortfolioResult r = run_portfolio(kind, 4, o, p);
  ASSERT_TRUE(r.found);
  ASSERT_EQ(r.result.found.size(), 1u);
  ValidationReport rep = validate(r.result.found[0]);
  EXPECT_TRUE(rep.packing);
  if (r.spec != kPlainSearch) {
    EXPECT_EQ(r.group["spec"], r.spec);
    EXPECT_TRUE(build_group(complete_packing_problem(kind, 4), r.spec).is_invariant(r.result.found[0]));
  }
}

TEST(ImposePortfolio, FindsFourColourCornerAndWangPackingsOnTwoThreads) {
  test::TempDir dir;
  expect_portfolio_finds(TileKind::Corner, dir / "stats.json");
  expect_portfolio_finds(TileKind::Wang, dir / "stats.json");
  PortfolioStats s = PortfolioStats::load(dir / "stats.json");
  auto rows = s.report()["groups"];
  ASSERT_FALSE(rows.empty());
  int successes = 0;
  for (const auto& row : rows) successes += row["successes"].get<int>();
  EXPECT_GE(successes, 2);
}

TEST(ImposePortfolio, EmptySubspacesAreDroppedAndAnEmptyPortfolioEndsAtOnce) {
  // No C=2 corner packing is invariant under t=(0,2) or t=(2,0) with the colours swapped (the
  // brute-force filter in test_impose_counts.cpp); all 32 are invariant under t=(2,2).
  SearchOptions o;
  o.threads = 2;
  o.time_limit = 30;
  PortfolioOptions p;
  p.stats_path = "-";
  p.specs = {"t=0,2:pi=1,0", "t=2,0:pi=1,0"};
  PortfolioResult none = run_portfolio(TileKind::Corner, 2, o, p);
  EXPECT_FALSE(none.found);
  EXPECT_LT(none.seconds, 5.0);
  p.specs.push_back("t=2,2:pi=1,0");
  PortfolioResult some = run_portfolio(TileKind::Corner, 2, o, p);
  ASSERT_TRUE(some.found);
  EXPECT_EQ(some.spec, "t=2,2:pi=1,0");
  EXPECT_TRUE(validate(some.result.found[0]).packing);
}

TEST(ImposePortfolio, StatisticsOrderProvenGroupsFirstAndFailuresLast) {
  PortfolioStats s;
  std::vector<std::string> specs = {"a", "b", "c", "d"};
  s.record(TileKind::Corner, 4, "a", false, 1.0);
  s.record(TileKind::Corner, 4, "c", true, 2.0);
  s.record(TileKind::Corner, 4, "d", true, 0.5);
  s.record(TileKind::Wang, 4, "b", true, 0.1);  // another problem: does not count
  EXPECT_EQ(s.order(TileKind::Corner, 4, specs), (std::vector<std::string>{"d", "c", "b", "a"}));
  EXPECT_EQ(s.find(TileKind::Corner, 4, "c")->median_seconds(), 2.0);
}

TEST(ImposePortfolio, StatisticsSurviveSaveAndLoadAndCorruptFileIsInputError) {
  test::TempDir dir;
  PortfolioStats s;
  s.record(TileKind::Corner, 5, "t=0,5:pi=1,2,3,4,0", true, 3.0);
  s.record(TileKind::Corner, 5, "t=0,5:pi=1,2,3,4,0", false, 9.0);
  s.save(dir / "s.json");
  auto g = PortfolioStats::load(dir / "s.json").find(TileKind::Corner, 5, "t=0,5:pi=1,2,3,4,0");
  ASSERT_TRUE(g.has_value());
  EXPECT_EQ(g->tries, 2u);
  EXPECT_EQ(g->successes, 1u);
  test::write_text(dir / "bad.json", "{not json");
  EXPECT_THROW(PortfolioStats::load(dir / "bad.json"), InputError);
  EXPECT_FALSE(PortfolioStats::load(dir / "missing.json").find(TileKind::Corner, 5, "x").has_value());
}

}  // namespace
}  // namespace tilekit
