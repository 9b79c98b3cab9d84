#include "atlas/atlas_image.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <numbers>

#include "base/error.hpp"
#include "tilesets/tile_set_io.hpp"


namespace tilekit {

std::array<std::uint8_t, 3> palette_colour(std::uint32_t k, std::uint32_t colours) {
  // HSV with evenly spaced hues, s = 0.7, v = 0.95.
  const double h = 6.0 * double(k) / double(std::max<std::uint32_t>(colours, 1)), s = 0.7, v = 0.95;
  const int sector = int(h) % 6;
  const double f = h - std::floor(h), p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  double r = v, g = t, b = p;
  switch (sector) {
    case 1: r = q, g = v, b = p; break;
    case 2: r = p, g = v, b = t; break;
    case 3: r = p, g = q, b = v; break;
    case 4: r = t, g = p, b = v; break;
    case 5: r = v, g = p, b = q; break;
    default: break;
  }
  return {std::uint8_t(std::lround(r * 255)), std::uint8_t(std::lround(g * 255)), std::uint8_t(std::lround(b * 255))};
}

namespace {

double smooth(double x) { return x * x * (3 - 2 * x); }

struct RgbF {
  double r = 0, g = 0, b = 0;
};
RgbF rgb_of(std::uint32_t k, std::uint32_t colours) {
  auto c = palette_colour(k, colours);
  return {double(c[0]), double(c[1]), double(c[2])};
}

}  // namespace

Image generated_tile(TileKind kind, std::uint32_t colours, TileIndex tile, int size) {
  Image img{size, size, std::vector<std::uint8_t>(std::size_t(size) * std::size_t(size) * 4)};
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const double u = (x + 0.5) / size, v = (y + 0.5) / size;  // v downwards: 0 = north edge
      RgbF out;
      if (kind == TileKind::Corner) {
        const CornerTile t = corner_tile(tile, colours);  // thesis eq. (2.6)
        const RgbF nw = rgb_of(t.nw, colours), ne = rgb_of(t.ne, colours), sw = rgb_of(t.sw, colours),
                  se = rgb_of(t.se, colours);
        const double a = smooth(u), b = smooth(v);
        auto mix = [&](double RgbF::*ch) {
          return (1 - b) * ((1 - a) * nw.*ch + a * ne.*ch) + b * ((1 - a) * sw.*ch + a * se.*ch);
        };
        out = {mix(&RgbF::r), mix(&RgbF::g), mix(&RgbF::b)};
      } else {
        const WangTile t = wang_tile(tile, colours);  // thesis eq. (2.3)
        // Each edge's weight is 1 in its middle and 0 at its end points and on the other edges.
        const double bu = std::sin(std::numbers::pi * u), bv = std::sin(std::numbers::pi * v);
        double wn = bu * (1 - v) * (1 - v), ws = bu * v * v, ww = bv * (1 - u) * (1 - u), we = bv * u * u;
        const double sum = wn + ws + ww + we;
        if (sum > 1) wn /= sum, ws /= sum, ww /= sum, we /= sum;
        const double grey = 1 - (wn + ws + ww + we);
        const RgbF n = rgb_of(t.n, colours), s = rgb_of(t.s, colours), w = rgb_of(t.w, colours), e = rgb_of(t.e, colours);
        auto mix = [&](double RgbF::*ch) { return wn * n.*ch + ws * s.*ch + ww * w.*ch + we * e.*ch + grey * 128.0; };
        out = {mix(&RgbF::r), mix(&RgbF::g), mix(&RgbF::b)};
      }
      std::uint8_t* p = img.at(x, y);
      p[0] = std::uint8_t(std::clamp(std::lround(out.r), 0l, 255l));
      p[1] = std::uint8_t(std::clamp(std::lround(out.g), 0l, 255l));
      p[2] = std::uint8_t(std::clamp(std::lround(out.b), 0l, 255l));
      p[3] = 255;
    }
  return img;
}

namespace {

Image assemble(const AtlasLookup& a, int tile_size, const std::function<const Image&(TileIndex)>& tile_image) {
  // The depth of the tiles (all 8-bit, 16-bit or float: atlas_from_tile_images makes them agree).
  const int depth = a.cells.empty() ? 8 : tile_image(a.cells[0]).depth;
  Image atlas{a.cols * tile_size, a.rows * tile_size,
              std::vector<std::uint8_t>(std::size_t(a.cols) * std::size_t(a.rows) * std::size_t(tile_size) *
                                        std::size_t(tile_size) * 4 * std::size_t(depth / 8))};
  atlas.depth = depth;
  const std::size_t row_bytes = std::size_t(tile_size) * std::size_t(atlas.texel_bytes());
  for (int r = 0; r < a.rows; ++r)
    for (int c = 0; c < a.cols; ++c) {
      const Image& t = tile_image(a.cells[std::size_t(r) * std::size_t(a.cols) + std::size_t(c)]);
      for (int y = 0; y < tile_size; ++y)
        std::copy_n(t.at(0, y), row_bytes, atlas.at(c * tile_size, r * tile_size + y));
    }
  return atlas;
}

}  // namespace

