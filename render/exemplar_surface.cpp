#include "render/exemplar_surface.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>

#include "base/error.hpp"
#include "texture/mipmap.hpp"

namespace tilekit {

std::uint16_t float_to_half(float f) {
  std::uint32_t x;
  std::memcpy(&x, &f, 4);
  const std::uint32_t sign = (x >> 16) & 0x8000u, mant = x & 0x7fffffu;
  const int exp = int((x >> 23) & 0xffu);
  if (exp == 255) return std::uint16_t(sign | 0x7c00u | (mant ? 0x200u : 0u));  // infinity, NaN
  const int e = exp - 127 + 15;
  if (e >= 31) return std::uint16_t(sign | 0x7c00u);  // overflow: infinity
  // Keep `keep` bits of the 24-bit significand, rounding the dropped `shift` bits to nearest even.
  auto rounded = [](std::uint32_t m, int shift) {
    const std::uint32_t h = m >> shift, rem = m & ((1u << shift) - 1), half = 1u << (shift - 1);
    return h + (rem > half || (rem == half && (h & 1u)) ? 1u : 0u);
  };
  if (e <= 0) {  // a subnormal half (or zero)
    if (e < -10) return std::uint16_t(sign);
    return std::uint16_t(sign | rounded(mant | 0x800000u, 14 - e));
  }
  // A carry out of the significand moves into the exponent, which is the right result.
  return std::uint16_t(sign | ((std::uint32_t(e) << 10) + rounded(mant, 13)));
}

float half_to_float(std::uint16_t h) {
  const std::uint32_t sign = std::uint32_t(h & 0x8000u) << 16, exp = (h >> 10) & 31u, mant = h & 0x3ffu;
  std::uint32_t x;
  if (exp == 0) {
    const float v = std::ldexp(float(mant), -24);
    return sign ? -v : v;
  }
  if (exp == 31)
    x = sign | 0x7f800000u | (mant << 13);
  else
    x = sign | ((exp - 15 + 127) << 23) | (mant << 13);
  float f;
  std::memcpy(&f, &x, 4);
  return f;
}

namespace {

double normal_cdf(double x) {
  return 0.5 * std::erfc(-x / std::sqrt(2.0));
}

// The inverse of normal_cdf by Newton's method inside a shrinking bracket.
double normal_quantile(double p) {
  double lo = -9, hi = 9, x = 0;
  for (int i = 0; i < 100; ++i) {
    const double f = normal_cdf(x) - p;
    if (f < 0)
      lo = x;
    else
      hi = x;
    const double step = f / (std::exp(-0.5 * x * x) / std::sqrt(2 * M_PI));
    double next = x - step;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - x) < 1e-12) return next;
    x = next;
  }
  return x;
}

// Eigenvectors of a symmetric 3x3 matrix (cyclic Jacobi), as the columns of `v`, ordered by
// decreasing eigenvalue, each with a non-negative sum of components (a deterministic sign).
void symmetric_eigen(std::array<double, 9> a, std::array<double, 9>& v, std::array<double, 3>& values) {
  v = {1, 0, 0, 0, 1, 0, 0, 0, 1};  // column-major: v[3 * k + i] is component i of vector k
  for (int sweep = 0; sweep < 50; ++sweep) {
    double off = 0;
    for (int p = 0; p < 3; ++p)
      for (int q = p + 1; q < 3; ++q) off += a[3 * q + p] * a[3 * q + p];
    if (off < 1e-24) break;
    for (int p = 0; p < 3; ++p)
      for (int q = p + 1; q < 3; ++q) {
        const double apq = a[3 * q + p];
        if (std::abs(apq) < 1e-300) continue;
        const double theta = (a[3 * q + q] - a[3 * p + p]) / (2 * apq);
        const double t = (theta >= 0 ? 1 : -1) / (std::abs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < 3; ++k) {  // a = J^T a J, v = v J
          const double akp = a[3 * p + k], akq = a[3 * q + k];
          a[3 * p + k] = c * akp - s * akq;
          a[3 * q + k] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) {
          const double apk = a[3 * k + p], aqk = a[3 * k + q];
          a[3 * k + p] = c * apk - s * aqk;
          a[3 * k + q] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k) {
          const double vkp = v[3 * p + k], vkq = v[3 * q + k];
          v[3 * p + k] = c * vkp - s * vkq;
          v[3 * q + k] = s * vkp + c * vkq;
        }
      }
  }
  std::array<int, 3> order{0, 1, 2};
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return a[3 * x + x] > a[3 * y + y]; });
  std::array<double, 9> sorted{};
  for (int k = 0; k < 3; ++k) {
    const int src = order[std::size_t(k)];
    values[std::size_t(k)] = a[std::size_t(3 * src + src)];
    const double sign =
        v[std::size_t(3 * src)] + v[std::size_t(3 * src + 1)] + v[std::size_t(3 * src + 2)] < 0 ? -1 : 1;
    for (int i = 0; i < 3; ++i) sorted[std::size_t(3 * k + i)] = sign * v[std::size_t(3 * src + i)];
  }
  v = sorted;
}

