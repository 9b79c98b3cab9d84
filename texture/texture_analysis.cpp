// The measures of texture/texture_analysis.hpp; their definitions are in texture/README.md.
#include "texture/texture_analysis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "base/error.hpp"
#include "base/fft.hpp"
#include "base/parallel.hpp"
#include "texture/exemplar.hpp"
#include "texture/seam_metrics.hpp"

namespace tilekit {

namespace {

using Vec = std::array<double, 2>;

double norm(const Vec& v) {
  return std::hypot(v[0], v[1]);
}

// Chebyshev distance from lag (x, y) to the nearest lattice vector i a + j b (the offset plays no
// part in lags).
double distance_to_lattice(const Lattice& l, double x, double y) {
  const double det = l.a[0] * l.b[1] - l.a[1] * l.b[0];
  const double i = (x * l.b[1] - y * l.b[0]) / det, j = (l.a[0] * y - l.a[1] * x) / det;
  double best = 1e300;
  for (double di = std::floor(i) - 1; di <= std::ceil(i) + 1; ++di)
    for (double dj = std::floor(j) - 1; dj <= std::ceil(j) + 1; ++dj) {
      const double px = di * l.a[0] + dj * l.b[0], py = di * l.a[1] + dj * l.b[1];
      best = std::min(best, std::max(std::abs(x - px), std::abs(y - py)));
    }
  return best;
}

struct LumStats {
  double mean = 0, var = 0;
};
LumStats lum_stats(const std::vector<float>& lum) {
  LumStats s;
  for (float v : lum) s.mean += v;
  s.mean /= double(lum.size());
  for (float v : lum) s.var += (v - s.mean) * (v - s.mean);
  s.var /= double(lum.size());
  return s;
}

double correlation(const std::vector<float>& lum, int w, int h, const LumStats& st, int dx, int dy) {
  if (std::abs(dx) >= w || std::abs(dy) >= h || st.var <= 0) return 0;
  const int xa = std::max(0, -dx), xb = std::min(w, w - dx), ya = std::max(0, -dy), yb = std::min(h, h - dy);
  const float m = float(st.mean);
  double sum = 0;
  for (int y = ya; y < yb; ++y) {
    const float* p = &lum[std::size_t(y) * std::size_t(w)];
    const float* q = &lum[std::size_t(y + dy) * std::size_t(w)] + dx;
    float row = 0;
    for (int x = xa; x < xb; ++x) row += (p[x] - m) * (q[x] - m);
    sum += row;
  }
  return sum / (double(xb - xa) * double(yb - ya)) / st.var;
}

// R at a lag that need not be integer: the largest R over the integer lags around it (a lattice
// of fractional spacing repeats content at the nearest pixel, one way or the other).
LagValue lag_value(const std::vector<float>& lum, int w, int h, const LumStats& st, const Vec& d) {
  auto around = [](double v) {
    return v == std::floor(v) ? std::vector<int>{int(v)} : std::vector<int>{int(std::floor(v)), int(std::ceil(v))};
  };
  LagValue best{0, 0, -2};
  for (int x : around(d[0]))
    for (int y : around(d[1])) {
      const double r = correlation(lum, w, h, st, x, y);
      if (r > best.r) best = {x, y, r};
    }
  return best;
}

RadialSpectrum radial_spectrum(const std::vector<float>& lum, int w, int h, const Lattice& l, int threads) {
  std::size_t n = 1;
  while (n * 2 <= std::size_t(std::min(w, h))) n *= 2;
  const int x0 = (w - int(n)) / 2, y0 = (h - int(n)) / 2;  // the centred power-of-two square
  double mean = 0, var = 0;
  for (std::size_t y = 0; y < n; ++y)
    for (std::size_t x = 0; x < n; ++x) mean += lum[(std::size_t(y0) + y) * std::size_t(w) + std::size_t(x0) + x];
  mean /= double(n * n);
  std::vector<Complex> grid(n * n);
  std::vector<double> hann(n);
  for (std::size_t i = 0; i < n; ++i) hann[i] = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * double(i) / double(n));
  double wsum = 0;
  for (std::size_t y = 0; y < n; ++y)
    for (std::size_t x = 0; x < n; ++x) {
      const double v = lum[(std::size_t(y0) + y) * std::size_t(w) + std::size_t(x0) + x] - mean, wt = hann[x] * hann[y];
      var += v * v;
      wsum += wt * wt;
      grid[y * n + x] = v * wt;
    }
  var = std::max(var / double(n * n), 1e-12);
  fft2d(grid, n, threads);
  auto power = [&](long kx, long ky) {
    const long m = long(n);
    return std::norm(grid[std::size_t((ky % m + m) % m) * n + std::size_t((kx % m + m) % m)]) / (wsum * var);
  };
  RadialSpectrum s;
  const long half = long(n / 2);
  std::vector<double> sum(std::size_t(half) + 1, 0.0);
  std::vector<std::size_t> count(sum.size(), 0);
  for (long ky = -half + 1; ky <= half; ++ky)
    for (long kx = -half + 1; kx <= half; ++kx) {
      const long r = std::lround(std::hypot(double(kx), double(ky)));
      if (r > half) continue;
      sum[std::size_t(r)] += power(kx, ky);
      ++count[std::size_t(r)];
    }
  for (std::size_t r = 0; r < sum.size(); ++r) {
    s.frequency.push_back(double(r) / double(n));
    s.power.push_back(count[r] ? sum[r] / double(count[r]) : 0.0);
  }
  // The reciprocal basis: a* . a = 1, a* . b = 0, b* . a = 0, b* . b = 1. The spectrum is looked
  // at up to 8 times its shortest vector (the lattice's low harmonics, where repetition shows).
  const double det = l.a[0] * l.b[1] - l.a[1] * l.b[0];
  const Vec as{l.b[1] / det, -l.b[0] / det}, bs{-l.a[1] / det, l.a[0] / det};
  s.max_frequency = std::min(0.5, 8 * std::min(norm(as), norm(bs)));
  std::set<long> marks;  // the harmonics k a*, k b*, k (a* + b*), in units of 1e-9 cycles per pixel
  for (const Vec& v : {as, bs, Vec{as[0] + bs[0], as[1] + bs[1]}})
    for (int k = 1; k * norm(v) <= s.max_frequency; ++k) marks.insert(std::lround(k * norm(v) * 1e9));
  for (long f : marks) s.lattice_frequencies.push_back(double(f) * 1e-9);
  const int reach = int(std::ceil(s.max_frequency / std::min(norm(as), norm(bs)))) + 1;
  double peak_db = 0;
  int peaks = 0;
  for (int i = -reach; i <= reach; ++i)
    for (int j = 0; j <= reach; ++j) {
      if (j == 0 && i <= 0) continue;  // one of each pair +-f (the spectrum is symmetric)
      const Vec f{i * as[0] + j * bs[0], i * as[1] + j * bs[1]};
      const double r = norm(f);
      if (r > s.max_frequency) continue;
      const double kx = f[0] * double(n), ky = f[1] * double(n);
      double p = 0;  // at a fractional bin, the largest of the four around it
      for (double bx : {std::floor(kx), std::ceil(kx)})
        for (double by : {std::floor(ky), std::ceil(ky)}) p = std::max(p, power(long(bx), long(by)));
      const double ring = s.power[std::size_t(std::min<long>(half, std::lround(r * double(n))))];
      if (ring > 0 && p > 0) peak_db += 10 * std::log10(p / ring), ++peaks;
    }
  s.lattice_peak_db = peaks ? peak_db / peaks : 0.0;
  return s;
}

}  // namespace

