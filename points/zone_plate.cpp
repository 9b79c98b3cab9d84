#include "points/zone_plate.hpp"

#include <algorithm>
#include <cmath>

#include "base/error.hpp"

namespace tilekit::points {

namespace {

// The Mitchell-Netravali cubic with B = C = 1/3, support [-2, 2].
double mitchell(double x) {
  constexpr double B = 1.0 / 3, C = 1.0 / 3;
  x = std::abs(x);
  if (x < 1) return ((12 - 9 * B - 6 * C) * x * x * x + (-18 + 12 * B + 6 * C) * x * x + (6 - 2 * B)) / 6;
  if (x < 2)
    return ((-B - 6 * C) * x * x * x + (6 * B + 30 * C) * x * x + (-12 * B - 48 * C) * x + (8 * B + 24 * C)) / 6;
  return 0;
}

double zone(double x, double y) {
  return 0.5 * (1 + std::sin(x * x + y * y));
}  // thesis eq. (6.7)

}  // namespace

ZonePlate zone_plate(const std::vector<double>& xy, const Window& w, int res, double extent) {
  if (res < 8) throw InputError("the zone plate needs at least 8 x 8 pixels");
  std::vector<double> sum(std::size_t(res) * std::size_t(res), 0), weight(sum.size(), 0);
  const double px = extent / res;  // function units per pixel
  for (std::size_t i = 0; i + 1 < xy.size(); i += 2) {
    // Window coordinates -> [0, extent)^2, y up (image rows grow down).
    const double x = (xy[i] - w.x0) / w.width() * extent, y = (xy[i + 1] - w.y0) / w.height() * extent;
    const double value = zone(x, y);
    const double sx = x / px, sy = (extent - y) / px;  // continuous pixel coordinates
    for (int py = int(std::floor(sy - 2)); py <= int(std::ceil(sy + 2)); ++py) {
      if (py < 0 || py >= res) continue;
      const double wy = mitchell(py + 0.5 - sy);
      if (wy == 0) continue;
      for (int qx = int(std::floor(sx - 2)); qx <= int(std::ceil(sx + 2)); ++qx) {
        if (qx < 0 || qx >= res) continue;
        const double wgt = wy * mitchell(qx + 0.5 - sx);
        sum[std::size_t(py) * std::size_t(res) + std::size_t(qx)] += wgt * value;
        weight[std::size_t(py) * std::size_t(res) + std::size_t(qx)] += wgt;
      }
    }
  }
  ZonePlate z;
  z.image = Image(res, res);
  double inner = 0, outer = 0;
  long n_in = 0, n_out = 0;
  for (int py = 0; py < res; ++py)
    for (int qx = 0; qx < res; ++qx) {
      const std::size_t k = std::size_t(py) * std::size_t(res) + std::size_t(qx);
      const double v = weight[k] > 1e-3 ? std::clamp(sum[k] / weight[k], 0.0, 1.0) : 0.5;
      const auto g = std::uint8_t(std::lround(255 * v));
      z.image.set(qx, py, {g, g, g});
      const double x = (qx + 0.5) * px, y = extent - (py + 0.5) * px, r = std::hypot(x, y);
      const double e = v - zone(x, y);
      if (r < extent / 4) inner += e * e, ++n_in;
      if (r > extent / 2) outer += e * e, ++n_out;
    }
  z.rms_inner = n_in ? std::sqrt(inner / double(n_in)) : 0;
  z.rms_outer = n_out ? std::sqrt(outer / double(n_out)) : 0;
  return z;
}

}  // namespace tilekit::points
