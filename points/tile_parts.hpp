#pragma once
// Internal to points/: the region geometry of Poisson disk tiles (thesis Fig. 4.3(b)) and the
// sampling steps the corner-based, dual and edge-based constructions share.
//
// An edge region is the set of points closer than r to the edge's curve, minus the corner regions
// at its ends. The thesis' curve is the edge itself; here every edge region has its own curve,
// straight within the corner regions and wiggling by up to r (slope at most 1) in between. Any
// curve keeps the construction sound (two points on opposite sides of a tube of radius r around a
// curve are 2r apart: the segment between them crosses the curve), and curves that differ from
// edge to edge move the border between independently sampled regions from tile to tile. With the
// straight edges of the thesis that border is the same line in every tile; points pile up along
// it and the tiling's spectrum grows spikes on the axes (points/README.md, "Why the tiles showed").
#include <cmath>
#include <cstdint>
#include <vector>

#include "points/geometry.hpp"
#include "points/sampler.hpp"

namespace tilekit::points::parts {

// Whether p is closer than d to the polyline `curve`.
bool within_polyline(Point2 p, const std::vector<Point2>& curve, double d);

// Regions around the lattice of unit tiles, for Poisson radius r (points 2r apart).
struct Regions {
  double r = 0;          // edge regions: closer than r to the edge's curve
  double c = 0;          // corner regions: |x|, |y| < c about a lattice point, c = (1 + sqrt 2) r
  bool octagon = false;  // corner regions cut to the regular octagon of side 2r (Li et al.)

  explicit Regions(double radius, bool oct = false) : r(radius), c((1 + std::sqrt(2.0)) * radius), octagon(oct) {}
  double distance() const { return 2 * r; }

  // p relative to a lattice point.
  bool in_corner(Point2 p) const {
    const double ax = std::abs(p.x), ay = std::abs(p.y);
    return ax < c && ay < c && (!octagon || ax + ay < c * std::sqrt(2.0));
  }
  // p in tile coordinates: in none of the tile's corner regions.
  bool outside_corners(Point2 p) const {
    for (double cx : {0.0, 1.0})
      for (double cy : {0.0, 1.0})
        if (in_corner({p.x - cx, p.y - cy})) return false;
    return true;
  }
  bool in_tube(Point2 p, const std::vector<Point2>& curve) const { return within_polyline(p, curve, r); }
};

// An edge region: its points and its curve, in one frame. The canonical frame is a horizontal
// edge from (0, 0) to (1, 0).
struct EdgeRegion {
  std::vector<Point2> points, curve;
  EdgeRegion turned(int quarter_turns, Point2 centre = {}) const;
  EdgeRegion shifted(Point2 by) const;
};

// A random curve for a horizontal edge from (0, 0) to (1, 0): straight up to x = c and from
// 1 - c, a sum of sine harmonics in between, at most r from the edge and of slope at most 1.
// `odd`: symmetric under the half turn about (1/2, 0) (even harmonics only), for edges that are
// their own partner in the dual construction.
std::vector<Point2> random_curve(const Regions& g, std::uint64_t seed, bool odd = false);

SamplingOptions sampling_options(const Regions& g, int lloyd);

// A corner region: N points on the unit torus, cut out about the origin (thesis Fig. 4.19).
std::vector<Point2> corner_region(const Regions& g, std::uint32_t n, const SamplingOptions& o, std::uint64_t seed);

// The edge region along `curve` from corner region `a` at (0, 0) to `b` at (1, 0) (thesis
// Fig. 4.21): 2N points on the 2 x 1 torus around the two fixed corner regions, cut to the tube.
// With `half_turn`, the points are symmetric under the half turn about (1/2, 0).
EdgeRegion horizontal_edge_region(const Regions& g, std::uint32_t n, const std::vector<Point2>& a,
                                  const std::vector<Point2>& b, std::vector<Point2> curve, bool half_turn,
                                  const SamplingOptions& o, std::uint64_t seed);
// The same on the 1 x 2 torus from `a` at (0, 0) to `b` at (0, 1); `curve` in that frame.
EdgeRegion vertical_edge_region(const Regions& g, std::uint32_t n, const std::vector<Point2>& a,
                                const std::vector<Point2>& b, std::vector<Point2> curve, const SamplingOptions& o,
                                std::uint64_t seed);

// The corner and edge regions around one tile, in tile coordinates: their points (those outside
// the tile included, they constrain) and the curves of the tile's four edges.
struct Frame {
  std::vector<Point2> points;
  std::vector<std::vector<Point2>> curves;
  void add_corner(const std::vector<Point2>& pts, Point2 at);
  void add_edge(const EdgeRegion& e, Point2 at);
  // Neither in a corner region nor in an edge region of the tile.
  bool interior(const Regions& g, Point2 p) const;
};

// The interior of a unit tile (thesis Fig. 4.24): N minus the frame's points inside the tile,
// with context points in the gaps of the frame. `symmetry`: 1, 2 or 4 (about the tile centre).
std::vector<Point2> interior_region(const Regions& g, std::uint32_t n, const Frame& frame, int symmetry,
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
