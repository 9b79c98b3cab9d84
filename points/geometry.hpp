#pragma once
// Points in the plane, the relative radius of thesis sec. 4.2.3 and a uniform grid for
// neighbour queries (plain or toroidal). Everything else in points/ builds on these.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace tilekit::points {

struct Point2 {
  double x = 0, y = 0;
  friend bool operator==(const Point2&, const Point2&) = default;
};

inline double squared_distance(Point2 a, Point2 b) {
  const double dx = a.x - b.x, dy = a.y - b.y;
  return dx * dx + dy * dy;
}

// The packing density of the hexagonal lattice, pi / (2 sqrt 3) (thesis eq. 4.1).
inline constexpr double kHexagonalPackingDensity = 0.90689968211710892;

// The largest Poisson disk radius a distribution of `density` points per unit area can have:
// that of the hexagonal lattice, r_max = sqrt(1 / (2 sqrt(3) density)) (thesis eq. 4.2 with
// N points on the unit torus, density = N).
inline double max_poisson_radius(double density) {
  return std::sqrt(1.0 / (2.0 * std::sqrt(3.0) * density));
}

// The relative radius rho = r / r_max of a set with smallest point distance `min_distance`
// (r = min_distance / 2, thesis eq. 4.3).
inline double relative_radius(double min_distance, double density) {
  return 0.5 * min_distance / max_poisson_radius(density);
}

// x modulo p in [0, p).
inline double wrap(double x, double p) {
  const double r = std::fmod(x, p);
  return r < 0 ? r + p : r;
}
// The representative of x modulo p nearest to 0, in [-p/2, p/2).
inline double wrap_centred(double x, double p) {
  return x - p * std::floor(x / p + 0.5);
}

// Quarter turns about a centre: R(x, y) = (-y, x) relative to it (rows grow south, so one
// turn takes east to south). Rotations by multiples of 90 degrees map the tile lattice, its
// corner squares and edge strips onto themselves (the rotatable tiles of Li et al.).
inline Point2 rotate_quarter(Point2 p, int turns, Point2 centre = {}) {
  double x = p.x - centre.x, y = p.y - centre.y;
  for (int t = ((turns % 4) + 4) % 4; t > 0; --t) {
    const double nx = -y;
    y = x;
    x = nx;
  }
  return {x + centre.x, y + centre.y};
}

// A uniform grid of square cells over [x0, x0 + w) x [y0, y0 + h) holding point ids, for
// "every point within distance d of p" queries with d <= cell. With `torus`, coordinates and
// differences wrap with periods w and h. Points outside a plain grid's box are clamped into
// its border cells, so queries stay correct for them too.
class PointGrid {
 public:
  PointGrid(double x0, double y0, double w, double h, double cell, bool torus);

  void clear();
  // Adds point `id` at p (ids index the caller's arrays; any order, each at most once).
  void insert(int id, Point2 p);
  // Removes point `id`, inserted at p.
  void erase(int id, Point2 p);

  double cell() const { return cell_; }
  bool torus() const { return torus_; }
  // The difference a - b, wrapped to the nearest image on a torus.
  Point2 delta(Point2 a, Point2 b) const {
    double dx = a.x - b.x, dy = a.y - b.y;
    if (torus_) dx = wrap_centred(dx, w_), dy = wrap_centred(dy, h_);
    return {dx, dy};
  }

  // Calls f(id) for every point in the cells within `rings` cells of p's cell (rings = 1 covers
  // every point closer than one cell size). On a torus each cell is visited at most once.
  template <class F>
  void for_near(Point2 p, int rings, F&& f) const {
    any_near(p, rings, [&f](int id) {
      f(id);
      return false;
    });
  }
  // The same, stopping at the first id for which pred(id) is true; whether there was one.
  template <class F>
  bool any_near(Point2 p, int rings, F&& pred) const {
    const int cx = cell_x(p.x), cy = cell_y(p.y);
    for (int dy = -rings; dy <= rings; ++dy) {
      int y = cy + dy;
      if (torus_) {
        if (2 * rings + 1 > ny_ && (dy < -(ny_ / 2) || dy > (ny_ - 1) / 2)) continue;
        y = ((y % ny_) + ny_) % ny_;
      } else if (y < 0 || y >= ny_) {
        continue;
      }
      for (int dx = -rings; dx <= rings; ++dx) {
        int x = cx + dx;
        if (torus_) {
          if (2 * rings + 1 > nx_ && (dx < -(nx_ / 2) || dx > (nx_ - 1) / 2)) continue;
          x = ((x % nx_) + nx_) % nx_;
        } else if (x < 0 || x >= nx_) {
          continue;
        }
        for (int id = head_[std::size_t(y) * std::size_t(nx_) + std::size_t(x)]; id >= 0; id = next_[std::size_t(id)])
          if (pred(id)) return true;
      }
    }
    return false;
  }

  // The id of the point nearest to p among `pos` (the positions inserted), or -1 if empty.
  int nearest(Point2 p, const std::vector<Point2>& pos) const;

  // Cells by index (row-major): the cell holding p, and a cell's centre.
  int cell_index(Point2 p) const { return cell_y(p.y) * nx_ + cell_x(p.x); }
  Point2 cell_centre(int index) const {
    const double cw = torus_ ? w_ / nx_ : cell_, ch = torus_ ? h_ / ny_ : cell_;
    return {x0_ + (index % nx_ + 0.5) * cw, y0_ + (index / nx_ + 0.5) * ch};
  }

 private:
  int cell_x(double x) const {
    if (torus_) return std::min(nx_ - 1, int(wrap(x - x0_, w_) / (w_ / nx_)));
    return std::clamp(int(std::floor((x - x0_) / cell_)), 0, nx_ - 1);
  }
  int cell_y(double y) const {
    if (torus_) return std::min(ny_ - 1, int(wrap(y - y0_, h_) / (h_ / ny_)));
    return std::clamp(int(std::floor((y - y0_) / cell_)), 0, ny_ - 1);
  }

  double x0_, y0_, w_, h_, cell_;
  bool torus_;
  int nx_, ny_;
  std::vector<int> head_, next_;
  int count_ = 0;
};

// The smallest distance between two points of `pts` (a plain plane, O(n) expected with a grid);
// +infinity for fewer than two points.
double min_distance(const std::vector<Point2>& pts);

}  // namespace tilekit::points
