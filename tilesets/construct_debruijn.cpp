// Corner packings for odd C without search. A corner packing over C colours is a
// (C^2, C^2; 2, 2)_C de Bruijn torus: every 2x2 window of pegs occurs once.
// Row r of the pegs is a de Bruijn sequence s of order 2 shifted by the triangular number
// T(r) = r(r-1)/2: P(r, c) = s[(c + T(r)) mod N], N = C^2.
//   - The window at (r, c) has top pair at position p = c + T(r) of s and bottom pair at
//     p + r, since T(r+1) - T(r) = r. Over the N rows the offsets r = 0..N-1 are distinct
//     mod N, so (top pair, bottom pair) runs over every pair of pairs exactly once.
//   - The rows wrap: T(N) = N(N-1)/2 = 0 mod N exactly when N is odd, i.e. C odd.
// The thesis (5.5.3, 7) lists a constructive method for corner packings as an open problem.
#include <cassert>

#include "tilesets/construct_internal.hpp"
#include "tilesets/constructions.hpp"

namespace tilekit {

namespace {
std::uint64_t triangular(std::uint64_t r) { return r * (r - 1) / 2; }  // T(r) = r(r-1)/2
}  // namespace

std::vector<Colour> corner_triangular_pegs(std::uint32_t colours) {
  const std::vector<Colour> s = eulerian_sequence(colours);  // de Bruijn sequence of order 2
  const std::uint64_t n = s.size();
  assert(n == std::uint64_t(colours) * colours);
  std::vector<Colour> pegs(n * n);
  for (std::uint64_t r = 0; r < n; ++r) {
    const std::uint64_t shift = r == 0 ? 0 : triangular(r) % n;
    for (std::uint64_t c = 0; c < n; ++c) pegs[r * n + c] = s[(c + shift) % n];  // P(r, c)
  }
  return pegs;
}

// Inverse of the construction: the top pair (nw, ne) sits at p = pos(nw, ne) in s and the
// bottom pair (sw, se) at q = p + r, so r = q - p and c = p - T(r) (mod N), with pos() the
// closed form of eulerian_position().
std::pair<int, int> corner_triangular_position(std::uint32_t colours, TileIndex tile) {
  const CornerTile t = corner_tile(tile, colours);  // thesis eq. (2.6)
  const std::uint64_t n = std::uint64_t(colours) * colours;
  const std::uint64_t p = eulerian_position(t.nw, t.ne), q = eulerian_position(t.sw, t.se);
  const std::uint64_t r = (q + n - p) % n;
  const std::uint64_t c = (p + n - triangular(r) % n) % n;
  assert(r < n && c < n);
  return {int(r), int(c)};
}

}  // namespace tilekit
