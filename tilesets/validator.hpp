#pragma once
// The independent validator. It shares no code with any generator or search: it decodes
// tile indices itself (thesis eq. 2.3 / 2.6; window indices as tilesets/window_torus.hpp defines
// them) and checks every edge of the grid (every overlap of neighbouring windows), torus
// wrap-around included, and, for packings, that every tile (window) occurs exactly once.
#include <string>
#include <vector>

#include "tilesets/tile_set.hpp"
#include "tilesets/tile_grid.hpp"

namespace tilekit {

struct ValidationReport {
  bool valid = false;    // every cell a tile (of the set, if given), every neighbour pair matches
  bool packing = false;  // valid, a torus, and every tile of the set (or the complete set) exactly once
  std::vector<std::string> errors;  // at most `max_errors`, then a summary line
};

// With `set`, every cell must hold a tile of that set (by index under the tiling's radix)
// and "packing" refers to that set; without it, to the complete set over the radix.
ValidationReport validate(const Tiling& t, const TileSet* set = nullptr, std::size_t max_errors = 20);

}  // namespace tilekit
