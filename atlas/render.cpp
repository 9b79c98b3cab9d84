#include "atlas/render.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit::atlas {

namespace {

constexpr int kMaxSide = 8192;  // largest picture side in pixels (an RGB raster of 200 MB)
constexpr int kSamples = 4;     // supersampling per pixel side (PNG)

int auto_tile_px(int rows, int cols, int preferred) {
  const int longest = std::max(rows, cols);
  return std::clamp(2048 / std::max(longest, 1), 4, preferred);
}

int border_px(const Picture& p) {
  return std::max(1, p.tile_px / 24);
}

// Colour of the point (u, v) in [0, 1)^2 of a tile (v grows to the south).
Rgb tile_colour(const PlacedTile& t, double u, double v) {
  if (t.kind == TileKind::Wang) {
    // four triangles from the centre to the edges: N, E, S, W
    const bool below_main = v > u, below_anti = v > 1 - u;
    std::uint32_t c = !below_main && !below_anti ? t.colours[0]  // N
                      : !below_main              ? t.colours[1]  // E
                      : below_anti               ? t.colours[2]  // S
                                                 : t.colours[3];               // W
    return palette_colour(c);
  }
  // corner tile: quarter discs of radius 1/2 at NE, SE, SW, NW
  const double cx[4] = {1, 1, 0, 0}, cy[4] = {0, 1, 1, 0};
  for (int k = 0; k < 4; ++k) {
    const double dx = u - cx[k], dy = v - cy[k];
    if (dx * dx + dy * dy < 0.25) return palette_colour(t.colours[std::size_t(k)]);
  }
  return kCornerBackground;
}

std::vector<int> slot_index(const Picture& p) {
  std::vector<int> slots(std::size_t(p.rows) * std::size_t(p.cols), -1);
  for (std::size_t k = 0; k < p.tiles.size(); ++k)
    slots[std::size_t(p.tiles[k].row) * std::size_t(p.cols) + std::size_t(p.tiles[k].col)] = int(k);
  return slots;
}

void check_size(const Picture& p) {
  if (p.rows < 1 || p.cols < 1) throw InputError("nothing to draw: the picture has no tiles");
  if (p.width() > kMaxSide || p.height() > kMaxSide)
    throw RequestError("tile_size",
                       fmt::format("picture would be {}x{} pixels, more than {} per side; use a smaller `tile_size`",
                                   p.width(), p.height(), kMaxSide));
}

PlacedTile place(TileKind kind, int row, int col, const std::vector<Colour>& file_colours) {
  PlacedTile t{row, col, kind, {}};
  const auto& f = file_colours;  // Wang: n s w e; corner: nw ne sw se
  if (kind == TileKind::Wang)
    t.colours = {f[0], f[3], f[1], f[2]};
  else
    t.colours = {f[1], f[3], f[2], f[0]};
  return t;
}

}  // namespace

Rgb palette_colour(std::uint32_t c) {
  static constexpr Rgb fixed[] = {{228, 40, 36}, {246, 214, 38},  {52, 172, 60},  {52, 200, 216},
                                  {44, 84, 226}, {208, 58, 208},  {244, 140, 36}, {124, 60, 196},
                                  {140, 90, 45}, {246, 154, 200}, {140, 154, 40}, {128, 128, 128}};
  if (c < std::size(fixed)) return fixed[c];
  // further colours: hues spaced by the golden angle, alternating lightness
  const double h = std::fmod(0.1 + 0.6180339887498949 * c, 1.0) * 6.0;
  const double s = 0.75, l = (c % 2) ? 0.45 : 0.62;
  const double ch = (1 - std::abs(2 * l - 1)) * s, x = ch * (1 - std::abs(std::fmod(h, 2.0) - 1)), m = l - ch / 2;
  double r = 0, g = 0, b = 0;
  switch (int(h)) {
    case 0:
      r = ch, g = x;
      break;
    case 1:
      r = x, g = ch;
      break;
    case 2:
      g = ch, b = x;
      break;
    case 3:
      g = x, b = ch;
      break;
    case 4:
      r = x, b = ch;
      break;
    default:
      r = ch, b = x;
      break;
  }
  auto byte = [](double v) { return std::uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255)); };
  return {byte(r + m), byte(g + m), byte(b + m)};
}

