#include "texture/exemplar.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "base/error.hpp"

namespace tilekit {

namespace {

// `img` repeated k times each way.
Image repeated(const Image& img, int k) {
  Image out(img.width * k, img.height * k, std::vector<std::uint8_t>(img.pixels.size() * std::size_t(k * k)),
            img.channels);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) std::copy_n(img.at(x % img.width, y % img.height), img.channels, out.at(x, y));
  return out;
}

}  // namespace

Exemplar exemplar_from_image(Image image, std::string name, bool tileable) {
  if (image.width < kMinExemplarSide || image.height < kMinExemplarSide)
    throw InputError(fmt::format("{}: the exemplar is {}x{} pixels, too small for texture tiles (at least {}x{})", name,
                                 image.width, image.height, kMinExemplarSide, kMinExemplarSide));
  if (image.channels == 1) {  // the exemplar is RGBA throughout
    Image rgba(image.width, image.height);
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        const std::uint8_t v = image.at(x, y)[0];
        rgba.set(x, y, {v, v, v});
      }
    image = std::move(rgba);
  }
  Exemplar e;
  if (tileable) {
    e.wrap_w = image.width;
    e.wrap_h = image.height;
    // copies enough for a window as large as the torus anywhere on it, and at least 512 pixels
    const int k = std::max(2, (511 + std::min(image.width, image.height)) / std::min(image.width, image.height));
    image = repeated(image, k);
  }
  e.image = std::move(image);
  e.name = std::move(name);
  double sum = 0, steps = 0;
  std::size_t pairs = 0;
  for (int y = 0; y + 1 < e.height(); ++y)
    for (int x = 0; x + 1 < e.width(); ++x) {
      sum += colour_distance(e.at(x, y), e.at(x + 1, y)) + colour_distance(e.at(x, y), e.at(x, y + 1));
      steps += channel_step(e.at(x, y), e.at(x + 1, y)) + channel_step(e.at(x, y), e.at(x, y + 1));
      pairs += 2;
    }
  e.neighbour_difference = std::max(1.0, sum / double(pairs));  // a flat image still gets a unit
  e.mean_step = std::max(0.5, steps / double(pairs));
  return e;
}

Exemplar load_exemplar(const std::string& path_or_name, bool tileable) {
  std::error_code ec;
  std::string path = path_or_name;
  if (!std::filesystem::exists(path, ec)) {
    const std::string cached = real_texture_path(path_or_name);
    if (!cached.empty()) path = cached, tileable = tileable || is_tileable_real_texture(path_or_name);
  }
  return exemplar_from_image(read_image(path), path, tileable);
}

Image resample_image(const Image& src, int w0, int h0, double sx, double sy, bool torus) {
  const int w = std::max(kMinExemplarSide, int(std::lround(w0 * sx))),
            h = std::max(kMinExemplarSide, int(std::lround(h0 * sy)));
  Image out(w, h, std::vector<std::uint8_t>(std::size_t(w) * std::size_t(h) * std::size_t(src.texel_bytes())),
            src.channels);
  out.depth = src.depth;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double fx = (x + 0.5) * w0 / w - 0.5, fy = (y + 0.5) * h0 / h - 0.5;
      const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
      const double ax = fx - x0, ay = fy - y0;
      auto texel = [&](int xx, int yy, int c) {
        xx = torus ? (xx % w0 + w0) % w0 : std::clamp(xx, 0, w0 - 1);
        yy = torus ? (yy % h0 + h0) % h0 : std::clamp(yy, 0, h0 - 1);
        return src.value(xx, yy, c);
      };
      for (int c = 0; c < src.channels; ++c) {
        const double v = (1 - ay) * ((1 - ax) * texel(x0, y0, c) + ax * texel(x0 + 1, y0, c)) +
                         ay * ((1 - ax) * texel(x0, y0 + 1, c) + ax * texel(x0 + 1, y0 + 1, c));
        out.set_value(x, y, c, v);  // rounded and clamped to 0..max at 8 and 16 bits
      }
    }
  return out;
}

