#pragma once
// The 47 tiles of the 8-neighbour blob set: a tile shows one terrain on a cell and which of its
// eight neighbours continue it; a corner neighbour counts only when both edge neighbours beside it
// do (16 edge patterns, 47 tiles in all). Matching along a border takes three samples, the edge's
// middle and its two ends (Tiled's "mixed" Wang sets), so each tile is a Wang tile whose edge
// colour is the triple (end, middle, end) read west to east or north to south: 4*a + 2*m + b,
// colours 0..7. Two blob tiles may sit side by side exactly when those Wang colours match.
#include <array>
#include <cstdint>
#include <vector>

#include "image/image.hpp"
#include "tilesets/tile_set.hpp"

namespace tilekit::tilemap {

inline constexpr int kBlobTiles = 47;

// A blob tile as its 8 neighbour bits: edges n, e, s, w and corners ne, se, sw, nw (a corner set
// only with both of its edges).
struct BlobTile {
  bool n = false, e = false, s = false, w = false, ne = false, se = false, sw = false, nw = false;
};

// The 47 tiles, in the order of their 8-bit masks (n=1, ne=2, e=4, se=8, s=16, sw=32, w=64, nw=128).
std::vector<BlobTile> blob_tiles();
std::uint8_t blob_mask(const BlobTile& t);
// The Wang set of the 47 tiles (named "blob-47").
TileSet blob_tile_set();
// A picture of a map of blob tiles (indices into blob_tiles()), each tile a 3 x 3 grid of squares
// of `px` / 3 pixels: the centre, the edges and the corners that belong to the terrain drawn dark.
Image blob_picture(const std::vector<int>& map, int rows, int cols, int px);

}  // namespace tilekit::tilemap
