// solve(): exact counts (32 two-colour corner packings, 203,520 Wang), validated solutions,
// tiling problems for the aperiodic engine, formulations agreeing with each other, and input
// errors.
#include <gtest/gtest.h>

#include <set>

#include "solver/solve.hpp"
#include "base/error.hpp"
#include "tilesets/tile_set_io.hpp"
#include "tilesets/validator.hpp"

using namespace tilekit;

namespace {

SearchResult run(const TilingProblem& p, SearchMode mode, int threads = 1, std::string formulation = "auto") {
  SearchOptions o;
  o.mode = mode;
  o.run.threads = threads;
  o.formulation = formulation_from_name(formulation).value();
  return solve(p, o);
}

TilingProblem tiling_problem(const std::string& set, int rows, int cols, bool torus) {
  TilingProblem p;
  p.set = resolve_tile_set(set);
  p.rows = rows, p.cols = cols, p.torus = torus;
  return p;
}

}  // namespace

TEST(CornerPacking, TwoColoursHasExactly32SolutionsInOneOrbit) {
  for (int threads : {1, 2}) {
    SearchResult r = run(complete_packing_problem(TileKind::Corner, 2), SearchMode::Count, threads);
    EXPECT_TRUE(r.complete);
    EXPECT_EQ(r.solutions, 32u) << threads << " threads";
    ASSERT_TRUE(r.orbits.has_value());
    EXPECT_EQ(*r.orbits, 1u);
  }
}

TEST(WangPacking, TwoColoursHasExactly203520Solutions) {
  for (int threads : {1, 2}) {
    SearchResult r = run(complete_packing_problem(TileKind::Wang, 2), SearchMode::Count, threads);
    EXPECT_TRUE(r.complete);
    EXPECT_EQ(r.solutions, 203520u) << threads << " threads";
    ASSERT_TRUE(r.orbits.has_value());
    EXPECT_GT(*r.orbits, 1u);
    EXPECT_LT(*r.orbits, 203520u / 16);
  }
}

TEST(Formulations, PegsEdgesAndCellsGiveTheSameCounts) {
  auto corner = complete_packing_problem(TileKind::Corner, 2);
  EXPECT_EQ(run(corner, SearchMode::Count, 1, "pegs").solutions, 32u);
  EXPECT_EQ(run(corner, SearchMode::Count, 1, "cell").solutions, 32u);
  auto wang = complete_packing_problem(TileKind::Wang, 2);
  SearchResult e = run(wang, SearchMode::Count, 2, "edges");
  EXPECT_EQ(e.solutions, 203520u);
  EXPECT_EQ(e.orbits, run(wang, SearchMode::Count, 1, "cell").orbits);
  SearchOptions mrv;
  mrv.mode = SearchMode::Count;
  mrv.ordering = "mrv";
  EXPECT_EQ(solve(wang, mrv).solutions, 203520u);
}

TEST(AllMode, StoresEveryCornerPackingOnceAndEachValidates) {
  for (int threads : {1, 2}) {
    auto p = complete_packing_problem(TileKind::Corner, 2);
    std::set<std::vector<TileIndex>> seen;
    std::size_t calls = 0;
    SearchOptions o;
    o.mode = SearchMode::All;
    o.run.threads = threads;
    o.on_solution = [&](const Tiling& t) {
      ++calls;
      EXPECT_TRUE(validate(t, &p.set).packing);
      seen.insert(t.cells);
    };
    SearchResult r = solve(p, o);
    EXPECT_EQ(r.solutions, 32u);
    EXPECT_EQ(calls, 32u);
    EXPECT_EQ(seen.size(), 32u);
  }
}

TEST(AllMode, StoresAll203520WangPackingsDistinct) {
  auto p = complete_packing_problem(TileKind::Wang, 2);
  std::set<std::vector<TileIndex>> seen;
  SearchOptions o;
  o.mode = SearchMode::All;
  o.run.threads = 2;
  o.on_solution = [&](const Tiling& t) { seen.insert(t.cells); };
  SearchResult r = solve(p, o);
  EXPECT_EQ(r.solutions, 203520u);
  EXPECT_EQ(seen.size(), 203520u);
}

TEST(FirstMode, ThreeColourPackingsValidate) {
  for (TileKind k : {TileKind::Corner, TileKind::Wang})
    for (int threads : {1, 2}) {
      auto p = complete_packing_problem(k, 3);
      SearchResult r = run(p, SearchMode::First, threads);
      ASSERT_EQ(r.found.size(), 1u) << kind_name(k);
      ValidationReport rep = validate(r.found[0], &p.set);
      EXPECT_TRUE(rep.packing) << kind_name(k) << ": " << (rep.errors.empty() ? "" : rep.errors[0]);
      EXPECT_EQ(r.solutions, 1u);
      EXPECT_FALSE(r.complete);
    }
}

