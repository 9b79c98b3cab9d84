#include "tiling/halton_tiling.hpp"

#include <fmt/format.h>

#include "base/error.hpp"

namespace tilekit {

namespace {

// Multiplicative inverse of a modulo m (a, m coprime), by the extended Euclidean algorithm.
std::uint64_t inverse_mod(std::uint64_t a, std::uint64_t m) {
  if (m == 1) return 0;
  __int128 t = 0, new_t = 1, r = m, new_r = a % m;
  while (new_r != 0) {
    __int128 q = r / new_r;
    std::swap(t, new_t);
    new_t -= q * t;
    std::swap(r, new_r);
    new_r -= q * r;
  }
  if (t < 0) t += m;
  return std::uint64_t(t);
}

std::uint64_t floor_mod(std::int64_t v, std::uint64_t m) {
  std::int64_t r = v % std::int64_t(m);
  return std::uint64_t(r < 0 ? r + std::int64_t(m) : r);
}

}  // namespace

HaltonColouring::HaltonColouring(std::uint32_t colours, std::uint64_t lattice_cols, std::uint64_t lattice_rows)
    : c_(colours) {
  if (colours < 1 || colours > 255) throw InputError(fmt::format("colours must be between 1 and 255, got {}", colours));
  if (lattice_cols < 1 || lattice_rows < 1 || lattice_cols > (1ull << 31) || lattice_rows > (1ull << 31))
    throw InputError("Halton tiling: the lattice must have 1 to 2^31 points per side");
  // the smallest n1, n2 with 2^n1 >= T_x + 1 and 3^n2 >= T_y + 1 (paper sec. 3.2)
  while (p1_ < lattice_cols) p1_ *= 2, ++n1_;
  while (p2_ < lattice_rows) p2_ *= 3, ++n2_;
  m1_ = inverse_mod(p2_ % p1_, p1_);  // m1 = p2^-1 mod p1
  m2_ = inverse_mod(p1_ % p2_, p2_);  // m2 = p1^-1 mod p2
  const unsigned __int128 total = (unsigned __int128)p1_ * p2_;
  for (std::uint32_t c = 0; c <= c_; ++c) thresholds_.push_back(std::uint64_t((total * c + c_ - 1) / c_));
}

std::uint64_t HaltonColouring::column_term(std::int64_t x) const {
  // l1 = phi_2^-1(x / 2^n1): x with its n1 binary digits reversed
  std::uint64_t v = floor_mod(x, p1_), l1 = 0;
  for (int k = 0; k < n1_; ++k) l1 = l1 * 2 + (v & 1), v >>= 1;
  return p2_ * ((l1 * m1_) & (p1_ - 1));  // p1 is a power of two: mod p1 is a mask (paper sec. 3.2)
}

std::uint64_t HaltonColouring::row_term(std::int64_t y) const {
  // l2 = phi_3^-1(y / 3^n2): y with its n2 ternary digits reversed
  std::uint64_t v = floor_mod(y, p2_), l2 = 0;
  for (int k = 0; k < n2_; ++k) l2 = l2 * 3 + v % 3, v /= 3;
  return p1_ * (l2 * m2_ % p2_);  // l2, m2 < p2 <= 3^20 < 2^32: no overflow
}

std::uint64_t HaltonColouring::index(std::int64_t x, std::int64_t y) const {
  // eq. (6); both terms are < p1 p2 < 2^63, so the sum does not overflow
  const std::uint64_t p = p1_ * p2_, s = column_term(x) + row_term(y);
  return s >= p ? s - p : s;
}

std::uint32_t HaltonColouring::colour_of_index(std::uint64_t i) const {
  // eq. (4) without a 128-bit division: the colour is the number of class boundaries <= i
  std::uint32_t c = std::uint32_t(double(i) / double(p1_ * p2_) * c_);
  if (c >= c_) c = c_ - 1;
  while (i < thresholds_[c]) --c;
  while (i >= thresholds_[c + 1]) ++c;
  return c;
}

std::pair<std::uint64_t, std::uint64_t> HaltonColouring::cell_of_point(std::uint64_t i, int n1, int n2) {
  // eq. (3): phi_b(i) mirrors the base-b digits of i around the radix point; scaled by b^n and
  // floored, only the n lowest digits of i remain, reversed.
  std::uint64_t x = 0, y = 0, v = i;
  for (int k = 0; k < n1; ++k) x = x * 2 + v % 2, v /= 2;
  v = i;
  for (int k = 0; k < n2; ++k) y = y * 3 + v % 3, v /= 3;
  return {x, y};
}

void HaltonColouring::prepare(RowCache& cache, std::int64_t x0, std::size_t n) const {
  cache.a.resize(n);
  for (std::size_t k = 0; k < n; ++k) cache.a[k] = column_term(x0 + std::int64_t(k));
}

void HaltonColouring::row(RowCache& cache, std::int64_t y, std::uint16_t* out) const {
  const std::uint64_t b = row_term(y), p = p1_ * p2_;
  const std::size_t n = cache.a.size();
  for (std::size_t k = 0; k < n; ++k) {
    std::uint64_t s = cache.a[k] + b;
    out[k] = std::uint16_t(colour_of_index(s >= p ? s - p : s));
  }
}

}  // namespace tilekit
