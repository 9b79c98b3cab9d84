#pragma once
// Scanline stochastic tiling algorithms (thesis sec. 3.2): tiles are placed west to east and
// north to south, each chosen uniformly at random among the tiles of the set that match the
// tiles already placed to the north and west. Not random access: the whole tiling is built.
#include <cstdint>

#include "tilesets/tile_set.hpp"
#include "tilesets/tile_grid.hpp"

namespace tilekit {

// Wang tiles (Cohen et al. 2003; thesis sec. 3.2.1). The set must hold a tile for every
// (N, W) colour pair over its radix (compact-wang-C holds two); InputError otherwise.
Tiling scanline_wang_tiling(const TileSet& set, int rows, int cols, std::uint64_t seed);

// Corner tiles (thesis sec. 3.2.2). The set must hold a tile for every (NE, NW, SW) colour
// triple (compact-corner-C holds two); InputError otherwise.
Tiling scanline_corner_tiling(const TileSet& set, int rows, int cols, std::uint64_t seed);

}  // namespace tilekit
