// Parameters, names and the independent check of Poisson disk tile sets.
#include "points/poisson_tiles.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include "base/error.hpp"
#include "base/parallel.hpp"
#include "base/random.hpp"
#include "base/signals.hpp"
#include "points/tile_parts.hpp"
#include "tilesets/tile_set.hpp"

namespace tilekit::points {

const char* method_name(PoissonTileMethod m) {
  switch (m) {
    case PoissonTileMethod::Corner:
      return "corner";
    case PoissonTileMethod::Wang:
      return "wang";
    case PoissonTileMethod::Dual:
      return "dual";
  }
  return "?";
}

PoissonTileMethod parse_poisson_tile_method(const std::string& name) {
  if (name == "corner") return PoissonTileMethod::Corner;
  if (name == "wang") return PoissonTileMethod::Wang;
  if (name == "dual") return PoissonTileMethod::Dual;
  throw InputError(fmt::format("unknown tile method '{}' (expected corner, wang or dual)", name));
}

double PoissonTileSet::guaranteed_distance() const {
  return 2 * radius * (1 + kMargin);
}

std::uint32_t default_tile_points(PoissonTileMethod m) {
  return m == PoissonTileMethod::Corner ? 1024 : 64;
}

void check_poisson_tile_params(const PoissonTileParams& asked) {
  PoissonTileParams p = asked;
  if (p.points == 0) p.points = default_tile_points(p.method);
  check_complete_set_colours(p.colours, "`colours`");
  if (p.edge_colours < 1 || p.edge_colours > 16)
    throw RequestError("edge_colours", fmt::format("`edge_colours` must be 1..16, got {}", p.edge_colours));
  if (p.edge_colours > 1 && p.method != PoissonTileMethod::Corner)
    throw RequestError("edge_colours",
                       fmt::format("`edge_colours` applies to `method` corner, not {}", method_name(p.method)));
  if (p.points < 1 || p.points > 65536)
    throw RequestError("points", fmt::format("`points` must be 1..65536, got {}", p.points));
  if (!(p.rho > 0 && p.rho < 1)) throw RequestError("rho", fmt::format("`rho` must be in (0, 1), got {}", p.rho));
  if (p.lloyd < 0 || p.lloyd > 10000)
    throw RequestError("lloyd", fmt::format("`lloyd` must be 0..10000, got {}", p.lloyd));
  const double r = p.rho * max_poisson_radius(p.points) * (1 + kMargin);
  // The sampler keeps a grid of cells 2r wide over each region (up to a whole tile) and, with
  // Lloyd iterations, 10 x 10 samples per cell: bound both before anything is allocated.
  const double cells = 1 / (4 * r * r), samples = p.lloyd > 0 ? 100 * cells : 0;
  if (cells > double(1 << 24) || samples > double(1 << 26))
    throw RequestError(
        "rho", fmt::format("`rho` {} with `points` {}: the sampler would need {:.3g} grid cells{} per tile (at most "
                           "2^24 cells and 2^26 "
                           "Lloyd samples); use `rho` {:.3g} or more{}",
                           p.rho, p.points, cells, p.lloyd > 0 ? fmt::format(" and {:.3g} Lloyd samples", samples) : "",
                           p.rho * std::sqrt(std::max(cells / double(1 << 24), samples / double(1 << 26))) * 1.001,
                           p.lloyd > 0 ? " (or `lloyd` 0)" : ""));
  // Two corner regions and the 2r between edge regions must fit along an edge: 2c + 2r <= 1.
  if (2 * (1 + std::sqrt(2.0)) * r + 2 * r > 1)
    throw RequestError(
        "points",
        fmt::format("`points` {} is too few for rho {}: corner regions would overlap (N >= {} needed)", p.points, p.rho,
                    int(std::ceil(std::pow(p.rho * (2 * (2 + std::sqrt(2.0))), 2) / (2 * std::sqrt(3.0)) *
                                  (1 + kMargin) * (1 + kMargin)))));
  double tiles = std::pow(double(p.colours) * p.edge_colours, 4);
  if (p.method == PoissonTileMethod::Dual) {
    tiles = std::pow(4.0 * p.colours, 4);
    if (p.points % 4 != 0)
      throw RequestError("method", "`method` dual needs `points` divisible by 4 (quarter-turn symmetric tiles)");
  }
  if (p.method == PoissonTileMethod::Wang) tiles = std::pow(double(p.colours), 12);
  if (tiles > double(1 << 20) || tiles * p.points > double(1 << 26))
    throw InputError(fmt::format("{} tiles of {} points is too large a tile set (at most 2^20 tiles, 2^26 points)",
                                 tiles, p.points));
}

std::uint64_t edged_tile_index(std::uint32_t nw, std::uint32_t ne, std::uint32_t sw, std::uint32_t se, std::uint32_t l,
                               std::uint32_t n, std::uint32_t e, std::uint32_t s, std::uint32_t w, std::uint32_t ec) {
  const std::uint64_t l4 = std::uint64_t(l) * l * l * l;
  return parts::corner_tile_index(nw, ne, sw, se, l) + l4 * (((std::uint64_t(n) * ec + e) * ec + s) * ec + w);
}

std::uint64_t wang_pd_tile_index(const std::uint32_t colours12[12], std::uint32_t c) {
  std::uint64_t i = 0;
  for (int k = 0; k < 12; ++k) i = i * c + colours12[k];
  return i;
}

namespace {

// Smallest squared distance between a point of `a` and a point of `b` shifted by `shift`.
double closest(const std::vector<Point2>& a, const std::vector<Point2>& b, Point2 shift) {
  double best = std::numeric_limits<double>::infinity();
  for (const Point2& p : a)
    for (const Point2& q : b) best = std::min(best, squared_distance(p, {q.x + shift.x, q.y + shift.y}));
  return best;
}

// Per tile, the points within distance d of each side and of each corner.
struct Borders {
  std::vector<Point2> east, west, north, south, ne, nw, se, sw;
};
Borders borders(const std::vector<Point2>& pts, double d) {
  Borders b;
  for (const Point2& p : pts) {
    if (p.x > 1 - d) b.east.push_back(p);
    if (p.x < d) b.west.push_back(p);
    if (p.y < d) b.north.push_back(p);
    if (p.y > 1 - d) b.south.push_back(p);
    if (p.x > 1 - d && p.y < d) b.ne.push_back(p);
    if (p.x < d && p.y < d) b.nw.push_back(p);
    if (p.x > 1 - d && p.y > 1 - d) b.se.push_back(p);
    if (p.x < d && p.y > 1 - d) b.sw.push_back(p);
  }
  return b;
}

// Random tilings of 8 x 8 tiles with every lattice colour (or Wang edge colour) uniform and
// independent; the smallest distance between points of different tiles.
double sampled_across(const PoissonTileSet& set, int samples, std::uint64_t seed) {
  double best = std::numeric_limits<double>::infinity();
  const int n = 8;
  SplitMix64 rng(seed);
  for (int s = 0; s < samples; ++s) {
    std::vector<std::vector<Point2>> tile(n * n);
    if (set.method == PoissonTileMethod::Wang) {
      const std::uint32_t c = set.colours;
      // H[y][x]: edge (x, y)-(x+1, y); V[y][x]: edge (x, y)-(x, y+1); one ring of extra edges.
      auto rnd = [&] { return std::uint32_t(rng.below(c)); };
      std::vector<std::uint32_t> h((n + 3) * (n + 3)), v((n + 3) * (n + 3));
      for (auto& e : h) e = rnd();
      for (auto& e : v) e = rnd();
      auto H = [&](int x, int y) { return h[std::size_t(y + 1) * (n + 3) + std::size_t(x + 1)]; };
      auto V = [&](int x, int y) { return v[std::size_t(y + 1) * (n + 3) + std::size_t(x + 1)]; };
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const std::uint32_t k[12] = {H(x, y),         V(x + 1, y),     H(x, y + 1),     V(x, y),
                                       V(x, y - 1),     H(x - 1, y),     V(x + 1, y - 1), H(x + 1, y),
                                       V(x + 1, y + 1), H(x + 1, y + 1), V(x, y + 1),     H(x - 1, y + 1)};
          tile[std::size_t(y * n + x)] = set.tiles[wang_pd_tile_index(k, c)];
        }
    } else {
      const std::uint32_t l = set.lattice_colours(), ec = set.edge_colours;
      // Lattice colours at the (n + 1)^2 points, edge colours of the edges starting at each point.
      std::vector<std::uint32_t> col((n + 1) * (n + 1)), h(col.size()), v(col.size());
      for (auto& k : col) k = std::uint32_t(rng.below(l));
      for (auto& k : h) k = std::uint32_t(rng.below(ec));
      for (auto& k : v) k = std::uint32_t(rng.below(ec));
      const auto i = [&](int x, int y) { return std::size_t(y) * (n + 1) + std::size_t(x); };
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
          tile[std::size_t(y * n + x)] =
              set.tiles[edged_tile_index(col[i(x, y)], col[i(x + 1, y)], col[i(x, y + 1)], col[i(x + 1, y + 1)], l,
                                         h[i(x, y)], v[i(x + 1, y)], h[i(x, y + 1)], v[i(x, y)], ec)];
    }
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        for (int dy = 0; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            if ((dy == 0 && dx <= 0) || x + dx < 0 || x + dx >= n || y + dy >= n) continue;
            best = std::min(best, closest(tile[std::size_t(y * n + x)], tile[std::size_t((y + dy) * n + x + dx)],
                                          {double(dx), double(dy)}));
          }
  }
  return best;
}

}  // namespace

