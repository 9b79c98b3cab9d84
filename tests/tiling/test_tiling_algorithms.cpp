// Every tiling algorithm gives valid tilings (checked by the independent validator) for
// C = 2..8 up to 257x257, and the direct ones are random access.
#include <gtest/gtest.h>

#include <set>

#include "tilesets/compact_sets.hpp"
#include "tiling/direct_tiling.hpp"
#include "base/error.hpp"
#include "tiling/halton_tiling.hpp"
#include "base/random.hpp"
#include "tilesets/tile_set_io.hpp"
#include "tiling/tiling_algorithms.hpp"
#include "tilesets/validator.hpp"

using namespace tilekit;

namespace {

struct Case {
  const char* set;  // pattern with {} for C
  TilingAlgo algo;
};

const Case kCases[] = {
    {"compact-wang-{}", TilingAlgo::Scanline},    {"compact-corner-{}", TilingAlgo::Scanline},
    {"complete-corner-{}", TilingAlgo::Direct},   {"complete-wang-{}", TilingAlgo::Direct},
    {"complete-wang-{}", TilingAlgo::DirectEdge}, {"compact-wang3-{}", TilingAlgo::DirectCompact},
    {"complete-corner-{}", TilingAlgo::Halton},   {"complete-corner-{}", TilingAlgo::Controlled},
};

std::string name_for(const char* pattern, std::uint32_t c) {
  std::string s = pattern;
  return s.replace(s.find("{}"), 2, std::to_string(c));
}

}  // namespace

TEST(TilingAlgorithms, EveryAlgorithmGivesValidTilingsForTwoToEightColoursUpTo257) {
  const std::pair<int, int> sizes[] = {{1, 1}, {3, 7}, {64, 33}, {257, 257}};
  for (std::uint32_t c = 2; c <= 8; ++c) {
    for (const Case& k : kCases) {
      const TileSet set = resolve_tile_set(name_for(k.set, c));
      for (auto [rows, cols] : sizes) {
        for (HashKind hash : {HashKind::Permutation, HashKind::LongPeriod}) {
          if (hash == HashKind::Permutation && (k.algo == TilingAlgo::Scanline || k.algo == TilingAlgo::Halton))
            continue;                                                           // no hash involved
          if (rows == 257 && hash == HashKind::Permutation && c % 2) continue;  // keep the suite fast
          TilingRequest req;
          req.algo = k.algo, req.rows = rows, req.cols = cols, req.seed = 1000 + c, req.hash = hash;
          const Tiling t = generate_tiling(set, req);
          ASSERT_EQ(t.rows, rows);
          ASSERT_EQ(t.cols, cols);
          const ValidationReport rep = validate(t, &set);
          ASSERT_TRUE(rep.valid) << set.name() << " " << tiling_algo_name(k.algo) << " " << cols << "x" << rows << ": "
                                 << (rep.errors.empty() ? "" : rep.errors[0]);
        }
      }
    }
  }
}

TEST(TilingAlgorithms, StochasticAlgorithmsUseTheWholeSetOnA257Grid) {
  // thesis 3.3.1 / 3.3.2: the direct algorithms "result in" the complete (or compact C^3) set;
  // the scanline ones choose among all tiles of the compact sets.
  for (const Case& k : kCases) {
    if (k.algo == TilingAlgo::Halton || k.algo == TilingAlgo::Controlled) continue;
    const TileSet set = resolve_tile_set(name_for(k.set, 3));
    TilingRequest req;
    req.algo = k.algo, req.rows = 257, req.cols = 257, req.seed = 5;
    const Tiling t = generate_tiling(set, req);
    EXPECT_EQ(std::set<TileIndex>(t.cells.begin(), t.cells.end()).size(), set.size())
        << set.name() << " " << tiling_algo_name(k.algo);
  }
}

TEST(TilingAlgorithms, SameSeedSameTilingOtherSeedOtherTiling) {
  const TileSet set = complete_corner_set(3);
  TilingRequest req;
  req.rows = 20, req.cols = 20, req.seed = 1;
  for (TilingAlgo algo : {TilingAlgo::Direct, TilingAlgo::Scanline, TilingAlgo::Controlled}) {
    req.algo = algo;
    req.seed = 1;
    const Tiling a = generate_tiling(set, req), b = generate_tiling(set, req);
    req.seed = 2;
    const Tiling c = generate_tiling(set, req);
    EXPECT_EQ(a.cells, b.cells) << tiling_algo_name(algo);
    EXPECT_NE(a.cells, c.cells) << tiling_algo_name(algo);
  }
}

namespace {

// tile(x, y) on its own equals the same tile of a full window generated at (x0, y0).
template <class Algo>
void expect_random_access(const Algo& algo, std::uint64_t seed) {
  SplitMix64 rng(seed);
  const int rows = 300, cols = 1500;  // wider than two periods of a 256-entry table
  const std::int64_t x0 = std::int64_t(rng.below(1ull << 41)) - (1ll << 40);
  const std::int64_t y0 = std::int64_t(rng.below(1ull << 41)) - (1ll << 40);
  std::vector<TileIndex> grid(std::size_t(rows) * cols);
  algo.fill(x0, y0, rows, cols, grid.data());
  for (int k = 0; k < 100000; ++k) {
    const int r = int(rng.below(rows)), c = int(rng.below(cols));
    ASSERT_EQ(algo.tile(x0 + c, y0 + r), grid[std::size_t(r) * cols + c]) << "at " << c << "," << r;
  }
}

}  // namespace