std::string hex(Rgb c) {
  return fmt::format("#{:02x}{:02x}{:02x}", c.r, c.g, c.b);
}

Picture draw_tile_set(const TileSet& set, const RenderOptions& opt) {
  Picture p;
  const int n = int(set.size());
  if (n == 0) throw InputError(fmt::format("tile set '{}' is empty: nothing to draw", set.name()));
  p.cols = std::max(1, int(std::ceil(std::sqrt(double(n)))));
  p.rows = (n + p.cols - 1) / p.cols;
  p.tile_px = opt.tile_px > 0 ? opt.tile_px : auto_tile_px(p.rows, p.cols, 48);
  p.gap = std::max(2, p.tile_px / 6);
  p.borders = opt.borders;
  for (int k = 0; k < n; ++k)
    p.tiles.push_back(place(set.kind(), k / p.cols, k % p.cols, set.file_colours(std::size_t(k))));
  check_size(p);
  return p;
}

namespace {

Picture tiling_frame(int rows, int cols, const RenderOptions& opt) {
  Picture p;
  p.rows = rows;
  p.cols = cols;
  p.tile_px = opt.tile_px > 0 ? opt.tile_px : auto_tile_px(p.rows, p.cols, 32);
  p.gap = 0;
  p.borders = opt.borders;
  check_size(p);
  return p;
}

}  // namespace

void check_tiling_picture(int rows, int cols, const RenderOptions& opt) {
  tiling_frame(rows, cols, opt);
}

Picture draw_tiling(const Tiling& t, const RenderOptions& opt) {
  Picture p = tiling_frame(t.rows, t.cols, opt);
  const std::uint32_t ch = t.ch(), cv = t.kind == TileKind::Wang ? t.cv() : t.ch();
  const std::uint64_t limit = std::uint64_t(ch) * ch * cv * cv;
  p.tiles.reserve(t.cells.size());
  for (int r = 0; r < t.rows; ++r)
    for (int c = 0; c < t.cols; ++c) {
      const TileIndex i = t.at(r, c);
      if (i >= limit)
        throw InputError(fmt::format("cell ({},{}): tile index {} is out of range (< {})", r, c, i, limit));
      PlacedTile pt{r, c, t.kind, {}};
      if (t.kind == TileKind::Wang) {
        const WangTile w = wang_tile(i, ch, cv);
        pt.colours = {w.n, w.e, w.s, w.w};
      } else {
        const CornerTile k = corner_tile(i, ch);
        pt.colours = {k.ne, k.se, k.sw, k.nw};
      }
      p.tiles.push_back(pt);
    }
  return p;
}

std::string to_svg(const Picture& p) {
  check_size(p);
  std::set<std::uint32_t> used;
  for (const auto& t : p.tiles) used.insert(t.colours.begin(), t.colours.end());
  std::string s = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" "
      "shape-rendering=\"geometricPrecision\">\n<style>",
      p.width(), p.height());
  for (std::uint32_t c : used) s += fmt::format(".c{}{{fill:{}}}", c, hex(palette_colour(c)));
  s += fmt::format(".bg{{fill:{}}}.bd{{fill:none;stroke:{};stroke-width:{}}}</style>\n", hex(kCornerBackground),
                   hex(kBorder), border_px(p));
  s += fmt::format("<rect width=\"{}\" height=\"{}\" fill=\"{}\"/>\n", p.width(), p.height(), hex(kPaper));
  const int pitch = p.tile_px + p.gap, d = p.tile_px;
  const double r = d / 2.0;
  for (const auto& t : p.tiles) {
    const int x0 = p.gap + t.col * pitch, y0 = p.gap + t.row * pitch, x1 = x0 + d, y1 = y0 + d;
    const double cx = x0 + r, cy = y0 + r;
    if (t.kind == TileKind::Wang) {
      s += fmt::format("<path class=\"c{}\" d=\"M{} {}H{}L{} {}Z\"/>", t.colours[0], x0, y0, x1, cx, cy);  // N
      s += fmt::format("<path class=\"c{}\" d=\"M{} {}V{}L{} {}Z\"/>", t.colours[1], x1, y0, y1, cx, cy);  // E
      s += fmt::format("<path class=\"c{}\" d=\"M{} {}H{}L{} {}Z\"/>", t.colours[2], x1, y1, x0, cx, cy);  // S
      s += fmt::format("<path class=\"c{}\" d=\"M{} {}V{}L{} {}Z\"/>", t.colours[3], x0, y1, y0, cx, cy);  // W
    } else {
      s += fmt::format("<rect class=\"bg\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/>", x0, y0, d, d);
      // quarter discs, each from one edge to the other around its corner (sweep 1, y down)
      s += fmt::format("<path class=\"c{}\" d=\"M{} {}V{}A{} {} 0 0 1 {} {}Z\"/>", t.colours[0], x1, y0, y0 + r, r, r,
                       x1 - r, y0);  // NE
      s += fmt::format("<path class=\"c{}\" d=\"M{} {}H{}A{} {} 0 0 1 {} {}Z\"/>", t.colours[1], x1, y1, x1 - r, r, r,
                       x1, y1 - r);  // SE
      s += fmt::format("<path class=\"c{}\" d=\"M{} {}V{}A{} {} 0 0 1 {} {}Z\"/>", t.colours[2], x0, y1, y1 - r, r, r,
                       x0 + r, y1);  // SW
      s += fmt::format("<path class=\"c{}\" d=\"M{} {}H{}A{} {} 0 0 1 {} {}Z\"/>", t.colours[3], x0, y0, x0 + r, r, r,
                       x0, y0 + r);  // NW
    }
    if (p.borders) {
      const double b = border_px(p) / 2.0;
      s += fmt::format("<rect class=\"bd\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/>", x0 + b, y0 + b, d - 2 * b,
                       d - 2 * b);
    }
    s += '\n';
  }
  s += "</svg>\n";
  return s;
}

