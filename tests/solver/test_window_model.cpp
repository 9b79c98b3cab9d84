// De Bruijn tori in the engine: counts against known numbers and the corner packings, threads
// and shards, imposed groups, both lifts, and the CNF route.
#include <gtest/gtest.h>

#include "base/error.hpp"
#include "solver/sat_cnf.hpp"
#include "solver/solve.hpp"
#include "tests/build_paths.hpp"
#include "tilesets/constructions.hpp"
#include "tilesets/validator.hpp"
#include "tilesets/window_torus.hpp"

using namespace tilekit;

namespace {

SearchResult solve_window(std::uint32_t c, int k, int l, int r, int s, SearchMode mode, const std::string& extra = "",
                          const std::string& value = "", int threads = 1) {
  SearchOptions o;
  o.mode = mode;
  o.run.threads = threads;
  if (extra == "impose") o.impose = value;
  if (extra == "lift") o.lift = value;
  if (extra == "formulation") o.formulation = formulation_from_name(value).value();
  return solve(window_torus_problem(c, k, l, r, s), o);
}

std::string data(const std::string& name) { return std::string(TILEKIT_SOURCE_DIR) + "/tilesets/data/" + name; }

}  // namespace

TEST(WindowModel, CountsDeBruijnSequencesAsOneRowTori) {
  // binary order 3: 2 cyclic sequences x 8 rotations; order 2 over 3 symbols: (3!)^3 / 3^2 = 24 x 9
  EXPECT_EQ(solve_window(2, 1, 3, 1, 8, SearchMode::Count).solutions, 16u);
  EXPECT_EQ(solve_window(2, 3, 1, 8, 1, SearchMode::Count).solutions, 16u);
  EXPECT_EQ(solve_window(3, 1, 2, 1, 9, SearchMode::Count).solutions, 216u);
}

TEST(WindowModel, TwoByTwoWindowsCountLikeTheCornerPackings) {
  SearchResult w = solve_window(2, 2, 2, 4, 4, SearchMode::Count);
  EXPECT_TRUE(w.complete);
  EXPECT_EQ(w.solutions, 32u);  // the 32 corner packings of C = 2
  // A torus as tall as its window holds no de Bruijn torus (Paterson 1994: R > K unless R = K = 1).
  SearchResult flat = solve_window(2, 2, 2, 2, 8, SearchMode::Count);
  EXPECT_TRUE(flat.complete);
  EXPECT_EQ(flat.solutions, 0u);
}

TEST(WindowModel, CountsDoNotDependOnThreadsAndShardsSumToTheWhole) {
  const std::uint64_t whole = solve_window(3, 1, 2, 1, 9, SearchMode::Count, "", "", 2).solutions;
  EXPECT_EQ(whole, 216u);
  std::uint64_t sum = 0;
  for (int i = 0; i < 3; ++i) {
    SearchOptions o;
    o.mode = SearchMode::Count;
    o.run.shard = {i, 3};
    sum += solve(window_torus_problem(3, 1, 2, 1, 9), o).solutions;
  }
  EXPECT_EQ(sum, whole);
}

TEST(WindowModel, FirstModeFindsValidatedTori) {
  for (auto [c, k, l, r, s] : {std::array<int, 5>{2, 2, 3, 8, 8}, {2, 3, 2, 8, 8}, {3, 1, 2, 1, 9}}) {
    SearchResult res = solve_window(std::uint32_t(c), k, l, r, s, SearchMode::First);
    ASSERT_EQ(res.found.size(), 1u) << k << "x" << l;
    const Tiling& t = res.found.front();
    EXPECT_EQ(t.kind, TileKind::Window);
    EXPECT_EQ(t.window_rows, k);
    EXPECT_TRUE(validate(t).packing);
  }
}

