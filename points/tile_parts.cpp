#include "points/tile_parts.hpp"

#include <fmt/format.h>

#include "base/error.hpp"
#include "base/random.hpp"

namespace tilekit::points::parts {

SamplingOptions sampling_options(const Regions& g, int lloyd) {
  SamplingOptions o;
  o.min_distance = g.distance();
  o.lloyd = lloyd;
  return o;
}

double Regions::corner_area() const {
  return octagon ? 8 * (std::sqrt(2.0) - 1) * c * c : 4 * c * c;
}

std::vector<Point2> corner_region(const Regions& g, std::uint32_t n, const SamplingOptions& o, std::uint64_t seed) {
  return balanced(n * g.corner_area(), seed, [&](std::uint64_t s) {
    SamplingProblem p;
    p.torus = true;
    p.count = n;
    std::vector<Point2> out;
    for (const Point2& q : sample_poisson_disk(p, o, s).points) {
      const Point2 c{wrap_centred(q.x, 1.0), wrap_centred(q.y, 1.0)};
      if (g.in_corner(c)) out.push_back(c);
    }
    return out;
  });
}

namespace {

// Points of `pts` (on a torus w x h) in the edge region starting at the origin.
std::vector<Point2> cut_edge(const Regions& g, const std::vector<Point2>& pts, bool horizontal, double w, double h) {
  std::vector<Point2> out;
  for (const Point2& q : pts) {
    const Point2 c{horizontal ? q.x : wrap_centred(q.x, w), horizontal ? wrap_centred(q.y, h) : q.y};
    if (horizontal ? g.in_horizontal_edge(c) : g.in_vertical_edge(c)) out.push_back(c);
  }
  return out;
}

}  // namespace

std::vector<Point2> horizontal_edge_region(const Regions& g, std::uint32_t n, const std::vector<Point2>& a,
                                           const std::vector<Point2>& b, bool half_turn, const SamplingOptions& o,
                                           std::uint64_t seed) {
  SamplingProblem p;
  p.w = 2;
  p.h = 1;
  p.torus = true;
  place(a, {0, 0}, p.fixed);
  place(b, {1, 0}, p.fixed);
  p.free = [&g](Point2 q) {
    const double y = wrap_centred(q.y, 1.0);
    return !g.in_corner({wrap_centred(q.x, 2.0), y}) && !g.in_corner({wrap_centred(q.x - 1, 2.0), y});
  };
  if (2 * std::size_t(n) < p.fixed.size()) throw InputError("corner regions hold more than 2N points");
  p.count = 2 * std::size_t(n) - p.fixed.size();
  if (half_turn) {
    p.symmetry_order = 2;
    p.centre = {0.5, 0};
  }
  return balanced(n * g.edge_area(), seed,
                  [&](std::uint64_t s) { return cut_edge(g, sample_poisson_disk(p, o, s).points, true, 2, 1); });
}

std::vector<Point2> vertical_edge_region(const Regions& g, std::uint32_t n, const std::vector<Point2>& a,
                                         const std::vector<Point2>& b, const SamplingOptions& o, std::uint64_t seed) {
  SamplingProblem p;
  p.w = 1;
  p.h = 2;
  p.torus = true;
  place(a, {0, 0}, p.fixed);
  place(b, {0, 1}, p.fixed);
  p.free = [&g](Point2 q) {
    const double x = wrap_centred(q.x, 1.0);
    return !g.in_corner({x, wrap_centred(q.y, 2.0)}) && !g.in_corner({x, wrap_centred(q.y - 1, 2.0)});
  };
  if (2 * std::size_t(n) < p.fixed.size()) throw InputError("corner regions hold more than 2N points");
  p.count = 2 * std::size_t(n) - p.fixed.size();
  return balanced(n * g.edge_area(), seed,
                  [&](std::uint64_t s) { return cut_edge(g, sample_poisson_disk(p, o, s).points, false, 1, 2); });
}

std::vector<Point2> interior_region(const Regions& g, std::uint32_t n, const std::vector<Point2>& frame, int symmetry,
                                    const SamplingOptions& o, std::uint64_t seed) {
  SamplingProblem p;
  p.fixed = frame;
  p.free = [&g](Point2 q) { return g.in_interior(q); };
  const std::size_t inside = inside_unit_tile(frame).size();
  if (inside > n)
    throw InputError(
        fmt::format("the corner and edge regions put {} points into a tile of {}: raise --points", inside, n));
  p.count = n - inside;
  p.symmetry_order = symmetry;
  p.centre = {0.5, 0.5};
  return sample_poisson_disk(p, o, seed).points;
}

void place(const std::vector<Point2>& part, Point2 at, std::vector<Point2>& out) {
  for (const Point2& q : part) out.push_back({q.x + at.x, q.y + at.y});
}

std::vector<Point2> inside_unit_tile(const std::vector<Point2>& pts) {
  std::vector<Point2> out;
  for (const Point2& q : pts)
    if (q.x >= 0 && q.x < 1 && q.y >= 0 && q.y < 1) out.push_back(q);
  return out;
}

}  // namespace tilekit::points::parts
