#pragma once
// Spectral analysis of point sets as in thesis sec. 6.2.2 (Ulichney 1987; Lagae and Dutre) and
// the PSA tool of Heck, Schloemer and Deussen:
//  - the periodogram P(k) = |sum_j exp(-2 pi i k . x_j / L)|^2 / N of a set in a square window
//    of side L (thesis eq. 6.1, normalised so that white noise has P = 1), at integer k, computed
//    by a type-1 non-uniform FFT (Gaussian gridding, Greengard and Lee 2004) to about 1e-8;
//  - Bartlett's estimate of the power spectrum: the mean periodogram of K sets (eq. 6.2);
//  - the radially averaged power spectrum (eq. 6.3, annuli one sample wide) and the anisotropy
//    s^2 / P_r^2 in dB (eq. 6.4-6.5; -10 dB is the background for K = 10);
//  - the principal frequency f_p = 1 / (2 * 0.75 r_max) and the resolution of eq. 6.6;
//  - the effective Nyquist frequency (the largest frequency below which the radial power stays
//    under 0.1) and the oscillations (the largest radial power above it), after Heck et al.
#include <cstdint>
#include <vector>

#include "points/geometry.hpp"

namespace tilekit::points {

// Frequencies per axis for sets of `density` points per unit area in a window of side `side`:
// the next power of two of 4 f_p side (thesis eq. 6.6: twice the principal frequency of a set of
// relative radius 0.75 either way; 1024 for 16,384 points), at most `cap`.
std::size_t periodogram_size(double density, double side, std::size_t cap = 2048);

// The principal frequency 1 / (2 * 0.75 r_max(density)) in cycles per unit length.
double principal_frequency(double density);

struct PowerSpectrum {
  std::size_t size = 0;       // M: k_x, k_y in [-M/2, M/2)
  double side = 0;            // L: frequency k means k / L cycles per unit
  std::size_t sets = 0;       // periodograms averaged
  std::uint64_t points = 0;   // summed over the sets
  std::vector<double> power;  // mean periodogram, M x M, index (k_y + M/2) M + (k_x + M/2); DC is 0

  PowerSpectrum(std::size_t m, double l) : size(m), side(l), power(m * m, 0.0) {}
  double at(int kx, int ky) const {
    return power[std::size_t(ky + int(size / 2)) * size + std::size_t(kx + int(size / 2))];
  }
  // Adds the periodogram of the points inside [x0, x0 + L) x [y0, y0 + L) (others are ignored).
  void add(const std::vector<Point2>& pts, double x0, double y0, int threads = 1);
  void add(const std::vector<double>& xy, double x0, double y0, int threads = 1);
  double density() const { return sets ? double(points) / double(sets) / (side * side) : 0; }
};

struct RadialStats {
  std::vector<double> frequency;      // annulus centre, cycles per unit
  std::vector<double> power;          // P_r (eq. 6.3)
  std::vector<double> anisotropy_db;  // 10 log10(s^2 / P_r^2) (eq. 6.4, 6.5)
  std::vector<std::uint32_t> samples;
};
RadialStats radial_stats(const PowerSpectrum& s);

struct SpectralSummary {
  double density = 0;
  double principal_frequency = 0;     // f_p, cycles per unit
  double band_lo = 0.5, band_hi = 2;  // the anisotropy band, in units of f_p
  double max_anisotropy_db = 0;       // over the annuli in the band
  double mean_anisotropy_db = 0;
  double effective_nyquist = 0;    // in units of sqrt(density) (mean sampling frequency)
  double oscillations = 0;         // largest P_r above the effective Nyquist frequency
  double peak_frequency = 0;       // where P_r is largest, in units of f_p
  double low_frequency_power = 0;  // mean P_r of the annuli below 0.5 f_p
};
SpectralSummary summarize(const RadialStats& r, double density, double band_lo = 0.5, double band_hi = 2);

}  // namespace tilekit::points
