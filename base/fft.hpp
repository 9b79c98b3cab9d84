#pragma once
// The one FFT: radix-2 (iterative Cooley-Tukey, decimation in time), in 1-D and 2-D, for the
// periodograms of the point-set and texture analyses. Forward transform:
// X[k] = sum_n x[n] e^{-2 pi i k n / N}.
#include <complex>
#include <cstddef>
#include <vector>

namespace tilekit {

using Complex = std::complex<double>;

// In place; n = a.size() must be a power of two.
void fft(Complex* a, std::size_t n);

// In place on a row-major n x n array (rows, then columns), rows and columns on `threads` threads.
void fft2d(std::vector<Complex>& a, std::size_t n, int threads = 1);

inline bool is_power_of_two(std::size_t n) {
  return n > 0 && (n & (n - 1)) == 0;
}

}  // namespace tilekit
