// Counting under an imposed group: the symmetric counts and solution sets for C=2 must
// equal a brute-force filter of all packings (32 corner, 203,520 Wang), enumerated here by code
// that shares nothing with the symmetric engine.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <vector>

#include "solver/impose_domain.hpp"
#include "solver/solve.hpp"
#include "tilesets/tile.hpp"
#include "tilesets/validator.hpp"

namespace tilekit {
namespace {

// All corner packings of C=2: every peg colouring of the 4x4 torus whose 16 windows differ.
const std::vector<Tiling>& all_corner_packings_c2() {
  static const std::vector<Tiling> all = [] {
    std::vector<Tiling> out;
    for (std::uint32_t bits = 0; bits < (1u << 16); ++bits) {
      auto peg = [&](int r, int c) -> Colour { return (bits >> (((r + 4) % 4) * 4 + (c + 4) % 4)) & 1u; };
      Tiling t(TileKind::Corner, 2, 4, 4, true);
      std::uint32_t seen = 0;
      bool ok = true;
      for (int r = 0; r < 4 && ok; ++r)
        for (int c = 0; c < 4 && ok; ++c) {
          TileIndex i = corner_index(CornerTile{peg(r, c + 1), peg(r + 1, c + 1), peg(r + 1, c), peg(r, c)}, 2);
          ok = !(seen >> i & 1u);
          seen |= 1u << i;
          t.at(r, c) = i;
        }
      if (ok) out.push_back(t);
    }
    return out;
  }();
  return all;
}

// All Wang packings of C=2: tile-per-cell DFS in scanline order, each of the 16 tiles once.
void wang_dfs(Tiling& t, int pos, std::uint32_t used, std::vector<Tiling>& out) {
  if (pos == 16) {
    out.push_back(t);
    return;
  }
  int r = pos / 4, c = pos % 4;
  for (TileIndex i = 0; i < 16; ++i) {
    if (used >> i & 1u) continue;
    WangTile w = wang_tile(i, 2);
    if (c > 0 && wang_tile(t.at(r, c - 1), 2).e != w.w) continue;
    if (r > 0 && wang_tile(t.at(r - 1, c), 2).s != w.n) continue;
    if (c == 3 && wang_tile(t.at(r, 0), 2).w != w.e) continue;
    if (r == 3 && wang_tile(t.at(0, c), 2).n != w.s) continue;
    t.at(r, c) = i;
    wang_dfs(t, pos + 1, used | (1u << i), out);
  }
}

const std::vector<Tiling>& all_wang_packings_c2() {
  static const std::vector<Tiling> all = [] {
    std::vector<Tiling> out;
    Tiling t(TileKind::Wang, 2, 4, 4, true);
    wang_dfs(t, 0, 0, out);
    return out;
  }();
  return all;
}

// solve() under the group `spec` (the one engine).
SearchResult solve_imposed(const TilingProblem& p, const std::string& spec, SearchOptions o) {
  o.impose = spec;
  return solve(p, o);
}

std::uint64_t count_of(TileKind kind, const std::string& spec, int threads = 1) {
  SearchOptions o;
  o.mode = SearchMode::Count;
  o.run.threads = threads;
  return solve_imposed(complete_packing_problem(kind, 2), spec, o).solutions;
}

// Count in Count mode, collect in All mode, and compare both with the brute-force filter.
void expect_matches_filter(TileKind kind, const std::string& spec, const std::vector<Tiling>& all) {
  TilingProblem p = complete_packing_problem(kind, 2);
  ImposedGroup g = build_group(p, spec);
  std::set<std::vector<TileIndex>> expected;
  for (const auto& t : all)
    if (g.is_invariant(t)) expected.insert(t.cells);

  SearchOptions count;
  count.mode = SearchMode::Count;
  auto counted = solve_imposed(p, spec, count);
  EXPECT_TRUE(counted.complete) << spec;
  EXPECT_EQ(counted.solutions, expected.size()) << spec;

  SearchOptions all_mode;
  all_mode.mode = SearchMode::All;
  std::set<std::vector<TileIndex>> got;
  all_mode.on_solution = [&](const Tiling& t) {
    EXPECT_TRUE(validate(t).packing);
    EXPECT_TRUE(g.is_invariant(t));
    got.insert(t.cells);
  };
  auto listed = solve_imposed(p, spec, all_mode);
  EXPECT_EQ(listed.solutions, expected.size()) << spec;
  EXPECT_EQ(got, expected) << spec;
}

TEST(ImposeBruteForce, EnumeratesAll32CornerAnd203520WangPackings) {
  EXPECT_EQ(all_corner_packings_c2().size(), 32u);
  EXPECT_EQ(all_wang_packings_c2().size(), 203520u);
}

TEST(ImposeCount, CornerTwoColourCountsEqualBruteForceFilterForThreeGroups) {
  std::size_t total = 0;
  for (std::string spec : {"t=0,2:pi=1,0", "t=2,0:pi=1,0", "t=2,2:pi=1,0"}) {
    expect_matches_filter(TileKind::Corner, spec, all_corner_packings_c2());
    total += count_of(TileKind::Corner, spec);
  }
  EXPECT_GT(total, 0u);  // the filter is not vacuous for every group
}

TEST(ImposeCount, WangTwoColourCountsEqualBruteForceFilterForFiveGroups) {
  std::size_t nonzero = 0;
  for (std::string spec :
       {"t=0,2:pi=1,0", "t=2,2:pih=1,0", "t=0,2:piv=1,0", "t=2,0:pih=1,0:piv=1,0", "t=0,2:pih=1,0;t=2,0:piv=1,0"}) {
    expect_matches_filter(TileKind::Wang, spec, all_wang_packings_c2());
    nonzero += count_of(TileKind::Wang, spec) > 0;
  }
  EXPECT_GE(nonzero, 3u);
}

TEST(ImposeCount, TrivialGroupCountsEveryPacking) {
  EXPECT_EQ(count_of(TileKind::Corner, "t=0,0"), 32u);
  EXPECT_EQ(count_of(TileKind::Wang, "t=0,0"), 203520u);
}

TEST(ImposeCount, CountsDoNotDependOnThreadsAndShardsSumToTheWhole) {
  // The same engine as every other model: subproblems on all threads, shards by index.
  for (std::string spec : {"t=0,2:pi=1,0", "t=0,2:piv=1,0", "t=2,2:pih=1,0"}) {
    const std::uint64_t one = count_of(TileKind::Wang, spec, 1);
    EXPECT_EQ(count_of(TileKind::Wang, spec, 2), one) << spec;
    std::uint64_t sum = 0;
    for (int i = 0; i < 3; ++i) {
      SearchOptions o;
      o.mode = SearchMode::Count;
      o.run.threads = 2;
      o.run.shard = {i, 3};
      SearchResult r = solve_imposed(complete_packing_problem(TileKind::Wang, 2), spec, o);
      EXPECT_TRUE(r.complete);
      EXPECT_GT(r.shard_subproblems, 0u);
      sum += r.solutions;
    }
    EXPECT_EQ(sum, one) << spec;
  }
}

}  // namespace
}  // namespace tilekit
