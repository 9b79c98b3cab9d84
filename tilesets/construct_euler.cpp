// Eulerian tile packings (thesis 5.5.1-5.5.2): the 1D packing of the complete set over C
// colours is an Eulerian circuit of the complete digraph with loops on C vertices, and the
// Wang packing is the outer product of two such circuits (Wei 2004).
#include <cassert>

#include "tilesets/construct_internal.hpp"
#include "tilesets/constructions.hpp"

namespace tilekit {

// Hierholzer's algorithm, specialised to the complete digraph with loops and run one vertex
// at a time: the circuit over colours 0..k-1 is closed at vertex 0; the edges that colour k
// adds form the closed trail 0 -> k -> 1 -> k -> 2 -> ... -> k-1 -> k -> k -> 0, which is
// spliced in at that closing vertex. Every edge (a, b) is used once: pairs with max(a,b) < k
// by the old circuit, pairs with max(a,b) = k by the new trail.
std::vector<Colour> eulerian_sequence(std::uint32_t colours) {
  std::vector<Colour> s;
  if (colours == 0) return s;
  s.reserve(std::size_t(colours) * colours);
  s.push_back(0);  // the loop 0 -> 0
  for (Colour k = 1; k < colours; ++k) {
    s.push_back(0);
    s.push_back(k);
    for (Colour j = 1; j < k; ++j) {
      s.push_back(j);
      s.push_back(k);
    }
    s.push_back(k);
  }
  assert(s.size() == std::size_t(colours) * colours);
  return s;
}

// Closed-form position of the pair (a, b) in the circuit above (thesis 5.5.1: Wei 2004 gives a
// closed form for the 1D Eulerian packing). Pairs with max(a,b) = k occupy [k^2, (k+1)^2):
// the trail for k starts at position k^2 with (0,k), then (k,j), (j,k) for j = 1..k-1, then
// (k,k) and (k,0).
std::uint32_t eulerian_position(Colour a, Colour b) {
  if (a == 0 && b == 0) return 0;
  if (a < b) return 2 * a + b * b;                   // (a, k) with a < k
  if (a == b) return (a + 1) * (a + 1) - 2;          // (k, k)
  if (b > 0) return a * a + 2 * b - 1;               // (k, b) with 0 < b < k
  return (a + 1) * (a + 1) - 1;                      // (k, 0)
}

// Thesis 5.5.2: tile (r, c) has N = x[r], S = x[r+1], W = y[c], E = y[c+1] with x = y the
// circuit above, so every (N,S) pair meets every (W,E) pair once.
Tiling wang_euler_packing(std::uint32_t colours) {
  const std::vector<Colour> s = eulerian_sequence(colours);
  const int n = int(s.size());
  Tiling t(TileKind::Wang, colours, n, n, true);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      WangTile w{s[std::size_t(r)], s[std::size_t((c + 1) % n)], s[std::size_t((r + 1) % n)], s[std::size_t(c)]};
      t.at(r, c) = wang_index(w, colours);  // thesis eq. (2.2)
    }
  return t;
}

// Thesis 5.5.2: the 2D position is the 1D closed form in each dimension.
std::pair<int, int> wang_euler_position(std::uint32_t colours, TileIndex tile) {
  const WangTile w = wang_tile(tile, colours);  // thesis eq. (2.3)
  return {int(eulerian_position(w.n, w.s)), int(eulerian_position(w.w, w.e))};
}

}  // namespace tilekit