bool Lattice::is_square_grid() const {
  return a[1] == 0 && b[0] == 0 && a[0] == b[1] && a[0] >= 1 && a[0] == std::floor(a[0]) &&
         offset[0] == std::floor(offset[0]) && offset[1] == std::floor(offset[1]);
}

double Lattice::spacing() const {
  return std::max(norm(a), norm(b));
}

std::vector<float> luminance(const Image& img) {
  std::vector<float> lum(std::size_t(img.width) * std::size_t(img.height));
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const std::uint8_t* p = img.at(x, y);
      lum[std::size_t(y) * std::size_t(img.width) + std::size_t(x)] = img.channels == 1 ? float(p[0]) : luma(p);
    }
  return lum;
}

double autocorrelation(const std::vector<float>& lum, int w, int h, int dx, int dy) {
  return correlation(lum, w, h, lum_stats(lum), dx, dy);
}

std::vector<std::array<int, 2>> reference_lags(const Lattice& l) {
  std::set<std::array<int, 2>> lags;
  for (const Vec& v : {l.a, l.b, Vec{l.a[0] + l.b[0], l.a[1] + l.b[1]}}) {
    const double major = std::max(std::abs(v[0]), std::abs(v[1]));
    for (double k = std::ceil(major / 2); k <= std::floor(2 * major); ++k) {
      const double t = k / major;
      const std::array<int, 2> d{int(std::lround(t * v[0])), int(std::lround(t * v[1]))};
      if (distance_to_lattice(l, d[0], d[1]) > 3) lags.insert(d);
    }
  }
  return {lags.begin(), lags.end()};
}

