// Colour-quotient lifts and the binary lift construction that gives a corner packing
// for every power of two (and with the products, for every C) without search.
//
// The lift. Let B be a packing over m colours (period M = m^2) and E a k-colour tiling of the
// (k^2 M) x (k^2 M) torus. A(r,c) takes every corner (Wang: edge) colour b + m*e from the colour
// b of B at (r mod M, c mod M) and e of E at (r,c). A's tile at (r,c) thus splits digit by digit
// into B's tile at (r mod M, c mod M) (the digits mod m) and E's tile at (r,c) (the digits div m);
// the split is a bijection between C-colour tiles, C = k*m, and pairs (m-colour tile, k-colour
// tile). B holds every m-colour tile t_B at exactly one cell p, so the cells of A whose B-part is
// t_B are exactly the k^4 cells of the residue class of p mod M. Hence A holds every C-colour tile
// exactly once if and only if, on each residue class mod M, E's tiles are all k^4 k-colour tiles
// exactly once. (Matching edges of A follow from those of B and E: A is a valid torus tiling
// whenever B and E are.) The condition does not involve B: one quotient E lifts every packing of
// that period.
//
// The binary lift (k = 2, M even), derived for this project: with g a 4x4 binary de Bruijn torus
// (the pegs of a C=2 packing) and x(i) = 2*u(i) + (i mod 2), where for i = r + M*a (0 <= r < M,
// 0 <= a < 4) u(i) is bit 1 of a when i is even and bit 0 of a when i is odd, the pegs
// E(i,j) = g(x(i), x(j)) are a lift quotient of period M:
//   - The window of E at (i,j) is g's 2x2 "window" on the rows x(i), x(i+1) and the columns
//     x(j), x(j+1) (not adjacent in g in general).
//   - On the residue class of r, the row pairs (x(r+Ma), x(r+1+Ma)) for a = 0..3 are all four
//     pairs of {0,2} x {1,3} when r is even, all of {1,3} x {0,2} when r is odd (r = M-1 included:
//     there i+1 = M(a+1), whose bit 1 runs over 0,1,1,0 while bit 0 of a runs over 0,1,0,1).
//     The same holds for the columns.
//   - g maps each of the 2 x 2 combinations of these row-pair and column-pair families
//     injectively onto the 16 binary windows (checked below by binary_lift_torus_ok(), asserted
//     where it is used and tested). So every class holds the 16 windows once.
// Iterating from the stored C=2 packing gives C = 4, 8, 16, 32, ... (periods 4, 16, 64, 256).
#include <array>
#include <cassert>

#include "base/error.hpp"
#include "tilesets/construct_internal.hpp"
#include "tilesets/constructions.hpp"

namespace tilekit {

namespace {

// The 4x4 binary de Bruijn torus g (the (4,4;2,2)_2 torus; pegs of a C=2 corner packing).
constexpr std::array<std::array<Colour, 4>, 4> kBinaryTorus = {{{0, 1, 0, 0}, {0, 1, 1, 1}, {1, 1, 1, 0}, {0, 0, 1, 0}}};

// Window of g on rows (s, s2) and columns (t, t2) as a corner tile index over 2 colours.
TileIndex torus_window(int s, int s2, int t, int t2) {
  const auto& g = kBinaryTorus;
  CornerTile w{g[std::size_t(s)][std::size_t(t2)], g[std::size_t(s2)][std::size_t(t2)], g[std::size_t(s2)][std::size_t(t)],
               g[std::size_t(s)][std::size_t(t)]};  // ne, se, sw, nw
  return corner_index(w, 2);
}

// x(i) of the construction above: 2*u(i) + (i mod 2).
int lift_row(std::uint64_t i, std::uint64_t period) {
  const std::uint64_t a = (i / period) % 4;
  const std::uint64_t u = i % 2 == 0 ? a >> 1 : a & 1;
  return int(2 * u + i % 2);
}

}  // namespace

bool binary_lift_torus_ok() {
  // Row-pair families {0,2}x{1,3} and {1,3}x{0,2}; the same for columns.
  const std::array<std::array<std::array<int, 2>, 4>, 2> fam = {
      {{{{0, 1}, {0, 3}, {2, 1}, {2, 3}}}, {{{1, 0}, {1, 2}, {3, 0}, {3, 2}}}}};
  for (const auto& rows : fam)
    for (const auto& cols : fam) {
      unsigned seen = 0;
      for (const auto& rp : rows)
        for (const auto& cp : cols) seen |= 1u << torus_window(rp[0], rp[1], cp[0], cp[1]);
      if (seen != 0xffffu) return false;
    }
  return true;
}

std::vector<Colour> binary_lift_quotient_pegs(std::uint64_t period) {
  assert(period % 2 == 0 && binary_lift_torus_ok());
  const std::uint64_t n = 4 * period;
  std::vector<int> x(n);
  for (std::uint64_t i = 0; i < n; ++i) x[i] = lift_row(i, period);
  std::vector<Colour> e(n * n);
  for (std::uint64_t i = 0; i < n; ++i)
    for (std::uint64_t j = 0; j < n; ++j) e[i * n + j] = kBinaryTorus[std::size_t(x[i])][std::size_t(x[j])];
  return e;
}

std::pair<int, int> binary_lift_position(std::uint64_t period, std::pair<int, int> base_cell, TileIndex window) {
  assert(period % 2 == 0 && window < 16);
  const std::uint64_t n = 4 * period;
  for (std::uint64_t a = 0; a < 4; ++a)
    for (std::uint64_t b = 0; b < 4; ++b) {
      const std::uint64_t i = std::uint64_t(base_cell.first) + period * a, j = std::uint64_t(base_cell.second) + period * b;
      if (torus_window(lift_row(i, period), lift_row((i + 1) % n, period), lift_row(j, period),
                       lift_row((j + 1) % n, period)) == window)
        return {int(i), int(j)};
    }
  assert(false && "every binary window occurs once in each residue class");
  return {-1, -1};
}

Tiling colour_lift(const Tiling& base, const Tiling& quotient) {
  if (base.kind != quotient.kind || !base.torus || !quotient.torus || base.rows != base.cols ||
      quotient.rows != quotient.cols || quotient.rows % base.rows != 0)
    throw InputError("a colour lift needs a square base torus and a quotient torus of the same kind, a multiple of its size");
  const int period = base.rows;
  Tiling a(base.kind, base.ch() * quotient.ch(), quotient.rows, quotient.cols, true);
  if (base.kind == TileKind::Wang) a.vertical_colours = base.cv() * quotient.cv();
  for (int r = 0; r < a.rows; ++r)
    for (int c = 0; c < a.cols; ++c) {
      const TileIndex tb = base.at(r % period, c % period), te = quotient.at(r, c);
      if (base.kind == TileKind::Corner) {
        const std::uint32_t m = base.ch(), k = quotient.ch();
        const CornerTile b = corner_tile(tb, m), e = corner_tile(te, k);
        a.at(r, c) = corner_index({b.ne + m * e.ne, b.se + m * e.se, b.sw + m * e.sw, b.nw + m * e.nw}, a.ch());
      } else {  // N, S in the horizontal radix; E, W in the vertical one (thesis sec. 2.7)
        const std::uint32_t mh = base.ch(), mv = base.cv();
        const WangTile b = wang_tile(tb, mh, mv), e = wang_tile(te, quotient.ch(), quotient.cv());
        a.at(r, c) = wang_index({b.n + mh * e.n, b.e + mv * e.e, b.s + mh * e.s, b.w + mv * e.w}, a.ch(), a.cv());
      }
    }
  return a;
}

}  // namespace tilekit