TileSetCheck check_poisson_tiles(const PoissonTileSet& set, int threads) {
  TileSetCheck out;
  const double d = 3 * set.guaranteed_distance();
  double within = std::numeric_limits<double>::infinity();
  for (const auto& t : set.tiles) {
    if (t.size() != set.points) ++out.points_off_count;
    within = std::min(within, min_distance(t));
  }
  const double rmax = max_poisson_radius(set.points);
  out.rho_within = relative_radius(within, set.points);
  double across = std::numeric_limits<double>::infinity();
  const std::uint32_t l = set.lattice_colours(), ec = set.edge_colours;
  // Horizontal and vertical neighbours share two corners and an edge (L^2 E^3 each per tile);
  // diagonal ones one corner (L^3 E^4 each way).
  const std::uint64_t per_tile =
      2 * std::uint64_t(l) * l * ec * ec * ec + 2 * std::uint64_t(l) * l * l * ec * ec * ec * ec;
  const bool exhaustive = set.method != PoissonTileMethod::Wang && set.tiles.size() * per_tile <= (1ull << 25);
  if (exhaustive) {
    std::vector<Borders> b;
    b.reserve(set.tiles.size());
    for (const auto& t : set.tiles) b.push_back(borders(t, d));
    const std::uint64_t l4 = std::uint64_t(l) * l * l * l;
    const auto at = [&](std::uint32_t nw, std::uint32_t ne, std::uint32_t sw, std::uint32_t se, std::uint32_t en,
                        std::uint32_t ee, std::uint32_t es, std::uint32_t ew) -> const Borders& {
      return b[edged_tile_index(nw, ne, sw, se, l, en, ee, es, ew, ec)];
    };
    std::mutex mu;
    parallel_for(std::int64_t(set.tiles.size()), threads, [&](std::int64_t ti) {
      throw_if_interrupted();
      const auto k = parts::corners_of(std::uint64_t(ti) % l4, l);
      const std::uint64_t edges = std::uint64_t(ti) / l4;  // ((N E + E) E + S) E + W
      const std::uint32_t es = std::uint32_t(edges / ec % ec), ee = std::uint32_t(edges / ec / ec % ec);
      const Borders& a = b[std::size_t(ti)];
      double local = std::numeric_limits<double>::infinity();
      for (std::uint32_t u = 0; u < l; ++u)
        for (std::uint32_t v = 0; v < l; ++v)
          for (std::uint32_t x = 0; x < ec; ++x)
            for (std::uint32_t y = 0; y < ec; ++y)
              for (std::uint32_t z = 0; z < ec; ++z) {
                // east neighbour (ne, u, se, v) with west edge ee; south neighbour (sw, se, u, v), north edge es
                local = std::min(local, closest(a.east, at(k.ne, u, k.se, v, x, y, z, ee).west, {1, 0}));
                local = std::min(local, closest(a.south, at(k.sw, k.se, u, v, es, x, y, z).north, {0, 1}));
                for (std::uint32_t w = 0; w < l; ++w)
                  for (std::uint32_t q = 0; q < ec; ++q) {
                    // south-east neighbour (se, u, v, w); south-west neighbour (u, sw, v, w)
                    local = std::min(local, closest(a.se, at(k.se, u, v, w, x, y, z, q).nw, {1, 1}));
                    local = std::min(local, closest(a.sw, at(u, k.sw, v, w, x, y, z, q).ne, {-1, 1}));
                  }
              }
      std::lock_guard lock(mu);
      across = std::min(across, local);
    });
    out.pairs_checked = set.tiles.size() * per_tile;
    out.exhaustive = true;
  } else {
    const int samples = 64;
    across = sampled_across(set, samples, derive_seed(set.seed, 99));
    out.pairs_checked = std::uint64_t(samples);
  }
  out.rho_across = 0.5 * std::sqrt(across) / rmax;
  return out;
}

}  // namespace tilekit::points
