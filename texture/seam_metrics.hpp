#pragma once
// How visible the seams of a texture tiling are. The seam ratio is the mean colour
// step across tile borders divided by the mean step between neighbouring pixels inside tiles: 1
// means a border is as smooth as the texture itself; abutting random squares gives 2-4. The cut
// ratio does the same for every pair of neighbours copied from different samples (tile borders
// and the cuts inside tiles), which is where patch choice shows.
#include <cstdint>
#include <vector>

#include "image/image.hpp"
#include "texture/tile_synthesis.hpp"
#include "tilesets/tile_grid.hpp"

namespace tilekit {

struct SeamStatistics {
  double border_step = 0, interior_step = 0, seam_ratio = 0;  // across tile borders / inside tiles
  double cut_step = 0, same_source_step = 0, cut_ratio = 0;   // across sample boundaries / within one sample
  std::size_t border_pairs = 0, cut_pairs = 0;
};

// Mean absolute step (over R, G, B) of 4-neighbours of an image of a tiling with tile_px tiles
// whose borders lie at x0 and y0 plus multiples of tile_px. `sources` (optional, one id per
// pixel) names the sample each pixel came from.
SeamStatistics seam_statistics(const Image& img, int tile_px, const std::vector<std::uint32_t>* sources = nullptr,
                               int x0 = 0, int y0 = 0);

// The tiles of `set` laid out as `tiling` (rows x cols of tile indices), and the matching source
// map with ids made unique per tile where a sample belongs to one tile only.
Image stitch_tiles(const TextureTileSet& set, const Tiling& tiling, std::vector<std::uint32_t>* sources = nullptr);

}  // namespace tilekit
