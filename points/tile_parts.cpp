#include "points/tile_parts.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <numbers>

#include "base/error.hpp"
#include "base/random.hpp"

namespace tilekit::points::parts {

namespace {

// Squared distance from p to the segment ab.
double segment_distance2(Point2 p, Point2 a, Point2 b) {
  const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
  const double t = len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
  return squared_distance(p, {a.x + t * dx, a.y + t * dy});
}

}  // namespace

bool within_polyline(Point2 p, const std::vector<Point2>& curve, double d) {
  const double d2 = d * d;
  for (std::size_t i = 0; i + 1 < curve.size(); ++i) {
    const Point2 a = curve[i], b = curve[i + 1];
    // Segments whose bounding box is d or more away cannot be closer.
    if (p.x + d <= std::min(a.x, b.x) || p.x - d >= std::max(a.x, b.x) || p.y + d <= std::min(a.y, b.y) ||
        p.y - d >= std::max(a.y, b.y))
      continue;
    if (segment_distance2(p, a, b) < d2) return true;
  }
  return false;
}

EdgeRegion EdgeRegion::turned(int q, Point2 centre) const {
  EdgeRegion e;
  for (const Point2& p : points) e.points.push_back(rotate_quarter(p, q, centre));
  for (const Point2& p : curve) e.curve.push_back(rotate_quarter(p, q, centre));
  return e;
}

EdgeRegion EdgeRegion::shifted(Point2 by) const {
  EdgeRegion e;
  for (const Point2& p : points) e.points.push_back({p.x + by.x, p.y + by.y});
  for (const Point2& p : curve) e.curve.push_back({p.x + by.x, p.y + by.y});
  return e;
}

std::vector<Point2> random_curve(const Regions& g, std::uint64_t seed, bool odd) {
  SplitMix64 rng(seed);
  constexpr int kHarmonics = 4, kVertices = 40;
  double a[kHarmonics + 1] = {};
  for (int k = 1; k <= kHarmonics; ++k)
    if (!odd || k % 2 == 0) a[k] = (2 * rng.uniform() - 1) / k;
  const double x0 = g.c, len = 1 - 2 * g.c;
  const auto shape = [&](double x) {
    if (x <= x0 || x >= x0 + len) return 0.0;
    double y = 0;
    for (int k = 1; k <= kHarmonics; ++k) y += a[k] * std::sin(k * std::numbers::pi * (x - x0) / len);
    return y;
  };
  // Scale to a random amplitude up to r, with slope at most 0.9.
  double peak = 1e-300, slope = 1e-300;
  for (int i = 0; i <= 400; ++i) {
    const double x = x0 + len * i / 400.0;
    peak = std::max(peak, std::abs(shape(x)));
    if (i > 0) slope = std::max(slope, std::abs(shape(x) - shape(x - len / 400.0)) / (len / 400.0));
  }
  const double scale = std::min(g.r * (0.5 + 0.5 * rng.uniform()) / peak, 0.9 / slope);
  std::vector<Point2> curve = {{0, 0}};
  for (int i = 0; i <= kVertices; ++i) {
    const double x = x0 + len * i / kVertices;
    curve.push_back({x, scale * shape(x)});
  }
  curve.push_back({1, 0});
  return curve;
}

SamplingOptions sampling_options(const Regions& g, int lloyd) {
  SamplingOptions o;
  o.min_distance = g.distance();
  o.lloyd = lloyd;
  return o;
}

std::vector<Point2> corner_region(const Regions& g, std::uint32_t n, const SamplingOptions& o, std::uint64_t seed) {
  SamplingProblem p;
  p.torus = true;
  p.count = n;
  std::vector<Point2> out;
  for (const Point2& q : sample_poisson_disk(p, o, seed).points) {
    const Point2 c{wrap_centred(q.x, 1.0), wrap_centred(q.y, 1.0)};
    if (g.in_corner(c)) out.push_back(c);
  }
  return out;
}

EdgeRegion horizontal_edge_region(const Regions& g, std::uint32_t n, const std::vector<Point2>& a,
                                  const std::vector<Point2>& b, std::vector<Point2> curve, bool half_turn,
                                  const SamplingOptions& o, std::uint64_t seed) {
  SamplingProblem p;
  p.w = 2;
  p.h = 1;
  p.torus = true;
  place(a, {0, 0}, p.fixed);
  place(b, {1, 0}, p.fixed);
  const auto near_corner = [&g](Point2 q) {
    const double y = wrap_centred(q.y, 1.0);
    return g.in_corner({wrap_centred(q.x, 2.0), y}) || g.in_corner({wrap_centred(q.x - 1, 2.0), y});
  };
  p.free = [near_corner](Point2 q) { return !near_corner(q); };
  if (2 * std::size_t(n) < p.fixed.size()) throw InputError("corner regions hold more than 2N points");
  p.count = 2 * std::size_t(n) - p.fixed.size();
  if (half_turn) {
    p.symmetry_order = 2;
    p.centre = {0.5, 0};
  }
  EdgeRegion e;
  for (const Point2& q : sample_poisson_disk(p, o, seed).points) {
    const Point2 c{q.x, wrap_centred(q.y, 1.0)};
    if (c.x <= 1 && !near_corner(c) && g.in_tube(c, curve)) e.points.push_back(c);
  }
  e.curve = std::move(curve);
  return e;
}

EdgeRegion vertical_edge_region(const Regions& g, std::uint32_t n, const std::vector<Point2>& a,
                                const std::vector<Point2>& b, std::vector<Point2> curve, const SamplingOptions& o,
                                std::uint64_t seed) {
  SamplingProblem p;
  p.w = 1;
  p.h = 2;
  p.torus = true;
  place(a, {0, 0}, p.fixed);
  place(b, {0, 1}, p.fixed);
  const auto near_corner = [&g](Point2 q) {
    const double x = wrap_centred(q.x, 1.0);
    return g.in_corner({x, wrap_centred(q.y, 2.0)}) || g.in_corner({x, wrap_centred(q.y - 1, 2.0)});
  };
  p.free = [near_corner](Point2 q) { return !near_corner(q); };
  if (2 * std::size_t(n) < p.fixed.size()) throw InputError("corner regions hold more than 2N points");
  p.count = 2 * std::size_t(n) - p.fixed.size();
  EdgeRegion e;
  for (const Point2& q : sample_poisson_disk(p, o, seed).points) {
    const Point2 c{wrap_centred(q.x, 1.0), q.y};
    if (c.y <= 1 && !near_corner(c) && g.in_tube(c, curve)) e.points.push_back(c);
  }
  e.curve = std::move(curve);
  return e;
}

void Frame::add_corner(const std::vector<Point2>& pts, Point2 at) {
  place(pts, at, points);
}

void Frame::add_edge(const EdgeRegion& e, Point2 at) {
  place(e.points, at, points);
  curves.push_back(e.shifted(at).curve);
}

bool Frame::interior(const Regions& g, Point2 p) const {
  if (p.x < 0 || p.y < 0 || p.x >= 1 || p.y >= 1 || !g.outside_corners(p)) return false;
  // Only edges whose tube can reach p: every curve stays within r of its edge line, which is at
  // least min(x, 1 - x, y, 1 - y) away.
  if (std::min({p.x, 1 - p.x, p.y, 1 - p.y}) >= 2 * g.r) return true;
  for (const auto& c : curves)
    if (g.in_tube(p, c)) return false;
  return true;
}

std::vector<Point2> interior_region(const Regions& g, std::uint32_t n, const Frame& frame, int symmetry,
                                    const SamplingOptions& o, std::uint64_t seed) {
  SamplingProblem p;
  // The tile and a margin of one distance around it, so that the fixed points there constrain.
  const double m = g.distance();
  p.x0 = p.y0 = -m;
  p.w = p.h = 1 + 2 * m;
  p.fixed = frame.points;
  p.free = [&g, &frame](Point2 q) { return frame.interior(g, q); };
  const std::size_t inside = inside_unit_tile(frame.points).size();
  if (inside > n)
    throw RequestError(
        "points",
        fmt::format("the corner and edge regions put {} points into a tile of {}: raise `points`", inside, n));
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
