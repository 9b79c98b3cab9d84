#pragma once
// Radius analysis of a point set (thesis sec. 6.2.1; the "min dist" and "avg min dist" of the
// PSA tool of Heck, Schloemer and Deussen): the smallest and the average nearest-neighbour
// distance, and the relative radius rho = r / r_max (r half the smallest distance, r_max that
// of the hexagonal lattice of the same density, thesis eq. 4.2-4.3), globally and, for tiled
// sets, separately for pairs inside one tile and pairs across tile borders.
#include <cstdint>
#include <vector>

#include "points/geometry.hpp"

namespace tilekit::points {

struct RadiusStats {
  std::uint64_t count = 0;
  double density = 0;           // points per unit area of the window
  double min_distance = 0;      // smallest distance between two points
  double mean_nn_distance = 0;  // average distance from a point to its nearest neighbour
  double rho = 0;               // relative radius (thesis eq. 4.3)
  double mean_nn_relative = 0;  // mean_nn_distance / (2 r_max): 1 for the hexagonal lattice
  // With a tile size: the same smallest distance, split by whether the two points lie in the
  // same tile or in different tiles (tile (i, j) = [i s, (i+1) s) x [j s, (j+1) s)).
  bool tiled = false;
  double rho_within = 0, rho_across = 0;
  double min_within = 0, min_across = 0;
};

// `xy`: interleaved (x, y); `area`: the window's area (the density is count / area).
// `tile_size` > 0 splits by tiles. Pairs farther apart than twice the mean spacing are not
// looked at: a category with no closer pair reports that bound.
RadiusStats radius_stats(const std::vector<double>& xy, double area, double tile_size = 0);
RadiusStats radius_stats(const std::vector<Point2>& pts, double area, double tile_size = 0);

}  // namespace tilekit::points