TEST(RandomAccess, DirectCornerTileEqualsFullGridOn100000Positions) {
  for (HashKind h : {HashKind::Permutation, HashKind::LongPeriod}) expect_random_access(DirectCornerTiling(5, h, 1), 1);
}

TEST(RandomAccess, DirectWangTwoHashesTileEqualsFullGridOn100000Positions) {
  for (HashKind h : {HashKind::Permutation, HashKind::LongPeriod})
    expect_random_access(DirectWangTiling(3, 4, h, 2), 2);
}

TEST(RandomAccess, DirectCompactWangTileEqualsFullGridOn100000Positions) {
  for (HashKind h : {HashKind::Permutation, HashKind::LongPeriod})
    expect_random_access(DirectCompactWangTiling(4, h, 3), 3);
}

TEST(RandomAccess, DirectEdgeWangTileEqualsFullGridOn100000Positions) {
  for (HashKind h : {HashKind::Permutation, HashKind::LongPeriod})
    expect_random_access(DirectEdgeWangTiling(2, 3, h, 4), 4);
}

TEST(RandomAccess, HaltonTileEqualsFullGridOn100000Positions) {
  const HaltonCornerTiling algo(6, 700, 900);
  const Tiling grid = algo.generate();
  SplitMix64 rng(5);
  for (int k = 0; k < 100000; ++k) {
    const int r = int(rng.below(700)), c = int(rng.below(900));
    ASSERT_EQ(algo.tile(c, r), grid.at(r, c));
  }
}

TEST(RandomAccess, ControlledTileEqualsFullGridOn100000Positions) {
  const ProbabilityMap map = ProbabilityMap::ramp(4, 3, 17);
  const ControlledColouring h(map, 300, 350, HashKind::LongPeriod, 6);
  const Tiling grid = lattice_corner_tiling(h, 300, 350);
  SplitMix64 rng(6);
  for (int k = 0; k < 100000; ++k) {
    const int r = int(rng.below(300)), c = int(rng.below(350));
    ASSERT_EQ(lattice_corner_tile(h, c, r), grid.at(r, c));
  }
}

TEST(DirectCompactWang, ProducesExactlyTheCompactWang3Tiles) {
  for (std::uint32_t c = 2; c <= 8; ++c) {
    const TileSet set = compact_wang3_set(c);
    EXPECT_EQ(set.size(), std::size_t(c) * c * c);
    const Tiling t = DirectCompactWangTiling(c, HashKind::LongPeriod, c).generate(150, 150);
    std::set<TileIndex> seen(t.cells.begin(), t.cells.end());
    for (TileIndex i : seen) EXPECT_TRUE(set.find_index(i).has_value()) << i;
    if (c <= 4) {
      EXPECT_EQ(seen.size(), set.size()) << c;
    }
  }
}

TEST(DirectEdgeWang, EdgesComeFromTheDenseLatticeMidpoints) {
  // neighbouring tiles share the midpoint of their common edge on the dense lattice
  const DirectEdgeWangTiling a(3, 3, HashKind::LongPeriod, 9);
  for (std::int64_t x = -5; x < 5; ++x) {
    const WangTile t = wang_tile(a.tile(x, 0), 3), right = wang_tile(a.tile(x + 1, 0), 3),
                   below = wang_tile(a.tile(x, 1), 3);
    EXPECT_EQ(t.e, right.w);
    EXPECT_EQ(t.s, below.n);
  }
}

TEST(TilingAlgorithms, AlgorithmThatDoesNotFitTheSetIsAnInputError) {
  TilingRequest req;
  req.rows = req.cols = 4;
  auto message = [&](const std::string& set, TilingAlgo algo) {
    req.algo = algo;
    try {
      generate_tiling(resolve_tile_set(set), req);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("compact-corner-3", TilingAlgo::Direct).find("lacks"), std::string::npos);
  EXPECT_NE(message("complete-corner-3", TilingAlgo::DirectEdge).find("makes wang tilings"), std::string::npos);
  EXPECT_NE(message("complete-wang-3", TilingAlgo::Halton).find("makes corner tilings"), std::string::npos);
  EXPECT_NE(message("compact-wang-3", TilingAlgo::DirectCompact).find("compact-wang3-C"), std::string::npos);
  EXPECT_NE(message("kari-14", TilingAlgo::Scanline).find("(N, W) colour pair"), std::string::npos);
  EXPECT_NE(message("complete-wang-2x3", TilingAlgo::DirectCompact).find("one colour count"), std::string::npos);
  req.rows = 0;
  EXPECT_NE(message("complete-corner-2", TilingAlgo::Direct).find("tiling size"), std::string::npos);
  EXPECT_THROW(parse_tiling_algo("wave-function-collapse"), InputError);
}