std::vector<Rgb> rasterise(const Picture& p) {
  check_size(p);
  const int w = p.width(), h = p.height(), pitch = p.tile_px + p.gap, bw = border_px(p);
  const std::vector<int> slots = slot_index(p);
  std::vector<Rgb> img(std::size_t(w) * std::size_t(h), kPaper);
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      int sum[3] = {0, 0, 0};
      for (int sy = 0; sy < kSamples; ++sy)
        for (int sx = 0; sx < kSamples; ++sx) {
          const double x = px + (sx + 0.5) / kSamples - p.gap, y = py + (sy + 0.5) / kSamples - p.gap;
          Rgb c = kPaper;
          if (x >= 0 && y >= 0) {
            const int col = int(x) / pitch, row = int(y) / pitch;
            const double lx = x - col * pitch, ly = y - row * pitch;
            if (col < p.cols && row < p.rows && lx < p.tile_px && ly < p.tile_px) {
              const int k = slots[std::size_t(row) * std::size_t(p.cols) + std::size_t(col)];
              if (k >= 0) {
                if (p.borders && (lx < bw || ly < bw || lx >= p.tile_px - bw || ly >= p.tile_px - bw))
                  c = kBorder;
                else
                  c = tile_colour(p.tiles[std::size_t(k)], lx / p.tile_px, ly / p.tile_px);
              }
            }
          }
          sum[0] += c.r, sum[1] += c.g, sum[2] += c.b;
        }
      constexpr int n = kSamples * kSamples;
      img[std::size_t(py) * std::size_t(w) + std::size_t(px)] = {
          std::uint8_t((sum[0] + n / 2) / n), std::uint8_t((sum[1] + n / 2) / n), std::uint8_t((sum[2] + n / 2) / n)};
    }
  return img;
}

std::string to_png(const Picture& p) {
  const std::vector<Rgb> rgb = rasterise(p);
  Image img(p.width(), p.height());
  for (std::size_t i = 0; i < rgb.size(); ++i) {
    std::uint8_t* q = &img.pixels[i * 4];
    q[0] = rgb[i].r, q[1] = rgb[i].g, q[2] = rgb[i].b;
  }
  return encode_png(img);
}

bool is_picture_path(const std::string& path) {
  return path.ends_with(".svg") || path.ends_with(".png");
}

void write_picture(const Picture& p, const std::string& path) {
  if (path.ends_with(".svg"))
    write_file_atomic(path, to_svg(p));
  else if (path.ends_with(".png"))
    write_file_atomic(path, to_png(p));
  else
    throw InputError(fmt::format("{}: unknown picture format (expected a .svg or .png file name)", path));
}

}  // namespace tilekit::atlas
