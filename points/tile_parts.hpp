#pragma once
// Internal to points/: the region geometry of Poisson disk tiles (thesis Fig. 4.3(b)) and the
// sampling steps the corner-based, dual and edge-based constructions share.
#include <cmath>
#include <cstdint>
#include <vector>

#include "base/random.hpp"
#include "points/geometry.hpp"
#include "points/sampler.hpp"

namespace tilekit::points::parts {

// Regions around the lattice of unit tiles, for Poisson radius r (points 2r apart).
struct Regions {
  double r = 0;          // edge regions: closer than r to an edge line
  double c = 0;          // corner regions: |x|, |y| < c about a lattice point, c = (1 + sqrt 2) r
  bool octagon = false;  // corner regions cut to the regular octagon of side 2r (Li et al.)

  explicit Regions(double radius, bool oct = false) : r(radius), c((1 + std::sqrt(2.0)) * radius), octagon(oct) {}
  double distance() const { return 2 * r; }
  double corner_area() const;
  double edge_area() const { return 2 * r * (1 - 2 * c); }

  // p relative to a lattice point.
  bool in_corner(Point2 p) const {
    const double ax = std::abs(p.x), ay = std::abs(p.y);
    return ax < c && ay < c && (!octagon || ax + ay < c * std::sqrt(2.0));
  }
  // p relative to the start of a horizontal edge that runs to (1, 0).
  bool in_horizontal_edge(Point2 p) const { return std::abs(p.y) < r && p.x >= c && p.x <= 1 - c; }
  bool in_vertical_edge(Point2 p) const { return std::abs(p.x) < r && p.y >= c && p.y <= 1 - c; }
  // p in tile coordinates: neither in a corner nor an edge region of the tile.
  bool in_interior(Point2 p) const {
    if (p.x < r || p.y < r || p.x > 1 - r || p.y > 1 - r) return false;
    for (double cx : {0.0, 1.0})
      for (double cy : {0.0, 1.0})
        if (in_corner({p.x - cx, p.y - cy})) return false;
    return true;
  }
};

SamplingOptions sampling_options(const Regions& g, int lloyd);

// Samplings tried per corner or edge region to hold its expected share of points.
inline constexpr std::uint64_t kBalancingTries = 6;

// Of a few samplings of a region, the first whose point count is the expected one rounded (or
// the closest): the regions around a tile then hold close to their share of its N points, and
// its interior is neither crowded nor sparse.
template <class F>
std::vector<Point2> balanced(double expected, std::uint64_t seed, F&& make) {
  std::vector<Point2> best;
  double best_gap = 1e300;
  for (std::uint64_t i = 0; i < kBalancingTries; ++i) {
    auto pts = make(i == 0 ? seed : derive_seed(seed, i));
    const double gap = std::abs(double(pts.size()) - expected);
    if (gap < best_gap) best_gap = gap, best = std::move(pts);
    if (best_gap <= 0.5) break;
  }
  return best;
}

// A corner region: N points on the unit torus, cut out about the origin (thesis Fig. 4.19).
std::vector<Point2> corner_region(const Regions& g, std::uint32_t n, const SamplingOptions& o, std::uint64_t seed);

// The edge region from corner region `a` at (0, 0) to `b` at (1, 0) (thesis Fig. 4.21): 2N points
// on the 2 x 1 torus around the two fixed corner regions, cut to the edge region. With
// `half_turn`, the points are symmetric under the half turn about (1/2, 0).
std::vector<Point2> horizontal_edge_region(const Regions& g, std::uint32_t n, const std::vector<Point2>& a,
                                           const std::vector<Point2>& b, bool half_turn, const SamplingOptions& o,
                                           std::uint64_t seed);
// The same on the 1 x 2 torus from `a` at (0, 0) to `b` at (0, 1).
std::vector<Point2> vertical_edge_region(const Regions& g, std::uint32_t n, const std::vector<Point2>& a,
                                         const std::vector<Point2>& b, const SamplingOptions& o, std::uint64_t seed);

// The interior of a unit tile whose corner and edge regions are `frame` (tile coordinates; points
// outside the tile included, they constrain): N minus the frame's points inside the tile
// (thesis Fig. 4.24). `symmetry`: 1, 2 or 4 (rotations about the tile centre).
std::vector<Point2> interior_region(const Regions& g, std::uint32_t n, const std::vector<Point2>& frame, int symmetry,
                                    const SamplingOptions& o, std::uint64_t seed);

// Appends `part` translated by `at`.
void place(const std::vector<Point2>& part, Point2 at, std::vector<Point2>& out);
// The points of `pts` inside [0, 1)^2.
std::vector<Point2> inside_unit_tile(const std::vector<Point2>& pts);

// Corner tile index (thesis eq. 2.5) over L lattice colours, and its four corners.
inline std::uint64_t corner_tile_index(std::uint32_t nw, std::uint32_t ne, std::uint32_t sw, std::uint32_t se,
                                       std::uint32_t l) {
  return ((std::uint64_t(ne) * l + se) * l + sw) * l + nw;
}
struct Corners {
  std::uint32_t nw, ne, sw, se;
};
inline Corners corners_of(std::uint64_t t, std::uint32_t l) {
  Corners c;
  c.nw = std::uint32_t(t % l), t /= l;
  c.sw = std::uint32_t(t % l), t /= l;
  c.se = std::uint32_t(t % l), t /= l;
  c.ne = std::uint32_t(t % l);
  return c;
}

}  // namespace tilekit::points::parts
