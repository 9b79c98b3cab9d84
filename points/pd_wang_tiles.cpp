// Edge-based Poisson disk tiles (thesis sec. 4.3; Lagae and Dutre 2005), the Wang tile
// construction the corner-based one is compared with (thesis sec. 6.9, 6.11): C edge regions
// per direction, then C^4 corner regions around them, then C^12 interiors.
#include <fmt/format.h>

#include "base/parallel.hpp"
#include "base/progress.hpp"
#include "base/random.hpp"
#include "base/signals.hpp"
#include "points/poisson_tiles.hpp"
#include "points/tile_parts.hpp"

namespace tilekit::points {

using parts::Regions;

namespace {

// An edge region of one colour: N points on the unit torus, cut to the tube about `curve` along
// (0,0)-(1,0) (thesis Fig. 4.5); `vertical`: the same turned to run along (0,0)-(0,1).
parts::EdgeRegion edge_region(const Regions& g, std::uint32_t n, std::vector<Point2> curve, bool vertical,
                              const SamplingOptions& o, std::uint64_t seed) {
  SamplingProblem p;
  p.torus = true;
  p.count = n;
  parts::EdgeRegion e;
  for (const Point2& q : sample_poisson_disk(p, o, seed).points) {
    const Point2 c{q.x, wrap_centred(q.y, 1.0)};
    if (!g.in_corner(c) && !g.in_corner({c.x - 1, c.y}) && g.in_tube(c, curve)) e.points.push_back(c);
  }
  e.curve = std::move(curve);
  return vertical ? e.turned(1) : e;
}

struct EdgeScheme {
  std::uint32_t c;
  std::vector<parts::EdgeRegion> h, v;
  std::vector<std::vector<Point2>> corner;  // corner[((n C + e) C + s) C + w]

  // The edge regions incident to a lattice point: north-going n, east-going e, south-going s,
  // west-going w, placed about the point at `at`.
  void place_star(std::uint32_t n, std::uint32_t e, std::uint32_t s, std::uint32_t w, Point2 at,
                  parts::Frame& out) const {
    out.add_edge(v[n], {at.x, at.y - 1});
    out.add_edge(h[e], at);
    out.add_edge(v[s], at);
    out.add_edge(h[w], {at.x - 1, at.y});
  }
  std::uint32_t star(std::uint32_t n, std::uint32_t e, std::uint32_t s, std::uint32_t w) const {
    return ((n * c + e) * c + s) * c + w;
  }
  // The corner and edge regions of the tile with colours k (wang_pd_tile_index order).
  parts::Frame frame(const std::uint32_t k[12]) const {
    const std::uint32_t N = k[0], E = k[1], S = k[2], W = k[3];
    parts::Frame f;
    f.add_corner(corner[star(k[4], N, W, k[5])], {0, 0});    // NW: north-going, east = N, south = W, west-going
    f.add_corner(corner[star(k[6], k[7], E, N)], {1, 0});    // NE: north-going, east-going, south = E, west = N
    f.add_corner(corner[star(E, k[9], k[8], S)], {1, 1});    // SE: north = E, east-going, south-going, west = S
    f.add_corner(corner[star(W, S, k[10], k[11])], {0, 1});  // SW: north = W, east = S, south-going, west-going
    f.add_edge(h[N], {0, 0});
    f.add_edge(h[S], {0, 1});
    f.add_edge(v[W], {0, 0});
    f.add_edge(v[E], {1, 0});
    return f;
  }
};

void colours_of(std::uint64_t t, std::uint32_t c, std::uint32_t k[12]) {
  for (int i = 11; i >= 0; --i) k[i] = std::uint32_t(t % c), t /= c;
}

}  // namespace

PoissonTileSet build_wang_poisson_tiles(const PoissonTileParams& p, const Regions& g, ProgressReporter& progress) {
  const std::uint32_t c = p.colours, n = p.points;
  const SamplingOptions opts = parts::sampling_options(g, p.lloyd);
  EdgeScheme s{c, std::vector<parts::EdgeRegion>(c), std::vector<parts::EdgeRegion>(c),
               std::vector<std::vector<Point2>>(std::size_t(c) * c * c * c)};
  std::uint64_t tiles = 1;
  for (int i = 0; i < 12; ++i) tiles *= c;
  progress.set_total(double(2 * c + s.corner.size() + tiles));
  const auto seed_of = [&](std::uint64_t step, std::uint64_t i) { return derive_seed(derive_seed(p.seed, step), i); };
  auto run = [&](std::size_t count, auto&& body) {
    parallel_for(std::int64_t(count), p.threads, [&](std::int64_t i) {
      throw_if_interrupted();  // a caught signal ends the build (base/signals.hpp)
      body(std::size_t(i));
      progress.add(1);
    });
  };
  run(2 * c, [&](std::size_t i) {
    auto& dst = i < c ? s.h[i] : s.v[i - c];
    dst = edge_region(g, n, parts::random_curve(g, seed_of(4, i)), i >= c, opts, seed_of(1, i));
  });
  // thesis Fig. 4.7: each corner region assembled with its four edge regions, on a 2 x 2 torus
  // about the lattice point (so that the north- and south-going regions are distinct), 4N points.
  run(s.corner.size(), [&](std::size_t i) {
    const std::uint32_t w = std::uint32_t(i % c), so = std::uint32_t(i / c % c), e = std::uint32_t(i / c / c % c),
                        no = std::uint32_t(i / c / c / c);
    SamplingProblem q;
    q.x0 = q.y0 = -1;
    q.w = q.h = 2;
    q.torus = true;
    parts::Frame star;
    s.place_star(no, e, so, w, {0, 0}, star);
    q.fixed = star.points;
    q.free = [&g, &star](Point2 a) {
      const Point2 b{wrap_centred(a.x, 2.0), wrap_centred(a.y, 2.0)};
      for (const auto& curve : star.curves)
        if (g.in_tube(b, curve)) return false;
      return true;
    };
    q.count = 4 * std::size_t(n) - q.fixed.size();
    for (const Point2& a : sample_poisson_disk(q, opts, seed_of(2, i)).points) {
      const Point2 b{wrap_centred(a.x, 2.0), wrap_centred(a.y, 2.0)};
      if (g.in_corner(b)) s.corner[i].push_back(b);
    }
  });
  PoissonTileSet set;
  set.method = PoissonTileMethod::Wang;
  set.colours = c;
  set.points = n;
  set.rho = p.rho;
  set.radius = p.rho * max_poisson_radius(n);
  set.lloyd = p.lloyd;
  set.seed = p.seed;
  set.tiles.resize(tiles);
  run(tiles, [&](std::size_t t) {
    std::uint32_t k[12];
    colours_of(t, c, k);
    const auto f = s.frame(k);
    auto pts = parts::inside_unit_tile(f.points);
    const auto in = parts::interior_region(g, n, f, 1, opts, seed_of(3, t));
    pts.insert(pts.end(), in.begin(), in.end());
    set.tiles[t] = std::move(pts);
  });
  progress.finish();
  set.corner_regions = s.corner.size();
  set.edge_regions = 2 * c;
  set.interiors = tiles;
  return set;
}

}  // namespace tilekit::points
