#include "points/analysis_spectrum.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>

#include "base/error.hpp"
#include "base/fft.hpp"

namespace tilekit::points {

std::size_t periodogram_size(double density, double side, std::size_t cap) {
  const double width = 4 * principal_frequency(density) * side;
  std::size_t m = 16;
  while (double(m) < width && m < cap) m *= 2;
  return m;
}

double principal_frequency(double density) {
  return 1 / (2 * 0.75 * max_poisson_radius(density));
}

void PowerSpectrum::add(const std::vector<double>& xy, double x0, double y0, int threads) {
  std::vector<Point2> pts;
  pts.reserve(xy.size() / 2);
  for (std::size_t i = 0; i + 1 < xy.size(); i += 2) pts.push_back({xy[i], xy[i + 1]});
  add(pts, x0, y0, threads);
}

// Type-1 NUFFT by Gaussian gridding (Greengard and Lee 2004): spread every point with the
// Gaussian g(x) = exp(-x^2 / 4 tau) onto a grid R = 2 times finer than the frequencies, FFT, and
// divide by the Gaussian's Fourier coefficients sqrt(tau / pi) exp(-k^2 tau) per axis.
void PowerSpectrum::add(const std::vector<Point2>& all, double x0, double y0, int threads) {
  const std::size_t m = size, mr = 2 * m;
  constexpr int kSpread = 8;  // grid points each side: error about exp(-3 pi kSpread / 4) = 7e-9
  const double tau = std::numbers::pi * kSpread / (double(m) * double(m) * 2 * 1.5);
  const double h = 2 * std::numbers::pi / double(mr);
  std::vector<Complex> grid(mr * mr);
  std::uint64_t n = 0;
  double gx[2 * kSpread], gy[2 * kSpread];
  for (const Point2& p : all) {
    if (!(p.x >= x0 && p.x < x0 + side && p.y >= y0 && p.y < y0 + side)) continue;
    ++n;
    const double X = 2 * std::numbers::pi * (p.x - x0) / side, Y = 2 * std::numbers::pi * (p.y - y0) / side;
    const long ix = long(std::floor(X / h)), iy = long(std::floor(Y / h));
    for (int t = 0; t < 2 * kSpread; ++t) {
      const double dx = double(ix - kSpread + 1 + t) * h - X, dy = double(iy - kSpread + 1 + t) * h - Y;
      gx[t] = std::exp(-dx * dx / (4 * tau));
      gy[t] = std::exp(-dy * dy / (4 * tau));
    }
    for (int ty = 0; ty < 2 * kSpread; ++ty) {
      const std::size_t row = std::size_t((iy - kSpread + 1 + ty + long(mr)) % long(mr)) * mr;
      for (int tx = 0; tx < 2 * kSpread; ++tx)
        grid[row + std::size_t((ix - kSpread + 1 + tx + long(mr)) % long(mr))] += gx[tx] * gy[ty];
    }
  }
  if (n == 0) throw InputError("the spectrum window holds no points");
  fft2d(grid, mr, threads);
  const double scale = std::numbers::pi / tau / double(mr) / double(mr);
  const int half = int(m / 2);
  for (int ky = -half; ky < half; ++ky)
    for (int kx = -half; kx < half; ++kx) {
      if (kx == 0 && ky == 0) continue;  // the DC peak (N) is left out, as in the thesis' plots
      const Complex f = grid[std::size_t((ky + int(mr)) % int(mr)) * mr + std::size_t((kx + int(mr)) % int(mr))] *
                        (scale * std::exp(double(kx * kx + ky * ky) * tau));
      power[std::size_t(ky + half) * m + std::size_t(kx + half)] =
          (power[std::size_t(ky + half) * m + std::size_t(kx + half)] * double(sets) + std::norm(f) / double(n)) /
          double(sets + 1);
    }
  ++sets;
  points += n;
}

RadialStats radial_stats(const PowerSpectrum& s) {
  const int half = int(s.size / 2);
  std::vector<double> sum(std::size_t(half), 0), sum2(std::size_t(half), 0);
  std::vector<std::uint32_t> cnt(std::size_t(half), 0);
  for (int ky = -half; ky < half; ++ky)
    for (int kx = -half; kx < half; ++kx) {
      const long i = std::lround(std::sqrt(double(kx * kx + ky * ky)));
      if (i < 1 || i >= half) continue;  // annuli wholly inside the square
      const double p = s.at(kx, ky);
      sum[std::size_t(i)] += p;
      sum2[std::size_t(i)] += p * p;
      ++cnt[std::size_t(i)];
    }
  RadialStats r;
  for (int i = 1; i < half; ++i) {
    const double n = cnt[std::size_t(i)], mean = sum[std::size_t(i)] / n;
    const double var = (sum2[std::size_t(i)] - n * mean * mean) / (n - 1);  // eq. (6.5)
    r.frequency.push_back(double(i) / s.side);
    r.power.push_back(mean);
    r.anisotropy_db.push_back(10 * std::log10(std::max(var, 1e-300) / (mean * mean)));  // eq. (6.4)
    r.samples.push_back(cnt[std::size_t(i)]);
  }
  return r;
}

SpectralSummary summarize(const RadialStats& r, double density, double band_lo, double band_hi) {
  SpectralSummary s;
  s.density = density;
  s.principal_frequency = principal_frequency(density);
  s.band_lo = band_lo;
  s.band_hi = band_hi;
  s.max_anisotropy_db = -1e300;
  double sum_a = 0, low = 0;
  int in_band = 0, low_n = 0;
  std::size_t first_high = r.power.size();
  for (std::size_t i = 0; i < r.power.size(); ++i) {
    const double f = r.frequency[i] / s.principal_frequency;
    if (f >= band_lo && f <= band_hi) {
      s.max_anisotropy_db = std::max(s.max_anisotropy_db, r.anisotropy_db[i]);
      sum_a += r.anisotropy_db[i];
      ++in_band;
    }
    if (f < 0.5) low += r.power[i], ++low_n;
    if (first_high == r.power.size() && r.power[i] >= 0.1) first_high = i;
  }
  // No annulus in the band (a periodogram too small for the density): not measured, never a
  // placeholder value (NaN prints as null in JSON).
  if (!in_band) s.max_anisotropy_db = std::numeric_limits<double>::quiet_NaN();
  s.mean_anisotropy_db = in_band ? sum_a / in_band : std::numeric_limits<double>::quiet_NaN();
  s.low_frequency_power = low_n ? low / low_n : 0;
  // Heck et al.: the radial power stays below 0.1 up to the effective Nyquist frequency.
  const double nyquist = first_high == 0 ? 0 : r.frequency[first_high - 1];
  s.effective_nyquist = nyquist / std::sqrt(density);
  double peak = 0;
  for (std::size_t i = first_high; i < r.power.size(); ++i)
    if (r.power[i] > s.oscillations) s.oscillations = r.power[i], peak = r.frequency[i];
  s.peak_frequency = peak / s.principal_frequency;
  return s;
}

}  // namespace tilekit::points
