// The analysis gives the known answers: a regular grid's periodogram is N at the multiples of
// its reciprocal lattice and 0 elsewhere, white noise has a flat spectrum at 1 and an anisotropy
// at the -10 dB background of K = 10, radius statistics of a grid are exact, the FFT matches a
// direct DFT, and the zone plate of a dense grid reproduces the function at low frequencies.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "base/error.hpp"
#include "points/analysis_radius.hpp"
#include "points/analysis_spectrum.hpp"
#include "points/fft.hpp"
#include "points/reference_sets.hpp"
#include "points/zone_plate.hpp"

using namespace tilekit;
using namespace tilekit::points;

TEST(Fft, MatchesADirectDft) {
  const std::size_t n = 64;
  std::vector<Complex> a(n);
  for (std::size_t i = 0; i < n; ++i) a[i] = {std::sin(0.3 * double(i * i)), std::cos(1.7 * double(i))};
  auto f = a;
  fft(f.data(), n);
  for (std::size_t k = 0; k < n; ++k) {
    Complex d = 0;
    for (std::size_t j = 0; j < n; ++j) d += a[j] * std::polar(1.0, -2 * std::numbers::pi * double(k * j) / double(n));
    EXPECT_LT(std::abs(d - f[k]), 1e-9) << k;
  }
}

TEST(Periodogram, RegularGridHasSpikesOfHeightNAtItsReciprocalLattice) {
  // 32 x 32 points at spacing 1/32 in the unit square: the sum over points of exp(-2 pi i k.x) is
  // N when both k components are multiples of 32 and 0 otherwise, so P = N there and 0 elsewhere.
  const auto xy = grid_points({0, 0, 1, 1}, 1024, false, 1);
  ASSERT_EQ(xy.size(), 2u * 1024);
  PowerSpectrum ps(128, 1.0);
  ps.add(xy, 0, 0);
  for (int ky = -64; ky < 64; ++ky)
    for (int kx = -64; kx < 64; ++kx) {
      if (kx == 0 && ky == 0) continue;
      const bool spike = kx % 32 == 0 && ky % 32 == 0;
      EXPECT_NEAR(ps.at(kx, ky), spike ? 1024.0 : 0.0, 1e-3) << kx << "," << ky;  // NUFFT error ~1e-7 relative
    }
}

TEST(Periodogram, WhiteNoiseIsFlatAtOneWithBackgroundAnisotropy) {
  PowerSpectrum ps(128, 1.0);
  for (int k = 0; k < 10; ++k) ps.add(white_noise_points({0, 0, 1, 1}, 4096, std::uint64_t(k) + 1), 0, 0);
  const auto r = radial_stats(ps);
  double mean = 0, mean_db = 0;
  int n = 0;
  for (std::size_t i = 4; i < r.power.size(); ++i) mean += r.power[i], mean_db += r.anisotropy_db[i], ++n;
  EXPECT_NEAR(mean / n, 1.0, 0.02);        // flat at 1 (P normalised by N)
  EXPECT_NEAR(mean_db / n, -10.0, 0.35);   // var(P) = P^2 / K, K = 10 (thesis eq. 6.2)
  EXPECT_EQ(ps.sets, 10u);
}

TEST(Periodogram, BlueNoiseHasLittleLowFrequencyPower) {
  PowerSpectrum ps(128, 1.0);
  for (int k = 0; k < 4; ++k)
    ps.add(bridson_points({0, 0, 1, 1}, 2 * 0.75 * max_poisson_radius(2048), std::uint64_t(k) + 1, true), 0, 0);
  const auto s = summarize(radial_stats(ps), ps.density());
  EXPECT_LT(s.low_frequency_power, 0.2);
  EXPECT_GT(s.effective_nyquist, 0.2);
  EXPECT_GT(s.oscillations, 1.1);  // the peak at the principal frequency
}

TEST(RadiusStats, SquareGridHasTheKnownRelativeRadius) {
  // Spacing a, density 1/a^2: rho = (a/2) / sqrt(a^2 / (2 sqrt 3)) = sqrt(sqrt(3) / 2) = 0.9306.
  const auto xy = grid_points({0, 0, 10, 10}, 100, false, 1);
  const auto r = radius_stats(xy, 100.0, 1.0);
  EXPECT_NEAR(r.rho, std::sqrt(std::sqrt(3.0) / 2), 1e-4);
  EXPECT_NEAR(r.min_distance, 0.1, 1e-6);
  EXPECT_NEAR(r.mean_nn_distance, 0.1, 1e-6);
  EXPECT_NEAR(r.rho_across, r.rho, 1e-4);  // grid lines sit on both sides of each tile border
}

TEST(RadiusStats, WhiteNoiseHasASmallRelativeRadius) {
  const auto r = radius_stats(white_noise_points({0, 0, 1, 1}, 10000, 3), 1.0);
  EXPECT_LT(r.rho, 0.05);
  // Poisson process: mean nearest-neighbour distance 1 / (2 sqrt(density)).
  EXPECT_NEAR(r.mean_nn_distance, 0.5 / 100, 0.0003);
}

TEST(ZonePlate, DenseGridReproducesTheLowFrequencies) {
  const auto dense = grid_points({0, 0, 1, 1}, 512.0 * 512 * 4, false, 1);  // 4 samples per pixel
  const auto z = zone_plate(dense, {0, 0, 1, 1}, 128, 12);
  EXPECT_LT(z.rms_inner, 0.03);
  EXPECT_EQ(z.image.width, 128);
}
