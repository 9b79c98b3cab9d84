#include "base/fft.hpp"

#include <cassert>
#include <cmath>
#include <numbers>

#include "base/parallel.hpp"

namespace tilekit {

namespace {

// twiddle[k] = e^{-2 pi i k / n}, k < n / 2
std::vector<Complex> twiddles(std::size_t n) {
  std::vector<Complex> w(n / 2);
  for (std::size_t k = 0; k < n / 2; ++k) {
    const double angle = -2 * std::numbers::pi * double(k) / double(n);
    w[k] = {std::cos(angle), std::sin(angle)};
  }
  return w;
}

void transform(Complex* a, std::size_t n, const std::vector<Complex>& w) {
  assert(is_power_of_two(n));
  // Bit-reversal permutation.
  for (std::size_t i = 1, j = 0; i < n; ++i) {
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(a[i], a[j]);
  }
  // Butterflies of length len use every (n / len)-th twiddle.
  for (std::size_t len = 2; len <= n; len <<= 1) {
    const std::size_t half = len / 2, stride = n / len;
    for (std::size_t i = 0; i < n; i += len)
      for (std::size_t k = 0; k < half; ++k) {
        const Complex u = a[i + k], v = a[i + k + half] * w[k * stride];
        a[i + k] = u + v;
        a[i + k + half] = u - v;
      }
  }
}

}  // namespace

void fft(Complex* a, std::size_t n) {
  transform(a, n, twiddles(n));
}

void fft2d(std::vector<Complex>& a, std::size_t n, int threads) {
  assert(a.size() == n * n);
  const auto w = twiddles(n);
  parallel_for(std::int64_t(n), threads, [&](std::int64_t r) { transform(a.data() + std::size_t(r) * n, n, w); });
  parallel_for(std::int64_t(n), threads, [&](std::int64_t c) {
    std::vector<Complex> col(n);
    for (std::size_t r = 0; r < n; ++r) col[r] = a[r * n + std::size_t(c)];
    transform(col.data(), n, w);
    for (std::size_t r = 0; r < n; ++r) a[r * n + std::size_t(c)] = col[r];
  });
}

}  // namespace tilekit
