#pragma once
// Corner tilings from a coloured integer lattice (thesis sec. 3.3.1; semi-stochastic paper
// eq. 1-2): every lattice point gets a colour h(x, y), and the tile at (x, y) takes the colours
// of its four corners. Shared by the direct stochastic, Halton and controlled algorithms.
//
// Coordinates: tile (x, y) is the tile in column x and row y, and rows grow to the south
// (row 0 at the top, as every grid in Tilekit: tilesets/tile_grid.hpp). Its corners are the
// lattice points NW = (x, y), NE = (x+1, y), SW = (x, y+1), SE = (x+1, y+1). The thesis puts y
// to the north and names a tile by its SW corner; flipping the y axis maps one convention onto
// the other.
//
// A Lattice is any type with
//   std::uint32_t colours() const;  std::uint32_t colour(int64 x, int64 y) const;
//   struct RowCache;  void prepare(RowCache&, int64 x0, size_t n) const;
//   void row(RowCache&, int64 y, std::uint16_t* out) const;   // colour(x0 + k, y), k < n
#include <algorithm>
#include <cstdint>
#include <vector>

#include "base/parallel.hpp"
#include "tilesets/tile.hpp"
#include "tilesets/tile_grid.hpp"

namespace tilekit {

// The tile at (x, y) evaluated on its own: four lattice evaluations (thesis sec. 3.3.1).
template <class Lattice>
TileIndex lattice_corner_tile(const Lattice& h, std::int64_t x, std::int64_t y) {
  const TileIndex c = h.colours();
  // thesis eq. (2.5): i = ((NE C + SE) C + SW) C + NW
  return ((h.colour(x + 1, y) * c + h.colour(x + 1, y + 1)) * c + h.colour(x, y + 1)) * c + h.colour(x, y);
}

// The kernel of the byte-colour path of fill_lattice_corner_tiles (lattice_kernels.cpp): from the
// colours of the lattice row south of a row of tiles (n + 1 entries) and the north row's code
// NE C^3 + NW per tile, the tile indices (thesis eq. 2.5), and the south row's code for the next
// row of tiles. C^4 <= 65536.
void corner_row_tiles(const std::uint8_t* south, const std::uint16_t* north_code, std::size_t n, std::uint32_t colours,
                      TileIndex* out, std::uint16_t* south_code);
void corner_row_code(const std::uint8_t* row, std::size_t n, std::uint32_t colours, std::uint16_t* code);

// The tiles (x0 + c, y0 + r), r < rows, c < cols, into out[r * cols + c]. Every lattice point
// is evaluated once per block of rows (two lattice rows live at a time); the result equals
// lattice_corner_tile. When the lattice rows repeat with a short period p in x (a Lattice with
// x_period() > 0, e.g. one permutation table, thesis eq. 3.3, period N), each row of tiles
// repeats too: only its first p tiles are evaluated and the rest of the row is copied from
// them. With threads > 1, blocks of rows run in parallel (base/parallel.hpp); the tiles do
// not depend on the thread count.
template <class Lattice>
void fill_lattice_corner_tiles(const Lattice& h, std::int64_t x0, std::int64_t y0, int rows, int cols, TileIndex* out,
                               int threads = 1) {
  int evaluated = cols;
  if constexpr (requires { h.x_period(); }) {
    const std::uint64_t p = h.x_period();
    if (p > 0 && std::uint64_t(cols) > 2 * p) evaluated = int(p);
  }
  const std::size_t n = std::size_t(evaluated) + 1;
  const TileIndex c = h.colours();
  // Colours as bytes where the hash allows (ColourHash::bytes_suffice) and indices fit 16 bits:
  // the row kernels work on 16 or 32 lanes at a time.
  bool bytes = false;
  if constexpr (requires(typename Lattice::RowCache & rc) { h.row_bytes(rc, y0); })
    bytes = h.bytes_suffice() && std::uint64_t(c) * c * c * c <= 65536;
  auto block = [&](int r0, int r1) {
    if constexpr (requires(typename Lattice::RowCache & rc) { h.row_bytes(rc, y0); }) {
      if (bytes) {
        typename Lattice::RowCache cache;
        h.prepare(cache, x0, n);
        std::vector<std::uint16_t> north(n), south(n);
        corner_row_code(h.row_bytes(cache, y0 + r0), std::size_t(evaluated), c, north.data());
        for (int r = r0; r < r1; ++r) {
          const std::uint8_t* row = h.row_bytes(cache, y0 + r + 1);
          TileIndex* o = out + std::size_t(r) * std::size_t(cols);
          corner_row_tiles(row, north.data(), std::size_t(evaluated), c, o, south.data());
          for (int done = evaluated; done < cols; done += std::min(done, cols - done))
            std::copy_n(o, std::min(done, cols - done), o + done);  // the row repeats with period p
          north.swap(south);
        }
        return;
      }
    }
    typename Lattice::RowCache cache;
    h.prepare(cache, x0, n);
    std::vector<std::uint16_t> north(n), south(n);
    h.row(cache, y0 + r0, north.data());
    for (int r = r0; r < r1; ++r) {
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
  };
  if (threads <= 1 || rows < 2) return block(0, rows);
  const int blocks = std::min(rows, threads * 8), per = (rows + blocks - 1) / blocks;
  parallel_for(blocks, threads, [&](std::int64_t b) { block(int(b) * per, std::min(rows, int(b + 1) * per)); });
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