TEST(Tilings, CountsOfCompleteSetsOnSmallGridsAreColourChoices) {
  // Complete sets: every colouring of the pegs (corner) or edges (Wang) is a tiling.
  EXPECT_EQ(run(tiling_problem("complete-corner-2", 2, 2, true), SearchMode::Count).solutions, 16u);     // 2^4 pegs
  EXPECT_EQ(run(tiling_problem("complete-corner-2", 2, 2, false), SearchMode::Count).solutions, 512u);   // 2^9 pegs
  EXPECT_EQ(run(tiling_problem("complete-wang-2", 2, 3, true), SearchMode::Count, 2).solutions, 4096u);  // 2^12 edges
  EXPECT_EQ(run(tiling_problem("complete-wang-2", 2, 3, true), SearchMode::Count, 1, "edges").solutions, 4096u);
  EXPECT_EQ(run(tiling_problem("complete-corner-2", 1, 3, true), SearchMode::Count, 1, "pegs").solutions,
            8u);  // 1 row: 2^3
  EXPECT_EQ(run(tiling_problem("complete-corner-2", 1, 3, true), SearchMode::Count).solutions, 8u);
}

TEST(Tilings, AperiodicSetHasNoTorusTilingButTilesASquare) {
  for (int threads : {1, 2}) {
    SearchResult torus = run(tiling_problem("culik-13", 3, 4, true), SearchMode::First, threads);
    EXPECT_TRUE(torus.complete);
    EXPECT_TRUE(torus.found.empty());
    auto sq = tiling_problem("culik-13", 8, 8, false);
    SearchResult r = run(sq, SearchMode::First, threads);
    ASSERT_EQ(r.found.size(), 1u);
    EXPECT_TRUE(validate(r.found[0], &sq.set).valid);
    EXPECT_FALSE(r.found[0].torus);
  }
}

TEST(Tilings, PeriodicTilingOfARepeatingSetIsFoundAndValid) {
  auto p = tiling_problem("complete-corner-3", 3, 5, true);
  SearchResult r = run(p, SearchMode::First, 2);
  ASSERT_EQ(r.found.size(), 1u);
  EXPECT_TRUE(validate(r.found[0], &p.set).valid);
}

TEST(SolveErrors, ImpossibleProblemsAndOptionsThrowInputError) {
  auto p = complete_packing_problem(TileKind::Corner, 2);
  SearchOptions o;
  o.run.threads = 0;
  EXPECT_THROW(solve(p, o), InputError);
  o.run.threads = 1;
  o.run.shard = {4, 4};
  EXPECT_THROW(solve(p, o), InputError);
  o.run.shard = {0, 1};
  o.formulation = Formulation::Edges;
  EXPECT_THROW(solve(p, o), InputError);
  o.formulation = Formulation::Auto;
  p.rows = 2;
  EXPECT_THROW(solve(p, o), InputError);
  EXPECT_THROW(complete_packing_problem(TileKind::Wang, 0), InputError);
}

// The formulation is an enum with one word each (the CLI parses the word); solve() picks the
// model from its table of routes and names the route in the result.
TEST(Formulations, EachWordNamesOneFormulationAndTheRouteIsReported) {
  for (Formulation f : {Formulation::Auto, Formulation::Cell, Formulation::Pegs, Formulation::Edges, Formulation::Sat})
    EXPECT_EQ(formulation_from_name(formulation_name(f)), f) << formulation_name(f);
  EXPECT_FALSE(formulation_from_name("cellz").has_value());
  EXPECT_FALSE(formulation_from_name("").has_value());
  const TilingProblem corner = complete_packing_problem(TileKind::Corner, 2);
  EXPECT_EQ(run(corner, SearchMode::Count, 1, "auto").formulation, "cell");  // the measured default
  EXPECT_EQ(run(corner, SearchMode::Count, 1, "pegs").formulation, "pegs");
  const TilingProblem wang = complete_packing_problem(TileKind::Wang, 2);
  EXPECT_EQ(run(wang, SearchMode::First, 1, "edges").formulation, "edges");
  // No route: pegs for Wang tiles, sat without a subspace that has a CNF.
  SearchOptions o;
  o.run.threads = 1;
  o.formulation = Formulation::Pegs;
  EXPECT_THROW(solve(wang, o), InputError);
  o.formulation = Formulation::Sat;
  try {
    solve(corner, o);
    ADD_FAILURE() << "sat without a group or a lift was accepted";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.field(), "formulation");
  }
}