Exemplar resample_exemplar(const Exemplar& e, double sx, double sy) {
  // the torus resamples as a torus; a plain exemplar loses no more than a pixel at its edges
  const int w0 = e.wrap_w ? e.wrap_w : e.width(), h0 = e.wrap_h ? e.wrap_h : e.height();
  return exemplar_from_image(resample_image(e.image, w0, h0, sx, sy, e.wrap_w > 0), e.name, e.wrap_w > 0);
}

namespace {

// Lines (rows, or columns) apart over which an autocorrelation along one axis is summed: every
// line up to kAutocorrelationLines of them, evenly spaced beyond (every fourth row of a 2048²
// exemplar), so that the period and the feature size cost O(side²) per lag, not more.
constexpr int kAutocorrelationLines = 512;
int line_stride(int lines) {
  return std::max(1, (lines + kAutocorrelationLines - 1) / kAutocorrelationLines);
}

// The mean of (f(x, y) - centre) (f(x + dx, y + dy) - centre) over a w x h field, along x (dy =
// 0) or along y (dx = 0): round the torus along an axis that wraps, else over the pairs inside;
// every line_stride-th line across the lag. 0 without pairs.
double mean_lagged_product(const std::vector<float>& f, int w, int h, bool wrap_x, bool wrap_y, int dx, int dy,
                           double centre = 0) {
  const int sx = line_stride(w), sy = line_stride(h);
  double sum = 0;
  std::size_t pairs = 0;
  for (int y = 0; y < (wrap_y ? h : h - dy); y += dy == 0 ? sy : 1)
    for (int x = 0; x < (wrap_x ? w : w - dx); x += dx == 0 ? sx : 1, ++pairs)
      sum += (double(f[std::size_t(y) * std::size_t(w) + std::size_t(x)]) - centre) *
             (double(f[std::size_t((y + dy) % h) * std::size_t(w) + std::size_t((x + dx) % w)]) - centre);
  return pairs ? sum / double(pairs) : 0.0;
}

// The exemplar's luminance (all of it: on a torus the copies too), smoothed by a Gaussian of
// `sigma` pixels (none at 0; the image's edges clamped, the torus' copies wrap it).
std::vector<float> smoothed_luma(const Exemplar& e, double sigma) {
  const int W = e.width(), H = e.height();
  std::vector<float> l(std::size_t(W) * std::size_t(H));
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) l[std::size_t(y) * std::size_t(W) + std::size_t(x)] = luma(e.at(x, y));
  if (sigma <= 0) return l;
  const int radius = int(std::ceil(3 * sigma));
  std::vector<float> k(std::size_t(2 * radius + 1));
  float total = 0;
  for (int i = -radius; i <= radius; ++i)
    total += k[std::size_t(i + radius)] = float(std::exp(-0.5 * i * i / (sigma * sigma)));
  for (float& v : k) v /= total;
  std::vector<float> t(l.size());
  for (int y = 0; y < H; ++y)  // along x, then along y
    for (int x = 0; x < W; ++x) {
      float sum = 0;
      for (int i = -radius; i <= radius; ++i)
        sum +=
            k[std::size_t(i + radius)] * l[std::size_t(y) * std::size_t(W) + std::size_t(std::clamp(x + i, 0, W - 1))];
      t[std::size_t(y) * std::size_t(W) + std::size_t(x)] = sum;
    }
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      float sum = 0;
      for (int i = -radius; i <= radius; ++i)
        sum +=
            k[std::size_t(i + radius)] * t[std::size_t(std::clamp(y + i, 0, H - 1)) * std::size_t(W) + std::size_t(x)];
      l[std::size_t(y) * std::size_t(W) + std::size_t(x)] = sum;
    }
  return l;
}

}  // namespace

