// Imposed automorphism groups: spec parsing, the rules a packing group must obey, and
// first solutions that pass the independent validator and are invariant under the group.
#include <gtest/gtest.h>

#include <string>

#include "base/error.hpp"
#include "solver/impose_domain.hpp"
#include "solver/impose_model.hpp"
#include "solver/impose_sat.hpp"
#include "solver/solve.hpp"
#include "tilesets/validator.hpp"

namespace tilekit {
namespace {

// solve() under the group `spec` (the one engine).
SearchResult solve_under(const TilingProblem& p, const std::string& spec, SearchOptions o) {
  o.impose = spec;
  return solve(p, o);
}
SearchResult solve_under(TileKind kind, std::uint32_t c, const std::string& spec, const SearchOptions& o) {
  return solve_under(complete_packing_problem(kind, c), spec, o);
}

std::string input_error(TileKind kind, std::uint32_t c, const std::string& spec) {
  try {
    TilingProblem p = complete_packing_problem(kind, c);
    build_group(p, spec);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ImposeSpec, ParsesSeveralGeneratorsListAndCycleNotation) {
  GroupSpec s = parse_group_spec("t=0,8:pi=1,0,3,2; t=8,0:pi=(0 2)(1,3)");
  ASSERT_EQ(s.generators.size(), 2u);
  EXPECT_EQ(s.generators[0].dc, 8);
  EXPECT_EQ(s.generators[1].dr, 8);
  EXPECT_EQ(s.generators[1].pi.resolve(4, "pi"), (std::vector<Colour>{2, 3, 0, 1}));
  TilingProblem p = complete_packing_problem(TileKind::Corner, 4);
  ImposedGroup g = build_group(p, "t=0,8:pi=1,0,3,2;t=8,0:pi=(0 2)(1,3)");
  EXPECT_EQ(g.order(), 4u);  // Klein four-group: (0,8), (8,0), (8,8) and the identity
  EXPECT_EQ(g.spec_text(), "t=0,8:pi=1,0,3,2;t=8,0:pi=2,3,0,1");
  EXPECT_EQ(g.to_json()["order"], 4);
}

TEST(ImposeSpec, MalformedSpecsAreInputErrors) {
  for (std::string bad : {"", "t=0", "t=0,4", "x=1", "t=0,4:pi=1,2,3", "t=0,4:pi=1,1,2,3", "t=0,4:pi=1,2,3,9",
                          "t=a,4:pi=1,2,3,0", "t=0,4:pi=(0 1", "t=0,4:pi=1,2,3,0:pih=1,2,3,0"}) {
    EXPECT_NE(input_error(TileKind::Corner, 4, bad), "") << "accepted: '" << bad << "'";
  }
}

TEST(ImposeGroupRules, TranslationOrderMustMatchPermutationOrder) {
  std::string msg = input_error(TileKind::Corner, 4, "t=0,4:pi=1,0,3,2");
  EXPECT_NE(msg.find("order 4"), std::string::npos) << msg;
  EXPECT_NE(msg.find("order 2"), std::string::npos) << msg;
}

TEST(ImposeGroupRules, PermutationWithFixedPointIsRejectedForCornerPackings) {
  std::string msg = input_error(TileKind::Corner, 4, "t=0,8:pi=1,0,2,3");
  EXPECT_NE(msg.find("fixes colour 2"), std::string::npos) << msg;
}

TEST(ImposeGroupRules, ProductReachingIdentityPermutationIsRejected) {
  // (0,2) and (2,0) each swap the colours, so their product (2,2) fixes every tile.
  std::string msg = input_error(TileKind::Corner, 2, "t=0,2:pi=1,0;t=2,0:pi=1,0");
  EXPECT_NE(msg.find("group element t=2,2"), std::string::npos) << msg;
}

TEST(ImposeGroupRules, WangNeedsOneFixedPointFreeDirection) {
  EXPECT_EQ(input_error(TileKind::Wang, 4, "t=0,8:pih=1,0,3,2"), "");  // vertical identity is fine
  std::string msg = input_error(TileKind::Wang, 4, "t=0,8:pih=1,0,2,3:piv=0,1,3,2");
  EXPECT_NE(msg.find("its own image"), std::string::npos) << msg;
  EXPECT_NE(input_error(TileKind::Corner, 4, "t=0,8:pih=1,0,3,2"), "");  // pih is Wang-only
}

TEST(ImposeGroupRules, InconsistentGeneratorsAreRejected) {
  std::string msg = input_error(TileKind::Corner, 4, "t=0,8:pi=1,0,3,2;t=0,8:pi=2,3,0,1");
  EXPECT_NE(msg.find("inconsistent"), std::string::npos) << msg;
}

void expect_symmetric_packing(TileKind kind, std::uint32_t c, const std::string& spec, int threads) {
  SearchOptions o;
  o.run.threads = threads;
  o.run.seed = 7;
  o.run.time_limit = 60;
  TilingProblem p = complete_packing_problem(kind, c);
  ImposedGroup g = build_group(p, spec);
  SearchResult r = solve_under(p, spec, o);
  ASSERT_EQ(r.found.size(), 1u) << spec;
  const Tiling& t = r.found[0];
  ValidationReport rep = validate(t);
  EXPECT_TRUE(rep.valid);
  EXPECT_TRUE(rep.packing);
  EXPECT_TRUE(g.is_invariant(t));
  // The invariance check can fail: swapping two cells breaks it.
  Tiling broken = t;
  std::swap(broken.at(0, 0), broken.at(1, 1));
  EXPECT_FALSE(g.is_invariant(broken));
  EXPECT_EQ(r.group, g.spec_text());
  EXPECT_EQ(r.group_order, g.order());
}

TEST(ImposeFirst, CornerPackingsUnderCyclicGroupsValidateAndAreInvariant) {
  expect_symmetric_packing(TileKind::Corner, 3, "t=0,3:pi=1,2,0", 1);
  expect_symmetric_packing(TileKind::Corner, 4, "t=0,4:pi=1,2,3,0", 2);
  expect_symmetric_packing(TileKind::Corner, 4, "t=4,0:pi=(0 3 2 1)", 2);
}

TEST(ImposeFirst, WangPackingsUnderImposedGroupsValidateAndAreInvariant) {
  expect_symmetric_packing(TileKind::Wang, 3, "t=0,3:pi=1,2,0", 1);
  expect_symmetric_packing(TileKind::Wang, 4, "t=0,4:pi=1,2,3,0", 2);
  expect_symmetric_packing(TileKind::Wang, 4, "t=0,4:pih=1,2,3,0;t=4,0:piv=1,2,3,0", 2);
}

TEST(ImposeFirst, SameSeedAndOneThreadGiveTheSameSolution) {
  SearchOptions o;
  o.run.seed = 3;
  auto a = solve_under(TileKind::Corner, 4, "t=0,4:pi=1,2,3,0", o);
  auto b = solve_under(TileKind::Corner, 4, "t=0,4:pi=1,2,3,0", o);
  ASSERT_EQ(a.found.size(), 1u);
  ASSERT_EQ(b.found.size(), 1u);
  EXPECT_EQ(a.found[0].cells, b.found[0].cells);
}

TEST(ImposeFirst, EmptySubspaceIsReportedCompleteWithoutSolution) {
  // A first-mode run agrees with Count: it finds a solution exactly when one exists, and when
  // none does it exhausts the subspace and says `complete`.
  SearchOptions count;
  count.mode = SearchMode::Count;
  for (std::string spec : {"t=0,2:pi=1,0", "t=2,2:pi=1,0"}) {
    auto n = solve_under(TileKind::Corner, 2, spec, count).solutions;
    SearchOptions first;
    auto r = solve_under(TileKind::Corner, 2, spec, first);
    EXPECT_EQ(r.solutions, n > 0 ? 1u : 0u) << spec;
    if (n == 0) {
      EXPECT_TRUE(r.complete) << spec;
    }
  }
}

TEST(ImposeTiling, PeriodicTilingOfASetWithRepeatsAllowed) {
  // Tiling mode (tiles may repeat): a 2-colour corner tiling of a 2x4 torus invariant under a
  // column shift by 2 that swaps the colours.
  TilingProblem p;
  p.set = complete_corner_set(2);
  p.rows = 2;
  p.cols = 4;
  p.torus = true;
  p.packing = false;
  ImposedGroup g = build_group(p, "t=0,2:pi=1,0");
  SearchOptions o;
  auto r = solve_under(p, "t=0,2:pi=1,0", o);
  ASSERT_EQ(r.found.size(), 1u);
  EXPECT_TRUE(validate(r.found[0]).valid);
  EXPECT_TRUE(g.is_invariant(r.found[0]));
  SearchOptions count;
  count.mode = SearchMode::Count;
  // 2x4 pegs, a fundamental domain of 2x2 free pegs: 16 tilings, every colouring allowed.
  EXPECT_EQ(solve_under(p, "t=0,2:pi=1,0", count).solutions, 16u);
}

}  // namespace
}  // namespace tilekit

namespace tilekit {
namespace {

TEST(ImposeSat, CadicalSolvesTheSameSubspaceAndTheResultValidates) {
  if (!sat_solver_available()) GTEST_SKIP() << "cadical not installed (scripts/setup.sh installs it)";
  for (auto [kind, spec] :
       {std::pair{TileKind::Corner, "t=0,3:pi=1,2,0"}, std::pair{TileKind::Wang, "t=0,3:pi=1,2,0"}}) {
    TilingProblem p = complete_packing_problem(kind, 3);
    ImposedGroup g = build_group(p, spec);
    SearchOptions o;
    o.run.time_limit = 60;
    o.formulation = Formulation::Sat;
    auto r = solve_under(p, spec, o);
    ASSERT_EQ(r.found.size(), 1u) << spec;
    EXPECT_TRUE(validate(r.found[0]).packing);
    EXPECT_TRUE(g.is_invariant(r.found[0]));
    EXPECT_EQ(r.formulation.rfind("sat-", 0), 0u);
  }
  // An empty subspace is proved empty: C=2 corner groups whose brute-force count is 0.
  for (std::string spec : {"t=0,2:pi=1,0", "t=2,2:pi=1,0"}) {
    SearchOptions count;
    count.mode = SearchMode::Count;
    if (solve_under(TileKind::Corner, 2, spec, count).solutions != 0) continue;
    SearchOptions sat;
    sat.formulation = Formulation::Sat;
    auto r = solve_under(TileKind::Corner, 2, spec, sat);
    EXPECT_TRUE(r.complete) << spec;
    EXPECT_TRUE(r.found.empty()) << spec;
  }
}

}  // namespace
}  // namespace tilekit

namespace tilekit {
namespace {

TEST(ImposeModelState, IncrementalStateEqualsARecomputationAlongRandomDives) {
  // Random dives with backtracking through the model's own branching: after every assign and
  // unassign the incremental counts (tight sites, used orbits, pattern demand/avail, per-cell
  // colour caches) equal a recomputation from the site values.
  for (auto [kind, c, spec] :
       {std::tuple{TileKind::Corner, 3u, "t=0,3:pi=1,2,0"}, std::tuple{TileKind::Wang, 3u, "t=0,3:pih=1,2,0"},
        std::tuple{TileKind::Corner, 4u, "t=0,8:pi=1,0,3,2;t=8,0:pi=2,3,0,1"}}) {
    TilingProblem p = complete_packing_problem(kind, c);
    ImposeModel m(FundamentalDomain::build(p, build_group(p, spec)), ImposeModel::Ordering::MostConstrained);
    ASSERT_TRUE(m.check_state());
    SplitMix64 rng(11);
    std::vector<std::pair<int, int>> path;
    std::vector<int> values;
    int checks = 0;
    for (int step = 0; step < 400; ++step) {
      int var = m.branch(values);
      if (var >= 0 && !values.empty() && rng.below(4) != 0) {
        int v = values[rng.below(values.size())];
        if (m.assign(var, v))
          path.push_back({var, v});
        else
          m.unassign(var, v);  // a failed assign undid itself: unassign is a no-op
      } else if (!path.empty()) {
        m.unassign(path.back().first, path.back().second);
        path.pop_back();
      }
      ASSERT_TRUE(m.check_state()) << spec << " at step " << step;
      ++checks;
    }
    EXPECT_EQ(checks, 400);
    while (!path.empty()) {
      m.unassign(path.back().first, path.back().second);
      path.pop_back();
    }
    EXPECT_TRUE(m.check_state());
  }
}

}  // namespace
}  // namespace tilekit