TEST(WindowModel, AllModeEmitsEveryTranslateOnce) {
  SearchOptions o;
  o.mode = SearchMode::All;
  std::set<std::vector<TileIndex>> seen;
  o.on_solution = [&](const Tiling& t) { EXPECT_TRUE(seen.insert(t.cells).second); };
  EXPECT_EQ(solve(window_torus_problem(2, 1, 3, 1, 8), o).solutions, 16u);
  EXPECT_EQ(seen.size(), 16u);
}

TEST(WindowModel, ImposedGroupsKeepOnlyInvariantTori) {
  // Every binary 2x2 torus is invariant under t=(2,2) with 0 <-> 1 (as for corner packings).
  EXPECT_EQ(solve_window(2, 2, 2, 4, 4, SearchMode::Count, "impose", "t=2,2:pi=1,0").solutions, 32u);
  EXPECT_EQ(solve_window(2, 2, 2, 4, 4, SearchMode::Count, "impose", "t=0,2:pi=1,0").solutions, 0u);
  SearchResult r = solve_window(3, 2, 2, 9, 9, SearchMode::First, "impose", "t=0,3:pi=1,2,0");
  ASSERT_EQ(r.found.size(), 1u);
  EXPECT_EQ(r.group_order, 3u);
  EXPECT_THROW(solve_window(2, 2, 2, 4, 4, SearchMode::Count, "impose", "t=2,2:pi=0,1"), InputError);
}

TEST(WindowModel, RowDifferenceLiftOverTheCornerTorusGivesEightByEightTori) {
  // B(i+1,j) - B(i,j) = B2(i mod 4, j mod 4): B2's columns sum to 1, so B's columns repeat every
  // 8 rows; the search decides the 8 top symbols, and 32 of the 256 rows make (8,8;3,2) tori.
  SearchResult r = solve_window(2, 3, 2, 8, 8, SearchMode::Count, "lift", "rows=" + data("packing-corner-2.json"));
  EXPECT_TRUE(r.complete);
  EXPECT_EQ(r.solutions, 32u);
  SearchResult b = solve_window(2, 3, 3, 16, 32, SearchMode::First, "lift", "rows=" + data("window-2x3-2-16x4.json"));
  ASSERT_EQ(b.found.size(), 1u);
  EXPECT_TRUE(validate(b.found.front()).packing);
  // The base's columns must close over the torus's rows.
  EXPECT_THROW(solve_window(2, 3, 2, 4, 16, SearchMode::Count, "lift", "rows=" + data("packing-corner-2.json")),
               InputError);
}

TEST(WindowModel, ColourLiftOverTheBinaryTorusFindsAFourSymbolTorus) {
  // (16,16;2,2)_4 over the stored binary 2x2 torus (the corner packing as the base).
  SearchResult r = solve_window(4, 2, 2, 16, 16, SearchMode::First, "lift", "2");
  ASSERT_EQ(r.found.size(), 1u);
  EXPECT_TRUE(validate(r.found.front()).packing);
  EXPECT_TRUE(validate(corner_torus_of_window_torus(r.found.front())).packing);  // a C = 4 corner packing
  EXPECT_THROW(solve_window(3, 2, 2, 9, 9, SearchMode::First, "lift", "2"), InputError);  // 3 is no multiple of 2
}

TEST(WindowModel, CadicalFindsTheToriAsCnf) {
  if (!sat_solver_available()) GTEST_SKIP() << "cadical not installed";
  for (auto [c, k, l, r, s] : {std::array<int, 5>{2, 2, 2, 4, 4}, {3, 1, 2, 1, 9}}) {
    SearchResult res = solve_window(std::uint32_t(c), k, l, r, s, SearchMode::First, "formulation", "sat");
    ASSERT_EQ(res.found.size(), 1u);
    EXPECT_EQ(res.formulation, "sat");
    EXPECT_TRUE(validate(res.found.front()).packing);
  }
  SearchResult none = solve_window(2, 2, 2, 2, 8, SearchMode::First, "formulation", "sat");
  EXPECT_TRUE(none.complete);  // unsatisfiable: R = K = 2
  EXPECT_TRUE(none.found.empty());
}