ExemplarPeriod period_at_scale(const Exemplar& e, double sigma) {
  const int w = e.wrap_w ? e.wrap_w : e.width(), h = e.wrap_h ? e.wrap_h : e.height();
  const int W = e.width(), H = e.height();
  const std::vector<float> l = smoothed_luma(e, sigma);
  // a period spans at least kPeriodSpan smoothing widths: shorter ones are the grain's to keep
  const int shortest = std::max(6, int(std::ceil(kPeriodSpan * sigma)));
  const auto at = [&](int x, int y) { return l[std::size_t(y) * std::size_t(W) + std::size_t(x)]; };
  std::vector<float> g(std::size_t(w) * std::size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float c = at(x, y);  // the torus' last column and row step onto its first ones
      const float dx = at(std::min(x + 1, W - 1), y) - c, dy = at(x, std::min(y + 1, H - 1)) - c;
      g[std::size_t(y) * std::size_t(w) + std::size_t(x)] = std::hypot(dx, dy);
    }
  double mean = 0, var = 0;
  for (float v : g) mean += v;
  mean /= double(g.size());
  for (float v : g) var += (v - mean) * (v - mean);
  ExemplarPeriod p;
  if (var <= 0) return p;
  // R(d) along one axis: over the pairs inside the image, or round the torus
  auto r = [&](int dx, int dy) {
    return mean_lagged_product(g, w, h, e.wrap_w > 0, e.wrap_h > 0, dx, dy, mean) / (var / double(g.size()));
  };
  for (int axis = 0; axis < 2; ++axis) {
    const int reach = (axis == 0 ? w : h) / 3;
    std::vector<double> v(std::size_t(reach) + 2);
    for (int d = 1; d <= reach + 1; ++d) v[std::size_t(d)] = axis == 0 ? r(d, 0) : r(0, d);
    // the local maxima far enough above the lowest value before them; the shortest of those
    // within 3 % of the highest (whole multiples of a period rise as high as the period)
    std::vector<std::pair<int, double>> peaks;
    double lowest = 1;
    for (int d = 1; d <= reach; ++d) {
      const double here = v[std::size_t(d)];
      if (d >= shortest && here >= v[std::size_t(d - 1)] && here >= v[std::size_t(d + 1)] && here > lowest) {
        const double rise = (here - lowest) / (1 - lowest);
        if (rise >= kPeriodProminence)
          peaks.push_back({d, rise});
        else
          (axis == 0 ? p.weak_x : p.weak_y) = std::max(axis == 0 ? p.weak_x : p.weak_y, rise);
      }
      lowest = std::min(lowest, here);
    }
    double top = 0;
    for (const auto& [d, rise] : peaks) top = std::max(top, rise);
    int best = 0;
    double strength = 0;
    for (const auto& [d, rise] : peaks)
      if (rise >= 0.97 * top) {
        best = d, strength = rise;
        break;
      }
    double period = best;
    if (best > 0) {  // the peak between lags, by a parabola through it and its neighbours
      const double a = v[std::size_t(best) - 1], b = v[std::size_t(best)], c = v[std::size_t(best) + 1];
      if (a - 2 * b + c < 0) period += 0.5 * (a - c) / (a - 2 * b + c);
      const int wrap = axis == 0 ? e.wrap_w : e.wrap_h;  // a torus holds a whole number of periods
      if (wrap) period = wrap / std::max(1.0, std::round(wrap / period));
    }
    (axis == 0 ? p.x : p.y) = period;
    (axis == 0 ? p.strength_x : p.strength_y) = strength;
  }
  return p;
}

ExemplarPeriod dominant_period(const Exemplar& e) {
  ExemplarPeriod p = period_at_scale(e, 0);
  for (const double sigma : kPeriodScales) {
    if (p.x > 0 && p.y > 0) break;
    const ExemplarPeriod coarse = period_at_scale(e, sigma);
    if (p.x == 0 && coarse.x > 0) p.x = coarse.x, p.strength_x = coarse.strength_x;
    if (p.y == 0 && coarse.y > 0) p.y = coarse.y, p.strength_y = coarse.strength_y;
  }
  return p;
}