std::array<double, 3> histogram_emd(const Image& a, const Image& b) {
  std::array<double, 3> emd{};
  for (int c = 0; c < 3; ++c) {
    std::array<double, 256> ha{}, hb{};
    auto fill = [c](const Image& img, std::array<double, 256>& hist) {
      const std::size_t px = std::size_t(img.width) * std::size_t(img.height);
      for (std::size_t i = 0; i < px; ++i)
        hist[img.pixels[i * std::size_t(img.channels) + (img.channels == 1 ? 0 : c)]] += 1;
      for (double& v : hist) v /= double(px);
    };
    fill(a, ha);
    fill(b, hb);
    double ca = 0, cb = 0;
    for (int k = 0; k < 256; ++k) {
      ca += ha[std::size_t(k)];
      cb += hb[std::size_t(k)];
      emd[std::size_t(c)] += std::abs(ca - cb);
    }
  }
  return emd;
}

std::vector<std::uint32_t> label_ids(const Image& labels) {
  std::vector<std::uint32_t> ids(std::size_t(labels.width) * std::size_t(labels.height));
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const std::uint8_t* p = labels.pixels.data() + i * std::size_t(labels.channels);
    ids[i] = labels.channels == 1 ? p[0] : std::uint32_t(p[0]) << 16 | std::uint32_t(p[1]) << 8 | p[2];
  }
  return ids;
}

TextureAnalysis analyze_texture(const Image& img, const Lattice& l, const Image* exemplar, const Image* labels,
                                int threads) {
  const double det = l.a[0] * l.b[1] - l.a[1] * l.b[0];
  if (!(std::abs(det) >= 4) || !std::isfinite(det))
    throw InputError("the lattice is degenerate: its basis vectors must span at least 4 square pixels");
  const int need = int(std::ceil(4 * l.spacing()));
  if (img.width < need || img.height < need)
    throw InputError(
        fmt::format("a {}x{} image is too small for a lattice of spacing {:g} px: the lags up to twice "
                    "the spacing need at least {}x{} pixels",
                    img.width, img.height, l.spacing(), need, need));
  if (labels && (labels->width != img.width || labels->height != img.height))
    throw InputError(fmt::format("the labels are {}x{} pixels but the image is {}x{}", labels->width, labels->height,
                                 img.width, img.height));
  TextureAnalysis r;
  r.width = img.width;
  r.height = img.height;
  r.lattice = l;
  const std::vector<float> lum = luminance(img);
  const LumStats st = lum_stats(lum);
  const std::vector<Vec> lattice_lags = {
      l.a, l.b, {l.a[0] + l.b[0], l.a[1] + l.b[1]}, {2 * l.a[0], 2 * l.a[1]}, {2 * l.b[0], 2 * l.b[1]}};
  const std::vector<std::array<int, 2>> ref = reference_lags(l);
  r.lattice_lags.resize(lattice_lags.size());
  std::vector<double> ref_r(ref.size());
  parallel_for(std::int64_t(lattice_lags.size() + ref.size()), threads, [&](std::int64_t k) {
    const std::size_t i = std::size_t(k);
    if (i < lattice_lags.size())
      r.lattice_lags[i] = lag_value(lum, img.width, img.height, st, lattice_lags[i]);
    else
      ref_r[i - lattice_lags.size()] =
          correlation(lum, img.width, img.height, st, ref[i - lattice_lags.size()][0], ref[i - lattice_lags.size()][1]);
  });
  for (const LagValue& v : r.lattice_lags) r.lattice_correlation += v.r / double(r.lattice_lags.size());
  for (double v : ref_r) r.reference_correlation += std::abs(v) / double(ref_r.size());
  r.reference_lags = ref.size();
  r.grid_repetition = r.lattice_correlation - r.reference_correlation;
  if (l.is_square_grid()) {
    r.seam_ratio = seam_statistics(img, int(l.a[0]), nullptr, int(l.offset[0]), int(l.offset[1])).seam_ratio;
    const LineContinuity c = line_continuity(img, int(l.a[0]), int(l.offset[0]), int(l.offset[1]));
    r.line_continuity = c.ratio, r.border_continuity = c.border, r.interior_continuity = c.interior;
  }
  if (labels) {
    const std::vector<std::uint32_t> ids = label_ids(*labels);
    r.cut_visibility =
        seam_statistics(img, std::max(img.width, img.height), &ids).cut_ratio;  // any tile size: cuts only
  }
  if (exemplar) {
    r.histogram_emd = histogram_emd(img, *exemplar);
    r.histogram_distance = ((*r.histogram_emd)[0] + (*r.histogram_emd)[1] + (*r.histogram_emd)[2]) / 3;
  }
  r.spectrum = radial_spectrum(lum, img.width, img.height, l, threads);
  return r;
}

