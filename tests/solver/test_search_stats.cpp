// Engine statistics (solver/search_stats.hpp): the counters agree with the engine's own counts
// and with each other (every refused decision has exactly one pruning rule, every node but a
// subproblem's root is left by one backtrack), and a count search counts the same on 1 and 2
// threads.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <numeric>

#include "solver/solve.hpp"
#include "tilesets/tile_set_io.hpp"

using namespace tilekit;

namespace {

SearchResult count_search(const TilingProblem& p, int threads, Formulation formulation = Formulation::Auto,
                          const std::string& impose = "") {
  SearchOptions o;
  o.mode = SearchMode::Count;
  o.run.threads = threads;
  o.formulation = formulation;
  o.impose = impose;
  return solve(p, o);
}

std::uint64_t assign_prunes(const SearchStats& s) {
  std::uint64_t n = 0;
  for (std::size_t i = 0; i < kPruneRules; ++i)
    if (Prune(i) != Prune::EmptyDomain) n += s.model.prunes[i];
  return n;
}

// The relations every complete, fresh search keeps.
void expect_consistent(const SearchResult& r) {
  const SearchStats& s = r.stats;
  EXPECT_TRUE(r.complete);
  EXPECT_EQ(s.searches, 1u);
  EXPECT_EQ(s.solutions, r.solutions);
  EXPECT_EQ(s.nodes, r.nodes) << "a fresh run's statistics count the engine's nodes";
  EXPECT_GT(s.nodes, 0u);
  EXPECT_LE(s.backtracks, s.nodes);
  EXPECT_LE(s.conflicts, s.decisions);
  EXPECT_EQ(assign_prunes(s), s.conflicts) << "one rule per refused decision";
  // Every node entered by a decision is left by one backtrack once its subtree is exhausted.
  EXPECT_EQ(s.backtracks, s.decisions - s.conflicts);
  // ... and the other nodes are subproblem roots and the split's own.
  EXPECT_GE(s.nodes, s.decisions - s.conflicts + r.subproblems_done);
  EXPECT_GT(s.search_seconds, 0.0);
  EXPECT_GT(s.setup_seconds, 0.0);
}

}  // namespace

TEST(SearchStats, WangTwoColourCountIsConsistent) {
  const SearchResult r = count_search(complete_packing_problem(TileKind::Wang, 2), 1);
  ASSERT_EQ(r.solutions, 203520u);
  expect_consistent(r);
  const SearchStats& s = r.stats;
  EXPECT_EQ(s.solutions, 203520u);
  EXPECT_EQ(s.leaves * 16, 203520u);  // a leaf stands for its 16 translates
  EXPECT_EQ(s.restarts, 0u);
  EXPECT_GT(s.model.propagations, 0u);
  // The cell model prunes by forward checking; whole-torus packings have no classes.
  EXPECT_GT(s.prunes(Prune::ForwardCheck), 0u);
  EXPECT_EQ(s.prunes(Prune::ClassCheck), 0u);
  EXPECT_EQ(s.prunes(Prune::OrbitUsed), 0u);
}

TEST(SearchStats, CountsDoNotDependOnTheThreadCount) {
  const SearchResult one = count_search(complete_packing_problem(TileKind::Wang, 2), 1);
  const SearchResult two = count_search(complete_packing_problem(TileKind::Wang, 2), 2);
  expect_consistent(two);
  EXPECT_EQ(two.stats.solutions, 203520u);
  EXPECT_EQ(one.stats.nodes, two.stats.nodes);
  EXPECT_EQ(one.stats.decisions, two.stats.decisions);
  EXPECT_EQ(one.stats.conflicts, two.stats.conflicts);
  EXPECT_EQ(one.stats.backtracks, two.stats.backtracks);
  EXPECT_EQ(one.stats.leaves, two.stats.leaves);
  EXPECT_EQ(one.stats.model.propagations, two.stats.model.propagations);
  EXPECT_EQ(one.stats.model.prunes, two.stats.model.prunes);
}