TileSizeChoice choose_tile_size(const Exemplar& e, const ExemplarPeriod& period) {
  TileSizeChoice c;
  const int w = e.wrap_w ? e.wrap_w : e.width(), h = e.wrap_h ? e.wrap_h : e.height();
  const int most = std::max(16, std::min({512, e.width() - 16, e.height() - 16}) / 2 * 2);
  const auto clamp = [&](int t) { return std::clamp(t / 2 * 2, std::min(64, most), most); };
  c.period = std::max(period.x, period.y);
  if (c.period > 0) {
    const double k = std::max(1.0, std::ceil(kPeriodicTilePx / c.period - 1e-9));
    c.tile_px = clamp(int(std::lround(k * c.period)));
    c.reason = fmt::format("period {:.1f} px: {} px tiles hold {:g} whole period{}", c.period, c.tile_px, k,
                           k == 1 ? "" : "s");
    return c;
  }
  // the luminance's autocorrelation along x and y (the torus, or the pairs inside the image)
  std::vector<float> l(std::size_t(w) * std::size_t(h));
  double mean = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) mean += l[std::size_t(y) * std::size_t(w) + std::size_t(x)] = luma(e.at(x, y));
  mean /= double(l.size());
  double var = 0;
  for (float& v : l) v = float(v - mean), var += double(v) * v;
  var /= double(l.size());
  c.feature_px = std::min(w, h) / 2.0;
  if (var > 0) {
    auto r = [&](int dx, int dy) { return mean_lagged_product(l, w, h, e.wrap_w > 0, e.wrap_h > 0, dx, dy) / var; };
    double before = 1, lowest = 1;
    int lowest_at = std::min(w, h) / 2;
    bool found = false;
    for (int d = 1; d < std::min(w, h) / 2; ++d) {
      const double here = (r(d, 0) + r(0, d)) / 2;
      if (here <= kFeatureCorrelation) {  // between lags, linearly
        c.feature_px = d - 1 + (before - kFeatureCorrelation) / std::max(1e-9, before - here);
        found = true;
        break;
      }
      if (here < lowest) lowest = here, lowest_at = d;
      before = here;
    }
    if (!found) c.feature_px = lowest_at;  // never that low (slow shading): where it is lowest
  }
  c.tile_px = clamp(int(std::ceil(2 * c.feature_px / 32)) * 32);
  c.reason = fmt::format(
      "features up to about {:.0f} px across (where the luminance autocorrelation falls to {:g}): "
      "{} px tiles{}",
      c.feature_px, kFeatureCorrelation, c.tile_px,
      c.tile_px >= int(std::ceil(2 * c.feature_px)) ? " hold two across" : " (the most this exemplar allows)");
  return c;
}

std::string texture_cache_dir() {
  if (const char* dir = std::getenv("TILEKIT_TEXTURES"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::string(xdg) + "/tilekit/textures";
  const char* home = std::getenv("HOME");
  return std::string(home && *home ? home : ".") + "/.cache/tilekit/textures";
}

const std::vector<RealTexture>& real_textures() {
  static const std::vector<RealTexture> list = {
      {"brick", false},      {"grass", false},  {"gravel", false},  {"gimp-stone33", true},
      {"gimp-walnut", true}, {"oa-dirt", true}, {"oa-brick", true}, {"oa-rock", true},
  };
  return list;
}

bool is_tileable_real_texture(const std::string& name) {
  for (const RealTexture& t : real_textures())
    if (t.name == name) return t.tileable;
  return false;
}

std::string real_texture_path(const std::string& name) {
  if (name.empty() || name.find('/') != std::string::npos) return "";
  std::error_code ec;
  for (const char* ext : {".png", ".jpg", ".tga", ".ppm"}) {
    const std::string path = texture_cache_dir() + "/" + name + ext;
    if (std::filesystem::is_regular_file(path, ec)) return path;
  }
  return "";
}

}  // namespace tilekit
