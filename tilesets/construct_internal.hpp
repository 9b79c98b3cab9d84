#pragma once
// The individual constructions behind construct_packing() (internal to tilesets/).
#include <utility>
#include <vector>

#include "tilesets/tile_grid.hpp"

namespace tilekit {

// construct_euler.cpp: Wang, any C (thesis 5.5.2).
Tiling wang_euler_packing(std::uint32_t colours);
std::pair<int, int> wang_euler_position(std::uint32_t colours, TileIndex tile);

// construct_debruijn.cpp: corner, odd C (de Bruijn rows shifted by triangular numbers).
std::vector<Colour> corner_triangular_pegs(std::uint32_t colours);  // C^2 x C^2, row-major
std::pair<int, int> corner_triangular_position(std::uint32_t colours, TileIndex tile);

// construct_product.cpp: corner, C = a*b with gcd(a, b) = 1 (Chinese remainder theorem).
std::vector<Colour> corner_product_pegs(const std::vector<Colour>& pegs_a, std::uint32_t a,
                                        const std::vector<Colour>& pegs_b, std::uint32_t b);

// construct_lift.cpp: the binary lift quotient of an even period M (a 4M x 4M binary peg torus
// holding every binary 2x2 window once on each residue class mod M), its inverse (the cell of
// the class of `base_cell` whose window is `window`), and the property of the 4x4 torus it uses.
std::vector<Colour> binary_lift_quotient_pegs(std::uint64_t period);
std::pair<int, int> binary_lift_position(std::uint64_t period, std::pair<int, int> base_cell, TileIndex window);
bool binary_lift_torus_ok();

}  // namespace tilekit