TEST(SearchStats, TheEdgesFormulationPrunesUsedTiles) {
  const SearchResult r = count_search(complete_packing_problem(TileKind::Wang, 2), 2, Formulation::Edges);
  ASSERT_EQ(r.solutions, 203520u);
  expect_consistent(r);
  EXPECT_GT(r.stats.prunes(Prune::TileUsed), 0u);
  EXPECT_EQ(r.stats.prunes(Prune::NoSuchTile), 0u);  // every edge colouring of a cell is a tile of the complete set
  EXPECT_GT(r.stats.prunes(Prune::ForwardCheck), 0u);
}

TEST(SearchStats, AnImposedGroupPrunesByOrbits) {
  const SearchResult r = count_search(complete_packing_problem(TileKind::Wang, 2), 1, Formulation::Auto, "t=0,2:pi=1,0");
  ASSERT_EQ(r.solutions, 1536u);  // tests/solver/test_impose_counts.cpp
  expect_consistent(r);
  EXPECT_GT(r.stats.prunes(Prune::OrbitUsed) + r.stats.prunes(Prune::PatternCount), 0u);
  EXPECT_EQ(r.stats.prunes(Prune::ForwardCheck), 0u);  // the domain model's forward checking empties domains
}

TEST(SearchStats, ATilingOfABoundedRegionPrunesMissingTiles) {
  TilingProblem p;
  p.set = resolve_tile_set("culik-13");
  p.rows = p.cols = 4;
  p.torus = false;
  SearchOptions o;
  o.mode = SearchMode::Count;
  o.formulation = Formulation::Edges;
  o.subproblems = 64;
  o.run.threads = 1;
  const SearchResult r = solve(p, o);
  expect_consistent(r);
  EXPECT_GT(r.stats.prunes(Prune::NoSuchTile), 0u);  // most edge colourings of a cell are no tile of 13
  EXPECT_EQ(r.stats.prunes(Prune::TileUsed), 0u);    // tiles repeat in a tiling
}

TEST(SearchStats, JsonAndTableNameEveryCounter) {
  const SearchResult r = count_search(complete_packing_problem(TileKind::Corner, 2), 1);
  ASSERT_EQ(r.solutions, 32u);
  const nlohmann::json j = r.stats;
  EXPECT_EQ(j["solutions"], 32);
  EXPECT_EQ(j["nodes"], r.nodes);
  EXPECT_EQ(j["prunes"].size(), kPruneRules);
  for (const char* rule :
       {"empty-domain", "forward-check", "class-check", "no-such-tile", "tile-used", "orbit-used", "pattern-count"})
    EXPECT_TRUE(j["prunes"].contains(rule)) << rule;
  for (const char* phase : {"setup", "split", "estimate", "search", "checkpoint"})
    EXPECT_TRUE(j["seconds"].contains(phase)) << phase;
  const std::string table = stats_table(r.stats);
  EXPECT_NE(table.find("prune forward-check"), std::string::npos) << table;
  EXPECT_NE(table.find("backtracks"), std::string::npos) << table;
}

TEST(SearchStats, SumsAddEveryCounterAndTime) {
  SearchStats a, b;
  a.nodes = 3, a.decisions = 5, a.searches = 1, a.search_seconds = 1.5;
  a.model.prune(Prune::TileUsed);
  b.nodes = 4, b.backtracks = 2, b.searches = 1, b.search_seconds = 0.5, b.checkpoints = 2;
  b.model.prune(Prune::TileUsed);
  b.model.propagations = 9;
  a += b;
  EXPECT_EQ(a.nodes, 7u);
  EXPECT_EQ(a.decisions, 5u);
  EXPECT_EQ(a.backtracks, 2u);
  EXPECT_EQ(a.searches, 2u);
  EXPECT_EQ(a.checkpoints, 2u);
  EXPECT_DOUBLE_EQ(a.search_seconds, 2.0);
  EXPECT_EQ(a.prunes(Prune::TileUsed), 2u);
  EXPECT_EQ(a.model.propagations, 9u);
}
