#pragma once
// Atlas images (thesis 5.4): the tiles of a packing laid out as one texture, either from a
// folder of tile images named by tile index, or from generated tiles that blend their corner
// (or edge) colours smoothly, so that the whole atlas is continuous across every tile border,
// wrap-around included: exactly the property a packing exists for.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "atlas/lookup.hpp"
#include "image/image.hpp"

namespace tilekit {

// One generated tile of `size` x `size` pixels: corner tiles blend their four corner colours
// (smoothstep-bilinear); Wang tiles blend each edge colour in from its edge, fading to grey
// at the tile corners (where four tiles meet), so a tile's border depends only on that edge.
Image generated_tile(TileKind kind, std::uint32_t colours, TileIndex tile, int size);

// The colour of colour number k of C (evenly spaced hues).
std::array<std::uint8_t, 3> palette_colour(std::uint32_t k, std::uint32_t colours);

Image atlas_from_generated_tiles(const AtlasLookup& a, int tile_size);
// Files in `dir` whose name (without extension) ends in a tile index, e.g. 17.png or
// tile-0017.png; every tile of the set exactly once, all of one size. Throws InputError. 16-bit
// tiles (PNG, TIFF) make a 16-bit atlas and float tiles (OpenEXR, float TIFF) a float one (the
// other tiles among them are converted: image/image.hpp's to_depth).
Image atlas_from_tile_images(const AtlasLookup& a, const std::string& dir);

// Largest colour step (max over channels) between horizontally or vertically adjacent pixels
// that straddle a tile border (wrap-around included), and the largest inside tiles.
struct SeamReport {
  int seam_jump = 0, interior_jump = 0;
};
SeamReport measure_seams(const Image& img, int tile_size);

}  // namespace tilekit