// Level l + 1 of a float mip chain: the mean of each 2x2 block of level l (OpenGL's sizes,
// max(1, floor(w / 2)); an odd last column or row is dropped, a side of 1 is repeated).
FloatImage halve(const FloatImage& in) {
  FloatImage out{std::max(1, in.width / 2), std::max(1, in.height / 2), {}};
  out.texels.resize(std::size_t(out.width) * std::size_t(out.height) * 4);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const int x0 = std::min(2 * x, in.width - 1), x1 = std::min(2 * x + 1, in.width - 1);
      const int y0 = std::min(2 * y, in.height - 1), y1 = std::min(2 * y + 1, in.height - 1);
      for (int c = 0; c < 4; ++c)
        out.at(x, y)[c] = 0.25f * (in.at(x0, y0)[c] + in.at(x1, y0)[c] + in.at(x0, y1)[c] + in.at(x1, y1)[c]);
    }
  return out;
}

void round_to_half(FloatImage& img) {
  for (float& v : img.texels) v = half_to_float(float_to_half(v));
}

// Heitz & Neyret's precomputation: decorrelate the colours (PCA), Gaussianize every decorrelated
// channel by its rank (T(x) = 1/2 + G^-1((rank + 1/2) / N) / 6), keep the sorted values for
// the inverse transformation, and prefilter that per mip level.
void histogram_transform(const Image& ex, ExemplarSurface& s) {
  const std::size_t n = std::size_t(ex.width) * std::size_t(ex.height);
  std::array<double, 3> mean{};
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) mean[std::size_t(c)] += ex.pixels[4 * i + std::size_t(c)];
  for (double& m : mean) m /= double(n);
  std::array<double, 9> cov{};
  for (std::size_t i = 0; i < n; ++i)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        cov[std::size_t(3 * c + r)] += (ex.pixels[4 * i + std::size_t(r)] - mean[std::size_t(r)]) *
                                       (ex.pixels[4 * i + std::size_t(c)] - mean[std::size_t(c)]);
  for (double& v : cov) v /= double(n);
  std::array<double, 9> basis;
  std::array<double, 3> variances;
  symmetric_eigen(cov, basis, variances);
  for (int k = 0; k < 9; ++k) s.basis[std::size_t(k)] = float(basis[std::size_t(k)]);
  for (int c = 0; c < 3; ++c) s.mean[std::size_t(c)] = float(mean[std::size_t(c)] / 255.0);

  FloatImage g{ex.width, ex.height, std::vector<float>(n * 4, 0.5f)};
  std::vector<std::vector<double>> sorted(3, std::vector<double>(n));
  std::vector<std::size_t> order(n);
  for (int k = 0; k < 3; ++k) {
    std::vector<double>& q = sorted[std::size_t(k)];
    for (std::size_t i = 0; i < n; ++i) {  // the decorrelated channel k, / 255
      double v = 0;
      for (int c = 0; c < 3; ++c)
        v += basis[std::size_t(3 * k + c)] * (ex.pixels[4 * i + std::size_t(c)] - mean[std::size_t(c)]);
      q[i] = v / 255.0;
    }
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return q[a] < q[b]; });
    for (std::size_t r = 0; r < n; ++r)
      g.texels[4 * order[r] + std::size_t(k)] = float(0.5 + normal_quantile((double(r) + 0.5) / double(n)) / 6.0);
    std::sort(q.begin(), q.end());
  }
  s.gaussian = {g};
  while (s.gaussian.back().width > 1 || s.gaussian.back().height > 1) s.gaussian.push_back(halve(s.gaussian.back()));
  for (FloatImage& level : s.gaussian) round_to_half(level);

  // The inverse transformation at level 0, sampled at the LUT's texel centres g = (i + 1/2) / W:
  // the sorted value of rank floor(N G(g)), G the Gaussian's distribution function.
  const int levels = int(s.gaussian.size());
  s.lut = FloatImage{kLutWidth, levels, std::vector<float>(std::size_t(kLutWidth) * std::size_t(levels) * 4, 0.0f)};
  std::vector<std::array<double, kLutWidth>> lut0(3);
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < kLutWidth; ++i) {
      const double u = normal_cdf(((i + 0.5) / kLutWidth - 0.5) * 6.0);
      const std::size_t rank = std::min(n - 1, std::size_t(std::max(0.0, std::floor(u * double(n)))));
      lut0[std::size_t(k)][std::size_t(i)] = sorted[std::size_t(k)][rank];
    }
  // Prefiltering: a texel of level l averages a footprint of level-0 texels whose Gaussian values
  // spread around the filtered one with the variance that filtering removed, var_0 - var_l; the
  // colour the footprint shows is the mean of the inverse transformation over that spread:
  // lut_l(g) = E[lut_0(g + e)], e ~ N(0, var_0 - var_l).
  auto variance = [](const FloatImage& img, int k) {
    double sum = 0, sq = 0;
    const std::size_t m = std::size_t(img.width) * std::size_t(img.height);
    for (std::size_t i = 0; i < m; ++i) sum += img.texels[4 * i + std::size_t(k)];
    for (std::size_t i = 0; i < m; ++i) {
      const double d = img.texels[4 * i + std::size_t(k)] - sum / double(m);
      sq += d * d;
    }
    return sq / double(m);
  };
  auto lut0_at = [&](int k, double gv) {  // linear between texel centres, clamped at the ends
    const double x = std::clamp(gv * kLutWidth - 0.5, 0.0, double(kLutWidth - 1));
    const int i = std::min(int(x), kLutWidth - 2);
    const double f = x - i;
    return (1 - f) * lut0[std::size_t(k)][std::size_t(i)] + f * lut0[std::size_t(k)][std::size_t(i + 1)];
  };
  for (int k = 0; k < 3; ++k) {
    const double var0 = variance(s.gaussian[0], k);
    for (int l = 0; l < levels; ++l) {
      const double spread = std::sqrt(std::max(0.0, var0 - variance(s.gaussian[std::size_t(l)], k)));
      for (int i = 0; i < kLutWidth; ++i) {
        const double gv = (i + 0.5) / kLutWidth;
        double sum = 0, wsum = 0;
        for (int z = -64; z <= 64; ++z) {  // e = spread * t, t in [-4, 4]
          const double t = z / 16.0, w = std::exp(-0.5 * t * t);
          sum += w * lut0_at(k, gv + spread * t);
          wsum += w;
        }
        s.lut.at(i, l)[k] = float(sum / wsum);
      }
    }
  }
  round_to_half(s.lut);
}

}  // namespace

