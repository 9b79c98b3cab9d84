#pragma once
// Compact tile sets used by the stochastic tiling algorithms (thesis ch. 3).
#include <cstdint>

#include "tilesets/tile_set.hpp"

namespace tilekit {

// 2C^2 Wang tiles: two for every (N, W) colour pair, for scanline tiling
// (Cohen et al. 2003; thesis sec. 3.2.1). Needs C >= 2.
TileSet compact_wang_set(std::uint32_t c);

// C^3 Wang tiles with N + S = E + W (mod C): exactly the tiles the direct compact
// algorithm produces, edges being sums of corner colours (thesis sec. 3.3.2.2).
TileSet compact_wang3_set(std::uint32_t c);

// 2C^3 corner tiles: two for every (NE, NW, SW) colour triple, for scanline corner
// tiling (thesis sec. 3.2.2). Needs C >= 2; for C = 2 it is the complete set.
TileSet compact_corner_set(std::uint32_t c);

}  // namespace tilekit