Image atlas_from_generated_tiles(const AtlasLookup& a, int tile_size) {
  if (tile_size < 2 || tile_size > 1024)
    throw RequestError("tile_size", fmt::format("`tile_size` must be 2..1024, got {}", tile_size));
  if (std::uint64_t(a.cols) * a.rows * std::uint64_t(tile_size) * std::uint64_t(tile_size) >
      std::uint64_t(kMaxImagePixels))
    throw RequestError("tile_size",
                       fmt::format("a {}x{} atlas of {}-pixel tiles is more than {} pixels; use a smaller `tile_size`",
                                   a.rows, a.cols, tile_size, kMaxImagePixels));
  std::vector<Image> tiles(a.cells.size());
  for (TileIndex i = 0; i < tiles.size(); ++i) tiles[i] = generated_tile(a.kind, a.colours, i, tile_size);
  return assemble(a, tile_size, [&](TileIndex i) -> const Image& { return tiles[i]; });
}

Image atlas_from_tile_images(const AtlasLookup& a, const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(fmt::format("{}: not a directory of tile images", dir));
  std::map<TileIndex, fs::path> files;
  // Through error codes: an unreadable folder or a link loop is the user's to fix (exit 2).
  fs::directory_iterator it(dir, ec), end;
  if (ec) throw InputError(fmt::format("{}: cannot list the tile images ({})", dir, ec.message()));
  for (; it != end; it.increment(ec)) {
    if (ec) throw InputError(fmt::format("{}: cannot list the tile images ({})", dir, ec.message()));
    const fs::directory_entry& entry = *it;
    const bool regular = entry.is_regular_file(ec);
    if (ec && entry.is_symlink())
      throw InputError(fmt::format("{}: a link that leads nowhere readable ({})", entry.path().string(), ec.message()));
    if (!regular) continue;
    const std::string stem = entry.path().stem().string();
    std::size_t digits = stem.size();
    while (digits > 0 && std::isdigit(static_cast<unsigned char>(stem[digits - 1]))) --digits;
    if (digits == stem.size() || stem.size() - digits > 10) continue;  // no trailing tile index
    const std::uint64_t index = std::stoull(stem.substr(digits));
    if (index >= a.cells.size())
      throw InputError(fmt::format("{}: tile index {} is out of range (the set has {} tiles)", entry.path().string(),
                                   index, a.cells.size()));
    auto [it, fresh] = files.emplace(TileIndex(index), entry.path());
    if (!fresh)
      throw InputError(fmt::format("{} and {} both hold tile {}", it->second.string(), entry.path().string(), index));
  }
  for (TileIndex i = 0; i < a.cells.size(); ++i)
    if (!files.count(i))
      throw InputError(fmt::format("{}: no image for tile {} ({} of {} tiles found; name files by tile index, "
                                   "e.g. {}.png)",
                                   dir, i, files.size(), a.cells.size(), i));
  std::vector<Image> tiles(a.cells.size());
  int size = 0;
  int depth = 8;  // a 16-bit tile makes a 16-bit atlas, a float tile a float one
  for (auto& [index, path] : files) {
    Image img = read_image(path.string(), 4, true);
    depth = std::max(depth, img.depth);
    const int w = img.width, h = img.height;
    if (w != h) throw InputError(fmt::format("{}: tile images must be square, this one is {}x{}", path.string(), w, h));
    if (size == 0) size = w;
    if (std::uint64_t(a.cols) * a.rows * std::uint64_t(w) * std::uint64_t(w) > std::uint64_t(kMaxImagePixels))
      throw InputError(fmt::format("{}: a {}x{} atlas of {}-pixel tiles is more than {} pixels; use smaller tiles",
                                   path.string(), a.rows, a.cols, w, kMaxImagePixels));
    if (w != size)
      throw InputError(fmt::format("{}: {}x{} pixels, but the other tiles are {}x{}", path.string(), w, h, size, size));
    tiles[index] = std::move(img);
  }
  for (Image& t : tiles) t = t.to_depth(depth);
  return assemble(a, size, [&](TileIndex i) -> const Image& { return tiles[i]; });
}

SeamReport measure_seams(const Image& img, int tile_size) {
  SeamReport rep;
  auto step = [&](int x0, int y0, int x1, int y1) {
    const std::uint8_t *p = img.at(x0, y0), *q = img.at(x1, y1);
    int m = 0;
    for (int c = 0; c < 3; ++c) m = std::max(m, std::abs(int(p[c]) - int(q[c])));
    return m;
  };
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const int xr = (x + 1) % img.width, yd = (y + 1) % img.height;  // wrap-around: the atlas is a torus
      const int h = step(x, y, xr, y), v = step(x, y, x, yd);
      int& hs = (x + 1) % tile_size == 0 ? rep.seam_jump : rep.interior_jump;
      hs = std::max(hs, h);
      int& vs = (y + 1) % tile_size == 0 ? rep.seam_jump : rep.interior_jump;
      vs = std::max(vs, v);
    }
  return rep;
}

}  // namespace tilekit
