// Colour-quotient lifts as portfolio candidates: which lifts the portfolio offers, and
// a lift candidate run by the scheduler over solve() finding a validated packing.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <unistd.h>

#include "base/error.hpp"
#include "solver/portfolio.hpp"
#include "solver/portfolio_stats.hpp"
#include "solver/sat_cnf.hpp"
#include "solver/solve.hpp"
#include "tilesets/validator.hpp"

namespace tilekit {
namespace {

bool has(const std::vector<std::string>& v, const std::string& x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}

TEST(LiftPortfolio, OffersALiftOverEveryProperDivisorWithAKnownPacking) {
  const auto eight = lift_candidates(TileKind::Corner, 8);
  EXPECT_TRUE(has(eight, "lift:4"));
  EXPECT_TRUE(has(eight, "lift:2"));
  EXPECT_FALSE(has(eight, "lift:8"));  // k = C / m must be at least 2
  EXPECT_EQ(has(eight, "lift-sat:4"), sat_solver_available());
  const auto six = lift_candidates(TileKind::Corner, 6);
  EXPECT_TRUE(has(six, "lift:3"));
  EXPECT_TRUE(has(six, "lift:2"));
  EXPECT_TRUE(lift_candidates(TileKind::Corner, 7).empty());  // a prime has no proper divisor
  // The default portfolio runs them before the plain search.
  const auto all = default_candidates(TileKind::Corner, 8);
  ASSERT_TRUE(has(all, "lift:4"));
  EXPECT_LT(std::find(all.begin(), all.end(), "lift:4") - all.begin(),
            std::find(all.begin(), all.end(), kPlainSearch) - all.begin());
}

TEST(LiftPortfolio, RejectsALiftThatDoesNotDivideTheColours) {
  const TilingProblem p = complete_packing_problem(TileKind::Corner, 7);
  EXPECT_THROW(make_candidate(p, "lift:2"), InputError);
  EXPECT_THROW(make_candidate(p, "lift-sat:3"), InputError);
  const Candidate c = make_candidate(complete_packing_problem(TileKind::Corner, 8), "lift:4");
  EXPECT_EQ(c.family, "lift");
  EXPECT_TRUE(c.resumable);
}

TEST(LiftPortfolio, TheLiftCandidateFindsAValidatedSixteenColourPacking) {
  SearchOptions o;
  o.run.threads = 2;
  o.run.time_limit = 120;
  PortfolioOptions po;
  po.stats_path = "-";
  po.candidates = {"lift:8"};
  PortfolioResult r = run_portfolio(complete_packing_problem(TileKind::Corner, 16), o, po);
  ASSERT_TRUE(r.found);
  EXPECT_EQ(r.winner, "lift:8");
  ASSERT_EQ(r.result.found.size(), 1u);
  const Tiling& a = r.result.found[0];
  EXPECT_EQ(a.rows, 256);
  EXPECT_TRUE(validate(a).packing);
}

// A portfolio slice ends with a time limit; the Luby dive it cut short must run again when the
// candidate resumes (else the natural-order dive 0, which finds lifts without backtracking, and
// every long dive would be lost at a slice's end).
TEST(LiftPortfolio, ADiveCutShortByTheTimeLimitIsRunAgainOnResume) {
  SearchOptions o;
  o.run.threads = 2;
  o.restarts = 1;
  o.restart_base = std::uint64_t(1) << 40;  // no dive ends by its node limit
  o.run.time_limit = 0.2;
  std::optional<SearchState> last;
  o.save_checkpoint = [&](const SearchState& st) { last = st; };
  SearchResult r = solve(complete_packing_problem(TileKind::Corner, 5), o);  // far from solved in 0.2 s
  ASSERT_TRUE(r.timed_out);
  ASSERT_TRUE(last.has_value());
  EXPECT_EQ(last->restarts, 0u);  // dives 0 and 1 were cut short: the resume starts at dive 0
  EXPECT_GE(r.restarts, 2u);      // both had started
}

// With two threads, cadical's candidates (which restart each slice) run in a side lane of their
// own beside the engine's candidates: lift-sat:3 finds C=6 on its own doubling schedule while the
// plain search takes the engine lane's slices, and the schedule's state says which lane ran what.
TEST(SideLane, CadicalRunsBesideTheEngineAndItsSolutionEndsTheRun) {
  if (!sat_solver_available()) GTEST_SKIP() << "cadical is not on PATH";
  SearchOptions o;
  o.run.threads = 2;
  o.run.time_limit = 300;
  PortfolioOptions po;
  po.stats_path = "-";
  po.candidates = {"plain", "lift-sat:3"};
  std::optional<PortfolioState> last;
  po.save_checkpoint = [&](const PortfolioState& s) { last = s; };
  PortfolioResult r = run_portfolio(complete_packing_problem(TileKind::Corner, 6), o, po);
  ASSERT_TRUE(r.found);
  EXPECT_EQ(r.winner, "lift-sat:3");
  ASSERT_EQ(r.result.found.size(), 1u);
  EXPECT_TRUE(validate(r.result.found[0]).packing);
  ASSERT_TRUE(last.has_value());
  EXPECT_EQ(last->side_next, 1u);  // the side lane stopped at the winner
  EXPECT_GE(last->candidates[0].slices, 1u);
  EXPECT_TRUE(last->candidates[0].engine.has_value());  // the engine lane ran the plain search
  EXPECT_FALSE(last->candidates[1].engine.has_value());
}

// The engine lane's solution cancels the cadical run in progress: with slices of 600 s neither
// lane ends by time, so the run ends only if lift:4's solution (seed 0: the natural-order dive,
// well under a second) stops the side lane's cadical on lift-sat:2. The cancelled slice teaches
// the statistics nothing.
TEST(SideLane, TheEngineLanesSolutionStopsCadicalAndTheCancelledSliceIsNotRecorded) {
  if (!sat_solver_available()) GTEST_SKIP() << "cadical is not on PATH";
  const std::string stats =
      (std::filesystem::temp_directory_path() / ("tilekit-side-lane-" + std::to_string(::getpid()) + ".json")).string();
  SearchOptions o;
  o.run.threads = 2;
  o.run.seed = 0;
  PortfolioOptions po;
  po.stats_path = stats;
  po.first_slice = 600;
  po.candidates = {"lift:4", "lift-sat:2"};
  PortfolioResult r = run_portfolio(complete_packing_problem(TileKind::Corner, 8), o, po);
  ASSERT_TRUE(r.found);
  EXPECT_EQ(r.winner, "lift:4");
  EXPECT_TRUE(validate(r.result.found[0]).packing);
  EXPECT_LT(r.seconds, 120.0);  // far below one 600 s slice: the side lane did not run to its end
  const PortfolioStats learned = PortfolioStats::load(stats);
  const auto won = learned.find(TileKind::Corner, 8, "lift:4");
  ASSERT_TRUE(won.has_value());
  EXPECT_FALSE(learned.find(TileKind::Corner, 8, "lift-sat:2").has_value());
  std::filesystem::remove(stats);
}

}  // namespace
}  // namespace tilekit
