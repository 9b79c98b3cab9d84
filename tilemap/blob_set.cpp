#include "tilemap/blob_set.hpp"

#include <fmt/format.h>

#include "base/error.hpp"

namespace tilekit::tilemap {

std::uint8_t blob_mask(const BlobTile& t) {
  return std::uint8_t(t.n * 1 + t.ne * 2 + t.e * 4 + t.se * 8 + t.s * 16 + t.sw * 32 + t.w * 64 + t.nw * 128);
}

std::vector<BlobTile> blob_tiles() {
  std::vector<BlobTile> out;
  for (int m = 0; m < 256; ++m) {
    BlobTile t{bool(m & 1), bool(m & 4), bool(m & 16), bool(m & 64), bool(m & 2), bool(m & 8), bool(m & 32), bool(m & 128)};
    if ((t.ne && !(t.n && t.e)) || (t.se && !(t.s && t.e)) || (t.sw && !(t.s && t.w)) || (t.nw && !(t.n && t.w))) continue;
    out.push_back(t);
  }
  return out;
}

TileSet blob_tile_set() {
  std::vector<WangTile> tiles;
  for (const BlobTile& t : blob_tiles()) {
    auto triple = [](bool a, bool m, bool b) { return Colour(4 * a + 2 * m + b); };
    tiles.push_back({triple(t.nw, t.n, t.ne), triple(t.ne, t.e, t.se), triple(t.sw, t.s, t.se), triple(t.nw, t.w, t.sw)});
  }
  return TileSet::wang(tiles, "blob-47", "the 8-neighbour blob set (tilemap/blob_set.hpp)", 8, 8);
}

Image blob_picture(const std::vector<int>& map, int rows, int cols, int px) {
  if (px < 3 || px % 3) throw RequestError("tile_px", "`tile_px` of a blob picture is a multiple of 3");
  if (std::int64_t(rows) * cols * px * px > kMaxImagePixels) throw InputError("the blob picture is too large");
  const std::vector<BlobTile> tiles = blob_tiles();
  const Rgb in{46, 110, 60}, out{222, 214, 180};
  Image img(cols * px, rows * px, out);
  const int q = px / 3;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const BlobTile& t = tiles.at(std::size_t(map[std::size_t(r) * std::size_t(cols) + std::size_t(c)]));
      const bool grid[3][3] = {{t.nw, t.n, t.ne}, {t.w, true, t.e}, {t.sw, t.s, t.se}};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          if (grid[i][j]) img.rect(c * px + j * q, r * px + i * q, c * px + j * q + q - 1, r * px + i * q + q - 1, in);
    }
  return img;
}

}  // namespace tilekit::tilemap
