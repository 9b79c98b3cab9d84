#include "points/geometry.hpp"

#include <algorithm>
#include <cassert>
#include <limits>

namespace tilekit::points {

PointGrid::PointGrid(double x0, double y0, double w, double h, double cell, bool torus)
    : x0_(x0), y0_(y0), w_(w), h_(h), cell_(cell), torus_(torus) {
  assert(w > 0 && h > 0 && cell > 0);
  // On a torus the cells must tile the period exactly, so they are widened to w / floor(w / cell).
  nx_ = std::max(1, int(std::floor(w / cell)));
  ny_ = std::max(1, int(std::floor(h / cell)));
  if (!torus) {
    nx_ = std::max(1, int(std::ceil(w / cell)));
    ny_ = std::max(1, int(std::ceil(h / cell)));
  }
  cell_ = torus ? std::max(w / nx_, h / ny_) : cell;
  head_.assign(std::size_t(nx_) * std::size_t(ny_), -1);
}

void PointGrid::clear() {
  std::fill(head_.begin(), head_.end(), -1);
  count_ = 0;
}

void PointGrid::insert(int id, Point2 p) {
  assert(id >= 0);
  if (std::size_t(id) >= next_.size()) next_.resize(std::size_t(id) + 1, -1);
  const std::size_t c = std::size_t(cell_y(p.y)) * std::size_t(nx_) + std::size_t(cell_x(p.x));
  next_[std::size_t(id)] = head_[c];
  head_[c] = id;
  ++count_;
}

void PointGrid::erase(int id, Point2 p) {
  int* link = &head_[std::size_t(cell_index(p))];
  while (*link >= 0 && *link != id) link = &next_[std::size_t(*link)];
  if (*link == id) *link = next_[std::size_t(id)], --count_;
}

int PointGrid::nearest(Point2 p, const std::vector<Point2>& pos) const {
  if (count_ == 0) return -1;
  int best = -1;
  double best_d2 = std::numeric_limits<double>::infinity();
  const int max_rings = std::max(nx_, ny_);
  // Ring k holds cells at Chebyshev distance k; any point outside rings 0..k is farther than
  // k * cell (k - 1 cells, plus at least the part of p's own cell), so stop once best is closer.
  for (int k = 0; k <= max_rings; ++k) {
    const int cx = cell_x(p.x), cy = cell_y(p.y);
    for (int dy = -k; dy <= k; ++dy)
      for (int dx = -k; dx <= k; ++dx) {
        if (std::max(std::abs(dx), std::abs(dy)) != k) continue;
        int x = cx + dx, y = cy + dy;
        if (torus_) {
          x = ((x % nx_) + nx_) % nx_;
          y = ((y % ny_) + ny_) % ny_;
        } else if (x < 0 || y < 0 || x >= nx_ || y >= ny_) {
          continue;
        }
        for (int id = head_[std::size_t(y) * std::size_t(nx_) + std::size_t(x)]; id >= 0; id = next_[std::size_t(id)]) {
          const Point2 d = delta(pos[std::size_t(id)], p);
          const double d2 = d.x * d.x + d.y * d.y;
          if (d2 < best_d2) best_d2 = d2, best = id;
        }
      }
    // Points first seen in ring k+1 are at least k * cell away (outside the (2k+1)-cell block
    // around p's cell, whose border is at least k cells from p).
    if (best >= 0 && best_d2 <= double(k) * cell_ * double(k) * cell_) break;
  }
  return best;
}

double min_distance(const std::vector<Point2>& pts) {
  if (pts.size() < 2) return std::numeric_limits<double>::infinity();
  double x0 = pts[0].x, x1 = x0, y0 = pts[0].y, y1 = y0;
  for (const auto& p : pts)
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  const double w = std::max(x1 - x0, 1e-300), h = std::max(y1 - y0, 1e-300);
  // About two points per cell: the nearest neighbour of most points is in the 3x3 block.
  const double cell = std::max(std::sqrt(2.0 * w * h / double(pts.size())), 1e-300);
  PointGrid grid(x0, y0, w, h, cell, false);
  for (std::size_t i = 0; i < pts.size(); ++i) grid.insert(int(i), pts[i]);
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < pts.size(); ++i)
    grid.for_near(pts[i], 1, [&](int id) {
      if (std::size_t(id) != i) best = std::min(best, squared_distance(pts[i], pts[std::size_t(id)]));
    });
  // Every pair closer than one cell lies in neighbouring cells, so a best below one cell is the
  // minimum. Otherwise (only for a handful of scattered points) compare all pairs.
  if (best > cell * cell)
    for (std::size_t i = 0; i < pts.size(); ++i)
      for (std::size_t j = i + 1; j < pts.size(); ++j) best = std::min(best, squared_distance(pts[i], pts[j]));
  return std::sqrt(best);
}

}  // namespace tilekit::points
