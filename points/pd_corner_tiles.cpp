// Corner-based Poisson disk tiles (thesis sec. 4.5) and their rotatable dual variant (Li et
// al., planar). Both colour the lattice points (L colours or states) and build a tile from the
// corner regions at its four corners, the edge regions along its four edges and an interior.
#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <chrono>

#include "base/error.hpp"
#include "base/parallel.hpp"
#include "base/progress.hpp"
#include "base/random.hpp"
#include "base/signals.hpp"
#include "points/poisson_tiles.hpp"
#include "points/tile_parts.hpp"

namespace tilekit::points {

using parts::Regions;

namespace {

// The regions of a corner-coloured lattice over L states whose edges carry E edge colours: a
// corner region per state, a horizontal and a vertical edge region per ordered pair of states
// and edge colour (index (a L + b) E + e), an interior per tile.
struct CornerScheme {
  std::uint32_t l = 0, ec = 1;
  std::vector<std::vector<Point2>> corner, interior;
  std::vector<parts::EdgeRegion> hedge, vedge;

  // The corner and edge regions around tile t (corners NW, NE, SW, SE; edges N, E, S, W), in
  // tile coordinates.
  parts::Frame frame(std::uint64_t t) const {
    const std::uint64_t l4 = std::uint64_t(l) * l * l * l, edges = t / l4;
    const auto k = parts::corners_of(t % l4, l);
    const std::uint32_t w = std::uint32_t(edges % ec), s = std::uint32_t(edges / ec % ec),
                        e = std::uint32_t(edges / ec / ec % ec), n = std::uint32_t(edges / ec / ec / ec);
    parts::Frame f;
    f.add_corner(corner[k.nw], {0, 0});
    f.add_corner(corner[k.ne], {1, 0});
    f.add_corner(corner[k.sw], {0, 1});
    f.add_corner(corner[k.se], {1, 1});
    f.add_edge(hedge[(k.nw * l + k.ne) * ec + n], {0, 0});
    f.add_edge(hedge[(k.sw * l + k.se) * ec + s], {0, 1});
    f.add_edge(vedge[(k.nw * l + k.sw) * ec + w], {0, 0});
    f.add_edge(vedge[(k.ne * l + k.se) * ec + e], {1, 0});
    return f;
  }
  std::vector<Point2> tile(std::uint64_t t) const {
    std::vector<Point2> pts = parts::inside_unit_tile(frame(t).points);
    pts.insert(pts.end(), interior[t].begin(), interior[t].end());
    return pts;
  }
};

// Runs body(i) for i < n on the set's threads, one progress unit each; a caught signal ends the
// loop (Interrupted: the set is not finished, nothing is written).
template <class F>
void for_each_task(std::size_t n, int threads, ProgressReporter& progress, F&& body) {
  parallel_for(std::int64_t(n), threads, [&](std::int64_t i) {
    throw_if_interrupted();
    body(std::size_t(i));
    progress.add(1);
  });
}

// ---- the dual (rotatable) scheme: a state is o * C + k, colour k turned o quarter turns ----

struct Dual {
  std::uint32_t c;
  std::uint32_t turn(std::uint32_t s, int q) const { return ((s / c + std::uint32_t(q)) % 4) * c + s % c; }
  // A horizontal edge (a, b) and its half-turned partner (b turned twice, a turned twice).
  std::uint32_t partner(std::uint32_t e, std::uint32_t l) const { return turn(e % l, 2) * l + turn(e / l, 2); }
  // Tile (NW, NE, SW, SE) turned a quarter about its centre: NW <- SW, NE <- NW, SE <- NE, SW <- SE.
  std::uint64_t turn_tile(std::uint64_t t, std::uint32_t l) const {
    const auto k = parts::corners_of(t, l);
    return parts::corner_tile_index(turn(k.sw, 1), turn(k.nw, 1), turn(k.se, 1), turn(k.ne, 1), l);
  }
};

std::vector<Point2> turned(const std::vector<Point2>& pts, int q, Point2 centre = {}) {
  std::vector<Point2> out;
  out.reserve(pts.size());
  for (const Point2& p : pts) out.push_back(rotate_quarter(p, q, centre));
  return out;
}

}  // namespace

// Declared in pd_wang_tiles.cpp.
PoissonTileSet build_wang_poisson_tiles(const PoissonTileParams& p, const Regions& g, ProgressReporter& progress);

PoissonTileSet build_poisson_tiles(const PoissonTileParams& asked) {
  check_poisson_tile_params(asked);
  PoissonTileParams p = asked;
  if (p.points == 0) p.points = default_tile_points(p.method);
  const auto start = std::chrono::steady_clock::now();
  const double r = p.rho * max_poisson_radius(p.points);
  const Regions g(r * (1 + kMargin), p.method == PoissonTileMethod::Dual);
  const SamplingOptions opts = parts::sampling_options(g, p.lloyd);
  const std::uint32_t c = p.colours, n = p.points;
  PoissonTileSet set;
  set.method = p.method;
  set.colours = c;
  set.edge_colours = p.edge_colours;
  set.points = n;
  set.rho = p.rho;
  set.radius = r;
  set.lloyd = p.lloyd;
  set.seed = p.seed;
  const std::uint32_t l = set.lattice_colours();
  ProgressReporter progress(fmt::format("points tiles {} C={} N={}", method_name(p.method), c, n), 0, p.progress);

  if (p.method == PoissonTileMethod::Wang) {
    PoissonTileSet w = build_wang_poisson_tiles(p, g, progress);
    w.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return w;
  }

  CornerScheme s;
  s.l = l;
  s.ec = set.edge_colours;
  const std::size_t ec4 = std::size_t(s.ec) * s.ec * s.ec * s.ec;
  const std::size_t tiles = std::size_t(l) * l * l * l * ec4, edge_count = std::size_t(l) * l * s.ec;
  s.corner.resize(l);
  s.hedge.resize(edge_count);
  s.vedge.resize(edge_count);
  s.interior.resize(tiles);
  const auto seed_of = [&](std::uint64_t step, std::uint64_t i) { return derive_seed(derive_seed(p.seed, step), i); };

  if (p.method == PoissonTileMethod::Corner) {
    progress.set_total(double(c + 2 * edge_count + tiles));
    // thesis sec. 4.5: corner regions, then edge regions around them, then interiors.
    for_each_task(c, p.threads, progress,
                  [&](std::size_t k) { s.corner[k] = parts::corner_region(g, n, opts, seed_of(1, k)); });
    for_each_task(2 * edge_count, p.threads, progress, [&](std::size_t i) {
      const std::size_t e = i / 2, a = e / s.ec / l, b = e / s.ec % l;
      if (i % 2 == 0)
        s.hedge[e] = parts::horizontal_edge_region(g, n, s.corner[a], s.corner[b],
                                                   parts::random_curve(g, seed_of(5, e)), false, opts, seed_of(2, e));
      else
        s.vedge[e] = parts::vertical_edge_region(
            g, n, s.corner[a], s.corner[b],
            parts::EdgeRegion{{}, parts::random_curve(g, seed_of(6, e))}.turned(1).curve, opts, seed_of(3, e));
    });
    for_each_task(tiles, p.threads, progress, [&](std::size_t t) {
      s.interior[t] = parts::interior_region(g, n, s.frame(t), 1, opts, seed_of(4, t));
    });
    set.corner_regions = c;
    set.edge_regions = 2 * edge_count;
    set.interiors = tiles;
  } else {
    // Li et al.: C corner regions, turned by each state's orientation.
    const Dual d{c};
    std::vector<std::vector<Point2>> base(c);
    std::vector<std::size_t> edges, interiors;
    for (std::uint32_t e = 0; e < l * l; ++e)
      if (e <= d.partner(e, l)) edges.push_back(e);
    for (std::uint64_t t = 0; t < tiles; ++t) {
      std::uint64_t m = t;
      for (std::uint64_t u = d.turn_tile(t, l); u != t; u = d.turn_tile(u, l)) m = std::min(m, u);
      if (m == t) interiors.push_back(t);
    }
    progress.set_total(double(c + edges.size() + interiors.size()));
    for_each_task(c, p.threads, progress,
                  [&](std::size_t k) { base[k] = parts::corner_region(g, n, opts, seed_of(1, k)); });
    for (std::uint32_t st = 0; st < l; ++st) s.corner[st] = turned(base[st % c], int(st / c));
    // Horizontal edge regions up to a half turn (8C^2 + 2C of them); self-partnered ones are
    // half-turn symmetric. Vertical edge (a, b) is horizontal edge (a, b turned back) turned once.
    for_each_task(edges.size(), p.threads, progress, [&](std::size_t i) {
      const std::uint32_t e = std::uint32_t(edges[i]), a = e / l, b = e % l;
      const bool self = d.partner(e, l) == e;
      s.hedge[e] = parts::horizontal_edge_region(
          g, n, s.corner[a], s.corner[b], parts::random_curve(g, seed_of(5, e), self), self, opts, seed_of(2, e));
    });
    for (std::uint32_t e : edges) s.hedge[d.partner(e, l)] = s.hedge[e].turned(2, {0.5, 0});
    for (std::uint32_t a = 0; a < l; ++a)
      for (std::uint32_t b = 0; b < l; ++b) s.vedge[a * l + b] = s.hedge[d.turn(a, 3) * l + d.turn(b, 3)].turned(1);
    // Interiors up to quarter turns (64C^4 + 4C^2 + 2C), symmetric under their stabiliser.
    for_each_task(interiors.size(), p.threads, progress, [&](std::size_t i) {
      const std::uint64_t t = interiors[i];
      int order = 1;
      for (std::uint64_t u = d.turn_tile(t, l); u != t; u = d.turn_tile(u, l)) ++order;
      s.interior[t] = parts::interior_region(g, n, s.frame(t), 4 / order, opts, seed_of(4, t));
    });
    for (std::uint64_t t : interiors) {
      std::uint64_t u = t;
      for (int q = 1; q < 4; ++q)
        if ((u = d.turn_tile(u, l)) != t) s.interior[u] = turned(s.interior[t], q, {0.5, 0.5});
    }
    set.corner_regions = c;
    set.edge_regions = edges.size();
    set.interiors = interiors.size();
  }
  set.tiles.resize(tiles);
  for (std::size_t t = 0; t < tiles; ++t) {
    set.tiles[t] = s.tile(t);
    assert(set.tiles[t].size() == n);
  }
  progress.finish();
  set.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return set;
}

}  // namespace tilekit::points
