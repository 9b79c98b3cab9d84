#pragma once
// The individual constructions behind construct_packing() (internal to tilesets/).
#include <utility>
#include <vector>

#include "tilesets/tiling.hpp"

namespace tilekit {

// construct_euler.cpp: Wang, any C (thesis 5.5.2).
Tiling wang_euler_packing(std::uint32_t colours);
std::pair<int, int> wang_euler_position(std::uint32_t colours, TileIndex tile);

// construct_debruijn.cpp: corner, odd C (DESIGN.md closed form).
std::vector<Colour> corner_triangular_pegs(std::uint32_t colours);  // C^2 x C^2, row-major
std::pair<int, int> corner_triangular_position(std::uint32_t colours, TileIndex tile);

// construct_product.cpp: corner, C = a*b with gcd(a, b) = 1 (DESIGN.md, Chinese remainder).
std::vector<Colour> corner_product_pegs(const std::vector<Colour>& pegs_a, std::uint32_t a,
                                        const std::vector<Colour>& pegs_b, std::uint32_t b);

}  // namespace tilekit