Image spectrum_plot(const TextureAnalysis& a, const std::string& title, int width, int height) {
  const Rgb black{0, 0, 0}, grid{225, 225, 225}, curve{20, 90, 200}, mark{210, 50, 40};
  Image img(width, height);
  const double left = 56, right = width - 16, top = 40, bottom = height - 40;
  const std::vector<double>& p = a.spectrum.power;
  double lo = 1e300, hi = -1e300;
  for (std::size_t i = 1; i < p.size() && a.spectrum.frequency[i] <= a.spectrum.max_frequency; ++i)
    if (p[i] > 0) lo = std::min(lo, 10 * std::log10(p[i])), hi = std::max(hi, 10 * std::log10(p[i]));
  if (lo > hi) lo = -10, hi = 10;
  lo = 10 * std::floor(lo / 10), hi = 10 * std::ceil(hi / 10 + 1e-9);
  if (hi - lo < 20) hi = lo + 20;
  const double fmax = a.spectrum.max_frequency;
  const auto X = [&](double f) { return left + (right - left) * f / fmax; };
  const auto Y = [&](double db) { return bottom - (bottom - top) * (db - lo) / (hi - lo); };
  const double tick = fmax > 0.25 ? 0.1 : fmax > 0.1 ? 0.02 : 0.01;
  for (double f = 0; f <= fmax + 1e-9; f += tick) {
    img.line(X(f), top, X(f), bottom, grid);
    const std::string label = fmt::format("{:g}", f);
    img.text(int(X(f)) - Image::text_width(label) / 2, int(bottom) + 6, label, black);
  }
  for (double v = lo; v <= hi + 1e-9; v += 10) {
    img.line(left, Y(v), right, Y(v), grid);
    const std::string label = fmt::format("{:g}", v);
    img.text(int(left) - 6 - Image::text_width(label), int(Y(v)) - 3, label, black);
  }
  for (double f : a.spectrum.lattice_frequencies) img.line(X(f), top, X(f), bottom, mark);
  img.line(left, top, left, bottom, black);
  img.line(left, bottom, right, bottom, black);
  for (std::size_t i = 2; i < p.size() && a.spectrum.frequency[i] <= fmax; ++i)
    if (p[i - 1] > 0 && p[i] > 0)
      img.line(X(a.spectrum.frequency[i - 1]), Y(10 * std::log10(p[i - 1])), X(a.spectrum.frequency[i]),
               Y(10 * std::log10(p[i])), curve, 2);
  img.text(int(left), 8, title, black);
  img.text(
      int(left), 22,
      fmt::format("GRID REPETITION {:.3f}   LATTICE PEAK {:+.1f} DB", a.grid_repetition, a.spectrum.lattice_peak_db),
      black);
  img.line(right - 190, 12, right - 170, 12, curve, 2);
  img.text(int(right) - 164, 9, "POWER (DB)", black);
  img.line(right - 190, 26, right - 170, 26, mark);
  img.text(int(right) - 164, 23, "LATTICE FREQUENCIES", black);
  const std::string xlabel = "FREQUENCY (CYCLES PER PIXEL)";
  img.text(int((left + right) / 2) - Image::text_width(xlabel) / 2, height - 16, xlabel, black);
  return img;
}

LineContinuity line_continuity(const Image& img, int tile, int x0, int y0) {
  const std::vector<float> lum = luminance(img);
  const int w = img.width, h = img.height;
  const auto L = [&](int x, int y) { return double(lum[std::size_t(y) * std::size_t(w) + std::size_t(x)]); };
  // corr over t of the across-gradient on the two sides of the line at position p (between p-1 and p)
  const auto corr = [&](int p, bool vertical) {
    const int n = vertical ? h : w;
    double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    int count = 0;
    for (int t = 1; t + 1 < n; ++t) {
      const double a =
          vertical ? std::abs(L(p - 1, t + 1) - L(p - 1, t - 1)) : std::abs(L(t + 1, p - 1) - L(t - 1, p - 1));
      const double b = vertical ? std::abs(L(p, t + 1) - L(p, t - 1)) : std::abs(L(t + 1, p) - L(t - 1, p));
      sa += a, sb += b, saa += a * a, sbb += b * b, sab += a * b, ++count;
    }
    const double va = saa - sa * sa / count, vb = sbb - sb * sb / count;
    return va > 0 && vb > 0 ? (sab - sa * sb / count) / std::sqrt(va * vb) : 0.0;
  };
  LineContinuity c;
  for (int pass = 0; pass < 2; ++pass) {  // 0: the lattice's lines, 1: halfway between
    double sum = 0;
    int lines = 0;
    for (int vertical = 0; vertical < 2; ++vertical) {
      const int n = vertical ? w : h, start = ((vertical ? x0 : y0) + pass * (tile / 2)) % tile;
      for (int p = (start + tile) % tile; p < n; p += tile)
        if (p >= 1 && p + 1 < n) sum += corr(p, vertical != 0), ++lines;
    }
    (pass == 0 ? c.border : c.interior) = lines ? sum / lines : 0;
  }
  c.ratio = c.interior > 0 ? c.border / c.interior : 0;
  return c;
}

}  // namespace tilekit
