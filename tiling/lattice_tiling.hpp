#pragma once
// Corner tilings from a coloured integer lattice (thesis sec. 3.3.1; semi-stochastic paper
// eq. 1-2): every lattice point gets a colour h(x, y), and the tile at (x, y) takes the colours
// of its four corners. Shared by the direct stochastic, Halton and controlled algorithms.
//
// Coordinates: tile (x, y) is the tile in column x and row y, and rows grow to the south
// (DESIGN.md: row 0 at the top). Its corners are the lattice points NW = (x, y),
// NE = (x+1, y), SW = (x, y+1), SE = (x+1, y+1). The thesis puts y to the north and names a
// tile by its SW corner; flipping the y axis maps one convention onto the other.
//
// A Lattice is any type with
//   std::uint32_t colours() const;  std::uint32_t colour(int64 x, int64 y) const;
//   struct RowCache;  void prepare(RowCache&, int64 x0, size_t n) const;
//   void row(RowCache&, int64 y, std::uint16_t* out) const;   // colour(x0 + k, y), k < n
#include <algorithm>
#include <cstdint>
#include <vector>

#include "tilesets/tile.hpp"
#include "tilesets/tiling.hpp"

namespace tilekit {

// The tile at (x, y) evaluated on its own: four lattice evaluations (thesis sec. 3.3.1).
template <class Lattice>
TileIndex lattice_corner_tile(const Lattice& h, std::int64_t x, std::int64_t y) {
  const TileIndex c = h.colours();
  // thesis eq. (2.5): i = ((NE C + SE) C + SW) C + NW
  return ((h.colour(x + 1, y) * c + h.colour(x + 1, y + 1)) * c + h.colour(x, y + 1)) * c + h.colour(x, y);
}

// The tiles (x0 + c, y0 + r), r < rows, c < cols, into out[r * cols + c]. Every lattice point
// is evaluated once (two lattice rows live at a time); the result equals lattice_corner_tile.
// When the lattice rows repeat with a short period p in x (a Lattice with x_period() > 0, e.g.
// one permutation table, thesis eq. 3.3, period N), each row of tiles repeats too: only its
// first p tiles are evaluated and the rest of the row is copied from them.
template <class Lattice>
void fill_lattice_corner_tiles(const Lattice& h, std::int64_t x0, std::int64_t y0, int rows, int cols, TileIndex* out) {
  int evaluated = cols;
  if constexpr (requires { h.x_period(); }) {
    const std::uint64_t p = h.x_period();
    if (p > 0 && std::uint64_t(cols) > 2 * p) evaluated = int(p);
  }
  const std::size_t n = std::size_t(evaluated) + 1;
  typename Lattice::RowCache cache;
  h.prepare(cache, x0, n);
  std::vector<std::uint16_t> north(n), south(n);
  h.row(cache, y0, north.data());
  const TileIndex c = h.colours();
  for (int r = 0; r < rows; ++r) {
    h.row(cache, y0 + r + 1, south.data());
    TileIndex* o = out + std::size_t(r) * std::size_t(cols);
    const std::uint16_t* nr = north.data();
    const std::uint16_t* sr = south.data();
    for (int k = 0; k < evaluated; ++k)
      o[k] = ((TileIndex(nr[k + 1]) * c + sr[k + 1]) * c + sr[k]) * c + nr[k];  // thesis eq. (2.5)
    for (int done = evaluated; done < cols; done += std::min(done, cols - done))
      std::copy_n(o, std::min(done, cols - done), o + done);  // the row repeats with period p
    north.swap(south);
  }
}

// The lattice colours themselves, (cols x rows points from (x0, y0)), row-major.
template <class Lattice>
std::vector<std::uint16_t> lattice_colours(const Lattice& h, std::int64_t x0, std::int64_t y0, int rows, int cols) {
  std::vector<std::uint16_t> out(std::size_t(rows) * std::size_t(cols));
  typename Lattice::RowCache cache;
  h.prepare(cache, x0, std::size_t(cols));
  for (int r = 0; r < rows; ++r) h.row(cache, y0 + r, out.data() + std::size_t(r) * std::size_t(cols));
  return out;
}

// A rows x cols corner tiling (not a torus) of a lattice colouring, from (x0, y0).
template <class Lattice>
Tiling lattice_corner_tiling(const Lattice& h, int rows, int cols, std::int64_t x0 = 0, std::int64_t y0 = 0) {
  Tiling t(TileKind::Corner, h.colours(), rows, cols, false);
  fill_lattice_corner_tiles(h, x0, y0, rows, cols, t.cells.data());
  return t;
}

}  // namespace tilekit
