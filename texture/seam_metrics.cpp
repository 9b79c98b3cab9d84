#include "texture/seam_metrics.hpp"

#include <algorithm>
#include <cassert>
#include <cstdlib>

namespace tilekit {

SeamStatistics seam_statistics(const Image& img, int tile_px, const std::vector<std::uint32_t>* src, int x0, int y0) {
  SeamStatistics s;
  double border = 0, interior = 0, cut = 0, same = 0;
  std::size_t interior_pairs = 0, same_pairs = 0;
  const int ch = img.channels == 1 ? 0 : 1;  // grey images: the one channel three times
  auto step = [&](const std::uint8_t* p, const std::uint8_t* q) {
    return (std::abs(int(p[0]) - int(q[0])) + std::abs(int(p[ch]) - int(q[ch])) +
            std::abs(int(p[2 * ch]) - int(q[2 * ch]))) /
           3.0;
  };
  auto on_border = [&](int v, int origin) { return ((v - origin) % tile_px + tile_px) % tile_px == 0; };
  auto pair = [&](int x0, int y0, int x1, int y1, bool across) {
    const double d = step(img.at(x0, y0), img.at(x1, y1));
    (across ? border : interior) += d;
    ++(across ? s.border_pairs : interior_pairs);
    if (src) {
      const bool differ = (*src)[std::size_t(y0) * std::size_t(img.width) + std::size_t(x0)] !=
                          (*src)[std::size_t(y1) * std::size_t(img.width) + std::size_t(x1)];
      (differ ? cut : same) += d;
      ++(differ ? s.cut_pairs : same_pairs);
    }
  };
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      if (x + 1 < img.width) pair(x, y, x + 1, y, on_border(x + 1, x0));
      if (y + 1 < img.height) pair(x, y, x, y + 1, on_border(y + 1, y0));
    }
  s.border_step = s.border_pairs ? border / double(s.border_pairs) : 0;
  s.interior_step = interior_pairs ? interior / double(interior_pairs) : 0;
  s.seam_ratio = s.interior_step > 0 ? s.border_step / s.interior_step : 0;
  s.cut_step = s.cut_pairs ? cut / double(s.cut_pairs) : 0;
  s.same_source_step = same_pairs ? same / double(same_pairs) : 0;
  s.cut_ratio = s.same_source_step > 0 ? s.cut_step / s.same_source_step : 0;
  return s;
}

Image stitch_tiles(const TextureTileSet& set, const Tiling& t, std::vector<std::uint32_t>* sources) {
  const int n = set.tile_px;
  Image img(t.cols * n, t.rows * n, Rgb{0, 0, 0});
  if (sources) sources->assign(std::size_t(img.width) * std::size_t(img.height), 0);
  for (int r = 0; r < t.rows; ++r)
    for (int c = 0; c < t.cols; ++c) {
      const TileIndex tile = t.at(r, c);
      assert(tile < set.tiles.size());
      for (int y = 0; y < n; ++y) {
        std::copy_n(set.tiles[tile].at(0, y), std::size_t(n) * 4, img.at(c * n, r * n + y));
        if (sources && tile < set.sources.size())
          for (int x = 0; x < n; ++x) {
            const std::uint32_t id = set.sources[tile][std::size_t(y) * std::size_t(n) + std::size_t(x)];
            // a sample of one tile is a new sample wherever that tile is placed
            (*sources)[std::size_t(r * n + y) * std::size_t(img.width) + std::size_t(c * n + x)] =
                id < set.shared_sources ? id : set.shared_sources + std::uint32_t(r * t.cols + c);
          }
      }
    }
  return img;
}

}  // namespace tilekit
