// Colour merges of corner sets (aperiodic/colour_merge.hpp): the recovery map puts back every
// merged colour on random patches (round trip), and merges that lose information are refused.
#include <gtest/gtest.h>

#include <map>
#include <optional>
#include <random>
#include <vector>

#include "aperiodic/colour_merge.hpp"
#include "aperiodic/steps.hpp"
#include "tilesets/tile_set_io.hpp"

using namespace tilekit;

namespace {

using Pegs = std::vector<std::vector<Colour>>;

// A random rows x cols grid of pegs whose every 2x2 window is a tile (randomised row-major
// backtracking; test fixture only).
std::optional<Pegs> random_corner_patch(const std::vector<CornerTile>& tiles, int rows, int cols, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Colour> colours;
  for (const CornerTile& t : tiles) colours.insert(colours.end(), {t.nw, t.ne, t.sw, t.se});
  std::sort(colours.begin(), colours.end());
  colours.erase(std::unique(colours.begin(), colours.end()), colours.end());
  auto is_tile = [&](Colour nw, Colour ne, Colour sw, Colour se) {
    return std::binary_search(tiles.begin(), tiles.end(), CornerTile{ne, se, sw, nw});
  };
  Pegs p(static_cast<std::size_t>(rows), std::vector<Colour>(static_cast<std::size_t>(cols)));
  std::size_t nodes = 0;
  auto place = [&](auto& self, int i) -> bool {
    if (i == rows * cols) return true;
    if (++nodes > 2'000'000) return false;
    const std::size_t r = std::size_t(i / cols), c = std::size_t(i % cols);
    std::vector<Colour> order = colours;
    std::shuffle(order.begin(), order.end(), rng);
    for (Colour v : order) {
      p[r][c] = v;
      if (r > 0 && c > 0 && !is_tile(p[r - 1][c - 1], p[r - 1][c], p[r][c - 1], v)) continue;
      if (self(self, i + 1)) return true;
    }
    return false;
  };
  if (!place(place, 0)) return std::nullopt;
  return p;
}

std::vector<CornerTile> sorted(std::vector<CornerTile> t) {
  std::sort(t.begin(), t.end());
  return t;
}

std::vector<CornerTile> jeandel_rao_corner() {
  TileSet s = resolve_tile_set("jeandel-rao-11-variant-2");
  for (const char* step : {"rotation", "prune"}) s = apply_step(s, step)->set;
  return sorted(s.corner_tiles());
}

}  // namespace

TEST(ColourMerge, RecoveryMapPutsEveryMergedColourBack) {
  const std::vector<CornerTile> source = jeandel_rao_corner();
  ASSERT_EQ(source.size(), 34u);
  const MergeSearch m = least_colour_merge(source, false, 1, 0, 8);
  ASSERT_FALSE(m.merges.empty());
  EXPECT_TRUE(m.conjugate);
  EXPECT_LT(m.tiles.size(), source.size());
  // Replay the merges one at a time; each round trip pi then phi gives back a random patch of the
  // set before the merge (all but its border of radius + margin pegs).
  std::vector<CornerTile> before = source;
  int patches = 0;
  for (const ColourMerge& x : m.merges) {
    bool conjugate = false;
    const auto after = merge_colours(before, x.kept, x.merged, false, x.radius, x.margin, &conjugate);
    ASSERT_TRUE(after.has_value());
    EXPECT_TRUE(conjugate);
    // The merge's own check, and the same radius with a margin of 1 where that check passes too.
    for (int margin : {x.margin, 1}) {
      if (margin != x.margin && !merge_colours(before, x.kept, x.merged, false, x.radius, margin)) continue;
      const std::size_t r = std::size_t(x.radius + margin);
      for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        const auto patch = random_corner_patch(before, 3 + 2 * int(r), 3 + 2 * int(r), seed);
        if (!patch) continue;
        ++patches;
        Pegs image = *patch;
        for (auto& row : image)
          for (Colour& c : row)
            if (c == x.merged) c = x.kept;
        const Pegs back = recover_pegs(before, x.kept, x.merged, x.radius, margin, image);
        ASSERT_EQ(back.size(), patch->size() - 2 * r);
        for (std::size_t i = 0; i < back.size(); ++i)
          for (std::size_t j = 0; j < back[i].size(); ++j)
            ASSERT_EQ(back[i][j], (*patch)[i + r][j + r]) << x.kept << "+" << x.merged << " m=" << margin;
      }
    }
    before = sorted(*after);
  }
  EXPECT_GT(patches, 0);
  EXPECT_EQ(before, m.tiles);
}

TEST(ColourMerge, MergeThatLosesInformationIsRefused) {
  // Every 2x2 colouring by {0, 1}: the merged set cannot tell 0 from 1.
  std::vector<CornerTile> full;
  for (Colour a = 0; a < 2; ++a)
    for (Colour b = 0; b < 2; ++b)
      for (Colour c = 0; c < 2; ++c)
        for (Colour d = 0; d < 2; ++d) full.push_back({a, b, c, d});
  // Its one tiling lifts (to the all-0 tiling) but stands for every tiling: no conjugacy.
  EXPECT_FALSE(merge_colours(full, 0, 1, false, 1).has_value());
  EXPECT_TRUE(merge_colours(full, 0, 1, true, 1).has_value());

  // Two constant tilings: after the merge one tiling is the image of both, so its tilings only lift.
  const std::vector<CornerTile> two = {{0, 0, 0, 0}, {1, 1, 1, 1}};
  bool conjugate = true;
  const auto lifted = merge_colours(two, 0, 1, true, 1, 0, &conjugate);
  ASSERT_TRUE(lifted.has_value());
  EXPECT_EQ(lifted->size(), 1u);
  EXPECT_FALSE(conjugate);
  EXPECT_FALSE(merge_colours(two, 0, 1, false, 1).has_value());

  // Pegs coloured (row + 2 column) mod 4, rows 0202.., 1313.., 2020.., 3131..: merging 0 and 2
  // lets a row of 0s sit between two rows 1313.., which no tiling of the source maps onto (above
  // 1313.. lies 0202.., below it 2020..): refused.
  std::vector<CornerTile> diag;
  for (Colour r = 0; r < 4; ++r) {
    auto at = [&](Colour i, Colour j) { return (r + i + 2 * j) % 4; };
    diag.push_back({at(0, 1), at(1, 1), at(1, 0), at(0, 0)});
  }
  EXPECT_FALSE(merge_colours(sorted(diag), 0, 2, true, 1).has_value());
  EXPECT_FALSE(merge_colours(sorted(diag), 0, 2, true, 2).has_value());
}

TEST(ColourMerge, BlocksPruneMergeGivesTheSmallestSoundSet) {
  // The chain the enumeration's best set comes from: every link sound, 26 tiles over 4 colours.
  TileSet s = resolve_tile_set("jeandel-rao-11-variant-2");
  for (const char* step : {"blocks", "prune", "merge-colours"}) {
    auto r = apply_step(s, step);
    ASSERT_TRUE(r) << step;
    EXPECT_TRUE(sound_label(r->label)) << step;
    s = r->set;
  }
  EXPECT_EQ(s.kind(), TileKind::Corner);
  EXPECT_EQ(s.size(), 26u);
}
