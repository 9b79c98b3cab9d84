#pragma once
// Tile packings without search, used by `tilekit pack --method construct|auto` and the atlas
// lookup (packing/find_packing.hpp).
//   - Wang, any C: outer product of two Eulerian circuits (thesis 5.5.1-5.5.2, Wei 2004).
//   - corner, odd C: de Bruijn sequence shifted by triangular numbers (construct_debruijn.cpp).
//   - corner, C = a*b with gcd(a,b) = 1: product of an a- and a b-packing (construct_product.cpp).
//   - corner, C = 2m with m even: binary colour-quotient lift of the m-packing
//     (construct_lift.cpp), so every power of two from 4 up, and with the products every C.
//   - corner C = 2, 4, 8: packings found by the solver, stored as data (used before the lift).
//
// Layout of a corner packing: the C^2 x C^2 torus of pegs P(r,c); the tile at cell (r,c) has
// nw = P(r,c), ne = P(r,c+1), sw = P(r+1,c), se = P(r+1,c+1) (indices mod C^2).
// Layout of a Wang packing: N/S edge colours x[r], x[r+1] and W/E edge colours y[c], y[c+1].
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "tilesets/tile_grid.hpp"

namespace tilekit {

struct ConstructedPacking {
  Tiling tiling;      // C^2 x C^2 torus packing of the complete set
  std::string how;    // e.g. "euler-product", "debruijn-triangular", "product 3x4", "stored"
  bool closed_form = false;  // tile_position() is a formula (no table) for this packing
};

// nullopt when no construction is known for this kind and C.
std::optional<ConstructedPacking> construct_packing(TileKind kind, std::uint32_t colours);

// The C-colour Eulerian circuit of the complete digraph with loops (thesis 5.5.1): a cyclic
// sequence s of length C^2 in which every ordered pair (s[i], s[i+1 mod C^2]) occurs once,
// i.e. a de Bruijn sequence of order 2. Built by Hierholzer splicing, one colour at a time.
std::vector<Colour> eulerian_sequence(std::uint32_t colours);
// Wei's closed form: the position i of the pair (a, b) in eulerian_sequence(C), for any
// C > max(a, b) (the circuit for C extends the one for C-1).
std::uint32_t eulerian_position(Colour a, Colour b);

// Row and column of `tile` in construct_packing(kind, colours), without building the packing
// when a closed form exists (Wang, odd corner) and from the factors' positions for products.
// nullopt when no packing is known for this C.
std::optional<std::pair<int, int>> packing_position(TileKind kind, std::uint32_t colours, TileIndex tile);

// A packing stored as data (tilesets/data/packing-<kind>-<C>.json, found by the solver; the
// file names the command that found it), checked by the validator on load.
std::optional<Tiling> stored_packing(TileKind kind, std::uint32_t colours);

// The colour counts in 1..max_colours for which construct_packing() succeeds.
std::vector<std::uint32_t> constructible_colours(TileKind kind, std::uint32_t max_colours);

// Colour-quotient lift (construct_lift.cpp): the tiling over (base colours) x
// (quotient colours) whose every corner or edge colour is b + m*e, b from `base` (a square torus,
// m colours, repeated with its period) and e from `quotient` (a k-colour torus whose side is a
// multiple of the base's). It is a packing exactly when `base` is one and `quotient` holds every
// k-colour tile once on each residue class of cells modulo the base's side. Throws InputError
// for mismatched kinds or sizes.
Tiling colour_lift(const Tiling& base, const Tiling& quotient);

}  // namespace tilekit
