// The portfolio: candidate groups, a scheduler over solve() on 2 threads that
// is resumable from its state, and statistics that persist, merge and order the next run.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <optional>

#include "../cli_runner.hpp"
#include "base/error.hpp"
#include "solver/impose_domain.hpp"
#include "solver/portfolio.hpp"
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
  for (const auto& spec : corner)
    EXPECT_NO_THROW(build_group(complete_packing_problem(TileKind::Corner, 4), spec)) << spec;
  for (const auto& spec : wang) EXPECT_NO_THROW(build_group(complete_packing_problem(TileKind::Wang, 4), spec)) << spec;
  // Odd C: only C-cycles (a fixed-point-free permutation of order k needs k | C).
  for (const auto& spec : candidate_groups(TileKind::Corner, 5))
    EXPECT_NE(spec.find("pi=1,2,3,4,0"), std::string::npos);
}

void expect_portfolio_finds(TileKind kind, const std::string& stats) {
  SearchOptions o;
  o.run.threads = 2;
  o.run.seed = 1;
  o.run.time_limit = 120;
  PortfolioOptions p;
  p.stats_path = stats;
  PortfolioResult r = run_portfolio(complete_packing_problem(kind, 4), o, p);
  ASSERT_TRUE(r.found);
  ASSERT_EQ(r.result.found.size(), 1u);
  ValidationReport rep = validate(r.result.found[0]);
  EXPECT_TRUE(rep.packing);
  if (r.winner != kPlainSearch && r.winner.rfind("lift", 0) != 0) {  // a group won
    EXPECT_EQ(r.result.group, r.winner);
    EXPECT_TRUE(build_group(complete_packing_problem(kind, 4), r.winner).is_invariant(r.result.found[0]));
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
  o.run.threads = 2;
  o.run.time_limit = 30;
  PortfolioOptions p;
  p.stats_path = "-";
  p.candidates = {"t=0,2:pi=1,0", "t=2,0:pi=1,0"};
  const TilingProblem c2 = complete_packing_problem(TileKind::Corner, 2);
  PortfolioResult none = run_portfolio(c2, o, p);
  EXPECT_FALSE(none.found);
  EXPECT_TRUE(none.complete);  // both subspaces exhausted
  EXPECT_LT(none.seconds, 5.0);
  p.candidates.push_back("t=2,2:pi=1,0");
  PortfolioResult some = run_portfolio(c2, o, p);
  ASSERT_TRUE(some.found);
  EXPECT_EQ(some.winner, "t=2,2:pi=1,0");
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

namespace tilekit {
namespace {

TEST(PortfolioCandidates, NamesMapToFamiliesAndBadNamesAreInputErrors) {
  TilingProblem p = complete_packing_problem(TileKind::Corner, 4);
  EXPECT_EQ(make_candidate(p, "plain").family, "plain");
  Candidate g = make_candidate(p, "t=0,4:pi=(0 1 2 3)");
  EXPECT_EQ(g.family, "impose");
  EXPECT_EQ(g.group, "t=0,4:pi=1,2,3,0");  // canonical spec
  EXPECT_EQ(make_candidate(p, "impose:t=0,4:pi=1,2,3,0").group, g.group);
  Candidate sat = make_candidate(p, "sat:t=0,4:pi=1,2,3,0");
  EXPECT_EQ(sat.family, "sat");
  EXPECT_FALSE(sat.resumable);
  EXPECT_THROW(make_candidate(p, "nonsense"), InputError);
  EXPECT_THROW(make_candidate(p, "impose:t=0,4:pi=1,0,3,2"), InputError);  // orders differ
}

// Runs the portfolio for at most `seconds`, keeping its state in `state`.
PortfolioResult portfolio_slice(const TilingProblem& p, const std::vector<std::string>& cands, double seconds,
                                std::optional<PortfolioState>& state, std::uint64_t seed = 3, int threads = 2) {
  SearchOptions o;
  o.run.threads = threads;
  o.run.seed = seed;
  o.run.time_limit = seconds;
  PortfolioOptions po;
  po.stats_path = "-";
  po.candidates = cands;
  po.first_slice = 0.05;
  po.resume_state = state;
  po.save_checkpoint = [&](const PortfolioState& s) { state = s; };
  return run_portfolio(p, o, po);
}

TEST(PortfolioResume, StateCarriesEmptySubspacesBudgetsAndEngineStatesAcrossRuns) {
  // C=5 corner: the group and the plain search take far longer than these short runs.
  const TilingProblem p = complete_packing_problem(TileKind::Corner, 5);
  const std::vector<std::string> cands = {"t=0,5:pi=1,2,3,4,0", "plain"};
  std::optional<PortfolioState> state;
  PortfolioResult a = portfolio_slice(p, cands, 0.3, state);
  ASSERT_TRUE(state.has_value());
  if (a.found) GTEST_SKIP() << "found a C=5 packing within 0.3 s (lucky seed)";
  EXPECT_TRUE(a.timed_out);
  ASSERT_EQ(state->candidates.size(), 2u);
  double budget = 0;
  std::uint64_t nodes = 0;
  for (const auto& c : state->candidates) {
    budget += c.seconds;
    nodes += c.nodes;
    if (c.slices) {
      EXPECT_TRUE(c.engine.has_value()) << c.name;  // its own engine checkpoint
    }
  }
  EXPECT_GT(nodes, 0u);
  EXPECT_GT(budget, 0.0);  // each candidate's budget used is carried
  const double before = state->seconds;
  PortfolioResult b = portfolio_slice(p, cands, 0.3, state);
  if (b.found) GTEST_SKIP() << "found a C=5 packing (lucky seed)";
  EXPECT_GT(state->seconds, before);  // the budget goes on from the first run
  std::uint64_t nodes2 = 0;
  for (const auto& c : state->candidates) nodes2 += c.nodes;
  EXPECT_GT(nodes2, nodes);
  // Another portfolio's state is refused.
  std::optional<PortfolioState> other = state;
  EXPECT_THROW(portfolio_slice(p, {"plain"}, 0.1, other), InputError);
  EXPECT_THROW(portfolio_slice(p, cands, 0.1, other, 4), InputError);  // another seed
}

TEST(PortfolioResume, EmptyCandidatesAreReDerivedOnResume) {
  const TilingProblem c2 = complete_packing_problem(TileKind::Corner, 2);
  std::optional<PortfolioState> state;
  PortfolioResult r = portfolio_slice(c2, {"t=0,2:pi=1,0", "t=2,0:pi=1,0"}, 10, state, 3, 1);  // one thread: same dives
  EXPECT_FALSE(r.found);
  EXPECT_TRUE(r.complete);
  ASSERT_TRUE(state.has_value());
  std::vector<std::uint64_t> nodes;
  for (const auto& c : state->candidates) {
    EXPECT_TRUE(c.empty) << c.name;
    nodes.push_back(c.nodes);
  }
  // Each candidate resumes its engine state and runs the dive that exhausted it again. The
  // engine reports a resumed state's nodes cumulatively; the portfolio adds only the new ones,
  // at most one more exhaustive dive's worth (counted twice, the total would exceed that).
  PortfolioResult again = portfolio_slice(c2, {"t=0,2:pi=1,0", "t=2,0:pi=1,0"}, 10, state, 3, 1);
  EXPECT_TRUE(again.complete);
  EXPECT_FALSE(again.found);
  for (std::size_t i = 0; i < state->candidates.size(); ++i) {
    EXPECT_TRUE(state->candidates[i].empty) << state->candidates[i].name;
    EXPECT_GT(state->candidates[i].nodes, nodes[i]) << state->candidates[i].name;
    EXPECT_LE(state->candidates[i].nodes, 2 * nodes[i]) << state->candidates[i].name;
  }
}

// A checkpoint that lies about emptiness (every candidate marked exhausted, for a problem with
// packings) does not resume to "no packing exists": the candidates run again and find one.
TEST(PortfolioResume, CandidatesMarkedEmptyWithoutProofRunAgain) {
  const TilingProblem c3 = complete_packing_problem(TileKind::Corner, 3);
  const std::vector<std::string> cands = {"plain"};
  std::optional<PortfolioState> state;
  portfolio_slice(c3, cands, 0.001, state);
  ASSERT_TRUE(state.has_value());
  for (auto& c : state->candidates) c.empty = true;
  PortfolioResult r = portfolio_slice(c3, cands, 30, state);
  EXPECT_FALSE(r.complete);
  ASSERT_TRUE(r.found);
  EXPECT_TRUE(validate(r.result.found[0]).packing);
}

// The schedule's candidates must be those its fingerprint names.
TEST(PortfolioResume, ACandidateListThatDiffersFromTheFingerprintIsRefused) {
  const TilingProblem c3 = complete_packing_problem(TileKind::Corner, 3);
  const std::vector<std::string> cands = {"plain", "t=0,3:pi=1,2,0"};
  std::optional<PortfolioState> state;
  portfolio_slice(c3, cands, 0.001, state);
  ASSERT_TRUE(state.has_value());
  ASSERT_EQ(state->candidates.size(), 2u);
  std::optional<PortfolioState> dropped = state;
  dropped->candidates.pop_back();
  EXPECT_THROW(portfolio_slice(c3, cands, 1, dropped), InputError);
  std::optional<PortfolioState> renamed = state;
  renamed->candidates[1].name = "t=3,0:pi=1,2,0";
  EXPECT_THROW(portfolio_slice(c3, cands, 1, renamed), InputError);
}

TEST(PortfolioShards, ShardsSplitTheDivesAndEachFindsAValidPacking) {
  // Two shards of one portfolio: each runs its share of every candidate's dives (different
  // seeds per dive), and each answer validates.
  for (int shard = 0; shard < 2; ++shard) {
    SearchOptions o;
    o.run.threads = 2;
    o.run.seed = 1;
    o.run.time_limit = 60;
    o.run.shard = {shard, 2};
    PortfolioOptions po;
    po.stats_path = "-";
    PortfolioResult r = run_portfolio(complete_packing_problem(TileKind::Wang, 4), o, po);
    ASSERT_TRUE(r.found) << shard;
    EXPECT_TRUE(validate(r.result.found[0]).packing);
  }
}

TEST(PortfolioStatsMerge, MergedFilesAddUpTriesAndSuccesses) {
  test::TempDir dir;
  PortfolioStats a, b;
  a.record(TileKind::Corner, 5, "t=0,5:pi=1,2,3,4,0", true, 3.0);
  b.record(TileKind::Corner, 5, "t=0,5:pi=1,2,3,4,0", false, 1.0);
  b.record(TileKind::Corner, 5, "plain", false, 1.0);
  a.save(dir / "a.json");
  b.save(dir / "b.json");
  PortfolioStats sum = PortfolioStats::load(dir / "a.json");
  sum.merge(PortfolioStats::load(dir / "b.json"));
  auto g = sum.find(TileKind::Corner, 5, "t=0,5:pi=1,2,3,4,0");
  ASSERT_TRUE(g.has_value());
  EXPECT_EQ(g->tries, 2u);
  EXPECT_EQ(g->successes, 1u);
  EXPECT_EQ(sum.find(TileKind::Corner, 5, "plain")->tries, 1u);
  test::write_text(dir / "badkey.json",
                   R"({"version":1,"groups":{"nonsense":{"tries":1,"successes":0,"success_seconds":[]}}})");
  EXPECT_THROW(PortfolioStats::load(dir / "badkey.json"), InputError);
}

}  // namespace
}  // namespace tilekit
