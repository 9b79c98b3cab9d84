#include "points/analysis_radius.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/error.hpp"

namespace tilekit::points {

RadiusStats radius_stats(const std::vector<double>& xy, double area, double tile_size) {
  std::vector<Point2> pts;
  pts.reserve(xy.size() / 2);
  for (std::size_t i = 0; i + 1 < xy.size(); i += 2) pts.push_back({xy[i], xy[i + 1]});
  return radius_stats(pts, area, tile_size);
}

RadiusStats radius_stats(const std::vector<Point2>& pts, double area, double tile_size) {
  if (pts.size() < 2) throw InputError("radius analysis needs at least two points");
  if (!(area > 0)) throw InputError("radius analysis needs a window of positive area");
  RadiusStats s;
  s.count = pts.size();
  s.density = double(pts.size()) / area;
  s.tiled = tile_size > 0;
  double x0 = pts[0].x, x1 = x0, y0 = pts[0].y, y1 = y0;
  for (const auto& p : pts)
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  // Cells of twice the mean spacing: every nearest neighbour of a reasonably even set is in the
  // 3x3 block; nearest() widens the search for the others.
  const double cell = 2 / std::sqrt(s.density);
  PointGrid grid(x0, y0, std::max(x1 - x0, cell), std::max(y1 - y0, cell), cell, false);
  for (std::size_t i = 0; i < pts.size(); ++i) grid.insert(int(i), pts[i]);
  const double inf = std::numeric_limits<double>::infinity();
  double best = inf, within = inf, across = inf, sum_nn = 0;
  const auto tile_of = [&](Point2 p) { return std::pair{std::floor(p.x / tile_size), std::floor(p.y / tile_size)}; };
  for (std::size_t i = 0; i < pts.size(); ++i) {
    double nn = inf;
    grid.for_near(pts[i], 1, [&](int id) {
      if (std::size_t(id) == i) return;
      const double d2 = squared_distance(pts[i], pts[std::size_t(id)]);
      nn = std::min(nn, d2);
      if (s.tiled) {
        if (tile_of(pts[i]) == tile_of(pts[std::size_t(id)]))
          within = std::min(within, d2);
        else
          across = std::min(across, d2);
      }
    });
    if (nn > cell * cell) {
      // A lonely point: search outwards for its nearest neighbour.
      for (int rings = 2; nn == inf || std::sqrt(nn) > (rings - 1) * cell; ++rings) {
        grid.for_near(pts[i], rings, [&](int id) {
          if (std::size_t(id) != i) nn = std::min(nn, squared_distance(pts[i], pts[std::size_t(id)]));
        });
        if (rings > 64) break;
      }
    }
    best = std::min(best, nn);
    sum_nn += std::sqrt(nn);
  }
  const double two_rmax = 2 * max_poisson_radius(s.density);
  s.min_distance = std::sqrt(best);
  s.mean_nn_distance = sum_nn / double(pts.size());
  s.rho = relative_radius(s.min_distance, s.density);
  s.mean_nn_relative = s.mean_nn_distance / two_rmax;
  if (s.tiled) {
    s.min_within = std::sqrt(std::min(within, cell * cell));
    s.min_across = std::sqrt(std::min(across, cell * cell));
    s.rho_within = relative_radius(s.min_within, s.density);
    s.rho_across = relative_radius(s.min_across, s.density);
  }
  return s;
}

}  // namespace tilekit::points
