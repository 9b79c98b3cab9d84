#include "tilesets/compact_sets.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "base/error.hpp"

namespace tilekit {

namespace {
void check_compact(std::uint32_t c, const char* family) {
  check_colour_count(c);
  if (c < 2) throw InputError(fmt::format("{} needs at least 2 colours (two choices per constraint)", family));
}
}  // namespace

TileSet compact_wang_set(std::uint32_t c) {
  check_compact(c, "compact-wang");
  std::vector<WangTile> tiles;
  for (Colour n = 0; n < c; ++n)
    for (Colour w = 0; w < c; ++w)
      for (Colour k = 0; k < 2; ++k)  // thesis sec. 3.2.1: two tiles per (N, W) pair
        tiles.push_back({n, (n + w + k) % c, (w + k + 1) % c, w});
  std::sort(tiles.begin(), tiles.end(), [c](const WangTile& a, const WangTile& b) {
    return wang_index(a, c) < wang_index(b, c);
  });
  return TileSet::wang(std::move(tiles), fmt::format("compact-wang-{}", c),
                       "compact Wang set, 2C^2 tiles (Cohen et al. 2003; thesis 3.2.1)", c, c);
}

TileSet compact_wang3_set(std::uint32_t c) {
  check_colour_count(c);
  std::vector<WangTile> tiles;
  for (TileIndex i = 0; i < complete_size(c, c); ++i) {
    WangTile t = wang_tile(i, c);
    if ((t.n + t.s) % c == (t.e + t.w) % c) tiles.push_back(t);  // thesis sec. 3.3.2.2
  }
  return TileSet::wang(std::move(tiles), fmt::format("compact-wang3-{}", c),
                       "compact Wang set of the direct compact algorithm, C^3 tiles (thesis 3.3.2.2)", c, c);
}

TileSet compact_corner_set(std::uint32_t c) {
  check_compact(c, "compact-corner");
  std::vector<CornerTile> tiles;
  for (Colour ne = 0; ne < c; ++ne)
    for (Colour nw = 0; nw < c; ++nw)
      for (Colour sw = 0; sw < c; ++sw)
        for (Colour k = 0; k < 2; ++k)  // thesis sec. 3.2.2: two tiles per (NE, NW, SW) triple
          tiles.push_back({ne, (ne + nw + sw + k) % c, sw, nw});
  std::sort(tiles.begin(), tiles.end(), [c](const CornerTile& a, const CornerTile& b) {
    return corner_index(a, c) < corner_index(b, c);
  });
  return TileSet::corner(std::move(tiles), fmt::format("compact-corner-{}", c),
                         "compact corner set, 2C^3 tiles (thesis 3.2.2)", c);
}

}  // namespace tilekit
