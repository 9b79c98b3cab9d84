// The packing symmetry group: canonical forms identify orbits, orbit sizes add up.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "solver/solve.hpp"
#include "solver/symmetry.hpp"
#include "tilesets/validator.hpp"

using namespace tilekit;

namespace {

std::vector<Tiling> all_packings(const TilingProblem& p) {
  std::vector<Tiling> out;
  SearchOptions o;
  o.mode = SearchMode::All;
  o.on_solution = [&](const Tiling& t) { out.push_back(t); };
  solve(p, o);
  return out;
}

}  // namespace

TEST(PackingSymmetry, GroupOrdersCountDihedralAndColourPermutations) {
  EXPECT_EQ(PackingSymmetry::for_problem(complete_packing_problem(TileKind::Corner, 2))->order(), 8u * 2);
  EXPECT_EQ(PackingSymmetry::for_problem(complete_packing_problem(TileKind::Wang, 2))->order(), 8u * 2 * 2);
  EXPECT_EQ(PackingSymmetry::for_problem(complete_packing_problem(TileKind::Corner, 3))->order(), 8u * 6);
  TilingProblem tiling = complete_packing_problem(TileKind::Corner, 2);
  tiling.packing = false;
  EXPECT_FALSE(PackingSymmetry::for_problem(tiling).has_value());
}

TEST(PackingSymmetry, AllCornerPackingsOfTwoColoursShareOneCanonicalForm) {
  auto p = complete_packing_problem(TileKind::Corner, 2);
  auto sym = PackingSymmetry::for_problem(p);
  std::set<std::vector<TileIndex>> canon;
  for (const Tiling& t : all_packings(p)) {
    std::uint64_t orbit = 0;
    Tiling c = sym->canonical(t, &orbit);
    EXPECT_TRUE(validate(c, &p.set).packing);
    EXPECT_EQ(orbit, 32u);
    canon.insert(c.cells);
  }
  EXPECT_EQ(canon.size(), 1u);
}

TEST(PackingSymmetry, WangOrbitSizesAddUpTo203520AndMatchTheOrbitCount) {
  auto p = complete_packing_problem(TileKind::Wang, 2);
  auto sym = PackingSymmetry::for_problem(p);
  std::map<std::vector<TileIndex>, std::uint64_t> orbits;
  std::uint64_t normal_forms = 0;
  for (const Tiling& t : all_packings(p)) {
    if (t.cells[0] != 0) continue;  // one translate of each: the normal forms
    ++normal_forms;
    std::uint64_t size = 0;
    Tiling c = sym->canonical(t, &size);
    auto [it, fresh] = orbits.emplace(c.cells, size);
    if (!fresh) {
      EXPECT_EQ(it->second, size);
    }
    // The image of a packing under any element has the same canonical form.
    Tiling moved = translate(t, 1, 3);
    EXPECT_EQ(sym->canonical(moved).cells, c.cells);
  }
  EXPECT_EQ(normal_forms, 203520u / 16);
  std::uint64_t total = 0;
  for (auto& [cells, size] : orbits) total += size;
  EXPECT_EQ(total, 203520u);
  SearchOptions o;
  o.mode = SearchMode::Count;
  EXPECT_EQ(*solve(p, o).orbits, orbits.size());
}
