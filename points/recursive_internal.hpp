#pragma once
// Internal to points/: the construction steps of recursive Wang tiles (recursive_tiles.hpp).
#include <cstdint>
#include <vector>

#include "points/geometry.hpp"

namespace tilekit::points::recursive {

// A point of a tile under construction: where it is and its rank in the source it came from.
struct RankedPoint {
  Point2 p;
  std::uint32_t source = 0, rank = 0;
};

// N points on the unit torus in the order relaxation dart throwing accepted them.
std::vector<Point2> progressive_source(std::uint32_t n, std::uint64_t seed);

// Kopf et al. sec. 4: the points of `tile` west of the seam and of `source` east of it, the seam
// a min-cost path from the NE to the SE corner over the Voronoi edges of their union.
std::vector<RankedPoint> merge_east(const std::vector<RankedPoint>& tile, const std::vector<RankedPoint>& source);

// Kopf et al. Fig. 5: the source rankings interleaved, then fixed greedily.
std::vector<Point2> progressive_order(std::vector<RankedPoint> pts, std::uint64_t seed);

}  // namespace tilekit::points::recursive