std::size_t ExemplarSurface::memory_bytes(bool hpn) const {
  std::size_t bytes = 0;
  if (!hpn)
    for (const Image& l : levels) bytes += l.pixels.size();
  else {
    for (const FloatImage& l : gaussian) bytes += l.texels.size() * 2;  // RGBA16F
    bytes += lut.texels.size() * 2;
  }
  return bytes;
}

ExemplarSurface make_exemplar_surface(const Image& exemplar, std::string name, float cell_px) {
  if (exemplar.channels != 4) throw InputError(fmt::format("{}: expected an RGBA image", name));
  ExemplarSurface s;
  s.name = std::move(name);
  s.width = exemplar.width;
  s.height = exemplar.height;
  const int side = std::min(s.width, s.height);
  s.cell_px = cell_px > 0 ? cell_px : std::floor(float(side) / (2.0f * std::sqrt(3.0f)));
  // A patch covers the hexagon of radius cell_px around its centre; 4 texels more keep the
  // bilinear and the first mip levels' filters inside the exemplar too.
  const float margin = s.cell_px + 4;
  if (!(s.cell_px >= 2) || 2 * margin >= float(side))
    throw InputError(
        fmt::format("{}: a {}x{} exemplar is too small for triangle cells of {} texels (a patch of "
                    "radius {} must fit inside it)",
                    s.name, s.width, s.height, s.cell_px, margin));
  s.centre_lo[0] = s.centre_lo[1] = margin;
  s.centre_hi[0] = float(s.width) - margin;
  s.centre_hi[1] = float(s.height) - margin;
  s.levels = mip_chain(exemplar, MipEdge::Wrap);
  histogram_transform(exemplar, s);
  return s;
}

}  // namespace tilekit
