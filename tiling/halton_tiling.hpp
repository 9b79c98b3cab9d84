#pragma once
// Semi-stochastic corner tiling from the Halton sequence (Schloemer & Deussen 2010, sec. 3.2,
// eq. 3-6). The scaled Halton points (2^n1 phi_2(i), 3^n2 phi_3(i)) visit every cell of the
// 2^n1 x 3^n2 grid exactly once for i < 2^n1 3^n2; the lattice point (x, y) gets the index i'
// of the point falling into its cell (eq. 5/6) and the colour floor(i' C / (2^n1 3^n2)) (eq. 4).
// n1, n2 are the smallest exponents with 2^n1 >= T_x + 1 and 3^n2 >= T_y + 1 for a tiling of
// T_x x T_y tiles. All arithmetic is 64-bit (the paper's 32-bit version stops near 46,000^2),
// so tilings up to 2^31 - 1 tiles per side are exact. Points outside the grid wrap modulo
// (2^n1, 3^n2). Deterministic: there is no seed.
#include <cstdint>
#include <utility>
#include <vector>

#include "tiling/lattice_tiling.hpp"

namespace tilekit {

class HaltonColouring {
 public:
  // A colouring for a lattice of `lattice_cols` x `lattice_rows` points (T_x + 1, T_y + 1).
  HaltonColouring(std::uint32_t colours, std::uint64_t lattice_cols, std::uint64_t lattice_rows);

  std::uint32_t colours() const { return c_; }
  int n1() const { return n1_; }
  int n2() const { return n2_; }
  std::uint64_t p1() const { return p1_; }
  std::uint64_t p2() const { return p2_; }

  // eq. (6): i' = (p2 (l1 m1 mod p1) + p1 (l2 m2 mod p2)) mod (p1 p2)
  std::uint64_t index(std::int64_t x, std::int64_t y) const;
  // eq. (4): floor(i' C / (p1 p2))
  std::uint32_t colour(std::int64_t x, std::int64_t y) const { return colour_of_index(index(x, y)); }
  std::uint32_t colour_of_index(std::uint64_t i) const;

  // Forward enumeration (eq. 3): the grid cell (x, y) of scaled Halton point i.
  static std::pair<std::uint64_t, std::uint64_t> cell_of_point(std::uint64_t i, int n1, int n2);

  struct RowCache {
    std::vector<std::uint64_t> a;  // p2 (l1(x) m1 mod p1) per column
  };
  void prepare(RowCache& cache, std::int64_t x0, std::size_t n) const;
  void row(RowCache& cache, std::int64_t y, std::uint16_t* out) const;

 private:
  std::uint64_t column_term(std::int64_t x) const;
  std::uint64_t row_term(std::int64_t y) const;
  std::uint32_t c_;
  int n1_ = 0, n2_ = 0;
  std::uint64_t p1_ = 1, p2_ = 1, m1_ = 0, m2_ = 0;
  std::vector<std::uint64_t> thresholds_;  // first index of each colour: ceil(c p1 p2 / C)
};

// Corner tiling of T_x x T_y tiles (cols x rows) from the Halton colouring of its lattice.
class HaltonCornerTiling {
 public:
  HaltonCornerTiling(std::uint32_t colours, int rows, int cols)
      : h_(colours, std::uint64_t(cols) + 1, std::uint64_t(rows) + 1), rows_(rows), cols_(cols) {}
  const HaltonColouring& colouring() const { return h_; }
  TileIndex tile(std::int64_t x, std::int64_t y) const { return lattice_corner_tile(h_, x, y); }
  void fill(TileIndex* out) const { fill_lattice_corner_tiles(h_, 0, 0, rows_, cols_, out); }
  Tiling generate() const { return lattice_corner_tiling(h_, rows_, cols_); }

 private:
  HaltonColouring h_;
  int rows_, cols_;
};

}  // namespace tilekit
