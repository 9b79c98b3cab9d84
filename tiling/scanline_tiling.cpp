#include "tiling/scanline_tiling.hpp"

#include <fmt/format.h>

#include <vector>

#include "base/error.hpp"
#include "base/random.hpp"

namespace tilekit {

namespace {

// Tile numbers grouped by a key in [0, keys).
struct Buckets {
  std::vector<std::vector<std::uint32_t>> of;
  explicit Buckets(std::size_t keys) : of(keys) {}
  std::uint32_t pick(std::size_t key, SplitMix64& rng) const {
    const auto& b = of[key];
    return b[rng.below(b.size())];
  }
};

void check_size(const TileSet& set, int rows, int cols) {
  if (rows < 1 || cols < 1) throw InputError(fmt::format("tiling size must be at least 1x1, got {}x{}", cols, rows));
  if (set.empty()) throw InputError(fmt::format("tile set '{}' is empty", set.name()));
}

}  // namespace

Tiling scanline_wang_tiling(const TileSet& set, int rows, int cols, std::uint64_t seed) {
  check_size(set, rows, cols);
  const auto& tiles = set.wang_tiles();
  const std::uint32_t ch = set.horizontal_radix(), cv = set.vertical_radix();
  Buckets by_nw(std::size_t(ch) * cv), by_w(cv), by_n(ch);
  for (std::uint32_t k = 0; k < tiles.size(); ++k) {
    by_nw.of[tiles[k].n * cv + tiles[k].w].push_back(k);
    by_w.of[tiles[k].w].push_back(k);
    by_n.of[tiles[k].n].push_back(k);
  }
  // Cohen et al. 2003: "so long as there is at least one tile in the set with each N and W
  // combination", every step has a choice.
  for (std::uint32_t n = 0; n < ch; ++n)
    for (std::uint32_t w = 0; w < cv; ++w)
      if (by_nw.of[n * cv + w].empty())
        throw InputError(
            fmt::format("tile set '{}' has no tile with N={} and W={}; scanline Wang tiling needs one "
                        "for every (N, W) colour pair (e.g. compact-wang-C)",
                        set.name(), n, w));
  SplitMix64 rng(seed);
  Tiling t(TileKind::Wang, ch, rows, cols, false);
  if (cv != ch) t.vertical_colours = cv;
  std::vector<std::uint32_t> placed(std::size_t(rows) * cols);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      std::uint32_t k;
      if (r == 0 && c == 0)
        k = std::uint32_t(rng.below(tiles.size()));  // any tile in the NW corner
      else if (r == 0)
        k = by_w.pick(tiles[placed[c - 1]].e, rng);  // W matches E of the left tile
      else if (c == 0)
        k = by_n.pick(tiles[placed[std::size_t(r - 1) * cols]].s, rng);  // N matches S above
      else
        k = by_nw.pick(
            tiles[placed[std::size_t(r - 1) * cols + c]].s * cv + tiles[placed[std::size_t(r) * cols + c - 1]].e, rng);
      placed[std::size_t(r) * cols + c] = k;
      t.at(r, c) = set.index_of(k);
    }
  return t;
}

Tiling scanline_corner_tiling(const TileSet& set, int rows, int cols, std::uint64_t seed) {
  check_size(set, rows, cols);
  const auto& tiles = set.corner_tiles();
  const std::size_t c1 = set.horizontal_radix();
  Buckets by_three(c1 * c1 * c1), by_west(c1 * c1), by_north(c1 * c1);
  for (std::uint32_t k = 0; k < tiles.size(); ++k) {
    const CornerTile& x = tiles[k];
    by_three.of[(x.ne * c1 + x.nw) * c1 + x.sw].push_back(k);
    by_west.of[x.nw * c1 + x.sw].push_back(k);
    by_north.of[x.nw * c1 + x.ne].push_back(k);
  }
  // thesis sec. 3.2.2: two tiles for each combination of NE, NW and SW corner colours
  for (std::uint32_t ne = 0; ne < c1; ++ne)
    for (std::uint32_t nw = 0; nw < c1; ++nw)
      for (std::uint32_t sw = 0; sw < c1; ++sw)
        if (by_three.of[(ne * c1 + nw) * c1 + sw].empty())
          throw InputError(
              fmt::format("tile set '{}' has no tile with NE={}, NW={}, SW={}; scanline corner tiling "
                          "needs one for every (NE, NW, SW) colour triple (e.g. compact-corner-C)",
                          set.name(), ne, nw, sw));
  SplitMix64 rng(seed);
  Tiling t(TileKind::Corner, std::uint32_t(c1), rows, cols, false);
  std::vector<std::uint32_t> placed(std::size_t(rows) * cols);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      std::uint32_t k;
      if (r == 0 && c == 0) {
        k = std::uint32_t(rng.below(tiles.size()));
      } else if (r == 0) {  // NW, SW match NE, SE of the left tile
        const CornerTile& l = tiles[placed[c - 1]];
        k = by_west.pick(l.ne * c1 + l.se, rng);
      } else if (c == 0) {  // NW, NE match SW, SE of the tile above
        const CornerTile& a = tiles[placed[std::size_t(r - 1) * cols]];
        k = by_north.pick(a.sw * c1 + a.se, rng);
      } else {  // NE, NW from the tile above, SW from the tile to the left
        const CornerTile& a = tiles[placed[std::size_t(r - 1) * cols + c]];
        const CornerTile& l = tiles[placed[std::size_t(r) * cols + c - 1]];
        k = by_three.pick((a.se * c1 + a.sw) * c1 + l.se, rng);
      }
      placed[std::size_t(r) * cols + c] = k;
      t.at(r, c) = set.index_of(k);
    }
  return t;
}

}  // namespace tilekit
