// Kopf et al. 2006 sec. 4: merging progressive source tiles along Voronoi seams, and the
// progressive ranking of the merged tile (their Fig. 4 and Fig. 5).
#include <algorithm>
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/dijkstra_shortest_paths.hpp>
#include <cmath>
#include <queue>

#include "base/random.hpp"
#include "points/recursive_internal.hpp"

namespace tilekit::points::recursive {

std::vector<Point2> progressive_source(std::uint32_t n, std::uint64_t seed) {
  // Relaxation dart throwing on the unit torus, radius shrinking by 1% after 100 consecutive
  // failures (McCool and Fiume 1992; Kopf et al. Fig. 8 use 0.99); the acceptance order is the rank.
  SplitMix64 rng(seed);
  const double final_spacing = 2 * 0.7 * max_poisson_radius(n);
  PointGrid grid(0, 0, 1, 1, final_spacing, true);
  std::vector<Point2> pts;
  double radius = 0.5;
  int failures = 0;
  while (pts.size() < n) {
    const Point2 q{rng.uniform(), rng.uniform()};
    bool ok = true;
    if (pts.size() < 64) {
      for (const Point2& p : pts) {
        const Point2 d = grid.delta(q, p);
        if (d.x * d.x + d.y * d.y < radius * radius) ok = false;
      }
    } else {
      grid.for_near(q, int(std::ceil(radius / grid.cell())), [&](int id) {
        const Point2 d = grid.delta(q, pts[std::size_t(id)]);
        if (d.x * d.x + d.y * d.y < radius * radius) ok = false;
      });
    }
    if (ok) {
      grid.insert(int(pts.size()), q);
      pts.push_back(q);
      failures = 0;
    } else if (++failures >= 100) {
      radius *= 0.99;
      failures = 0;
    }
  }
  return pts;
}

namespace {

using Graph = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS, boost::no_property,
                                    boost::property<boost::edge_weight_t, double>>;

// Cost per pixel of seam: (1 - d / d_max)^10 along Voronoi edges (Kopf et al. sec. 4), plus a
// small length penalty that keeps the seam near the edge it replaces; tile borders cost the most.
constexpr double kLengthPenalty = 0.02;
constexpr double kExponent = 10;

}  // namespace

std::vector<RankedPoint> merge_east(const std::vector<RankedPoint>& tile, const std::vector<RankedPoint>& source) {
  std::vector<Point2> all;
  for (const auto& p : tile) all.push_back(p.p);
  for (const auto& p : source) all.push_back(p.p);
  const int g = std::clamp(int(6 * std::sqrt(double(all.size()))), 64, 1024);
  // Raster Voronoi diagram of the union (plain distances inside the tile).
  PointGrid grid(0, 0, 1, 1, 1.5 / std::sqrt(double(all.size())), false);
  for (std::size_t i = 0; i < all.size(); ++i) grid.insert(int(i), all[i]);
  std::vector<int> owner(std::size_t(g) * std::size_t(g));
  for (int y = 0; y < g; ++y)
    for (int x = 0; x < g; ++x)
      owner[std::size_t(y) * std::size_t(g) + std::size_t(x)] = grid.nearest({(x + 0.5) / g, (y + 0.5) / g}, all);
  const auto own = [&](int x, int y) { return owner[std::size_t(y) * std::size_t(g) + std::size_t(x)]; };
  const auto dist = [&](int a, int b) { return std::sqrt(squared_distance(all[std::size_t(a)], all[std::size_t(b)])); };
  double dmax = 0;
  for (int y = 0; y < g; ++y)
    for (int x = 0; x < g; ++x) {
      if (x + 1 < g && own(x, y) != own(x + 1, y)) dmax = std::max(dmax, dist(own(x, y), own(x + 1, y)));
      if (y + 1 < g && own(x, y) != own(x, y + 1)) dmax = std::max(dmax, dist(own(x, y), own(x, y + 1)));
    }
  const auto cost = [&](int a, int b) { return std::pow(1 - dist(a, b) / dmax, kExponent) + kLengthPenalty; };
  // Nodes are pixel corners (x, y), 0 <= x, y <= g; edges run along pixel borders.
  const auto node = [&](int x, int y) { return std::size_t(y) * std::size_t(g + 1) + std::size_t(x); };
  Graph graph(std::size_t(g + 1) * std::size_t(g + 1));
  for (int y = 0; y <= g; ++y)
    for (int x = 0; x <= g; ++x) {
      // Horizontal border segment (x, y)-(x+1, y): between pixels (x, y-1) and (x, y).
      if (x < g && !(x + 1 == g && y > 0 && y < g)) {  // never onto the east edge between its corners
        double c = -1;
        if (y == 0 || y == g)
          c = 1 + kLengthPenalty;
        else if (own(x, y - 1) != own(x, y))
          c = cost(own(x, y - 1), own(x, y));
        if (c >= 0) boost::add_edge(node(x, y), node(x + 1, y), c, graph);
      }
      // Vertical segment (x, y)-(x, y+1): between pixels (x-1, y) and (x, y); never along the east edge.
      if (y < g && x < g) {
        double c = -1;
        if (x == 0)
          c = 1 + kLengthPenalty;
        else if (own(x - 1, y) != own(x, y))
          c = cost(own(x - 1, y), own(x, y));
        if (c >= 0) boost::add_edge(node(x, y), node(x, y + 1), c, graph);
      }
    }
  std::vector<std::size_t> pred(boost::num_vertices(graph));
  std::vector<double> d(boost::num_vertices(graph));
  boost::dijkstra_shortest_paths(graph, node(g, 0), boost::predecessor_map(pred.data()).distance_map(d.data()));
  // The seam: segments on the path from the SE corner back to the NE corner.
  std::vector<char> cut_v(std::size_t(g + 1) * std::size_t(g + 1), 0), cut_h(cut_v.size(), 0);
  for (std::size_t v = node(g, g); v != node(g, 0) && pred[v] != v; v = pred[v]) {
    const std::size_t u = pred[v], a = std::min(u, v), b = std::max(u, v);
    if (b == a + 1)
      cut_h[a] = 1;  // horizontal segment starting at node a
    else
      cut_v[a] = 1;  // vertical segment starting at node a
  }
  // Pixels east of the seam: flood fill from the east column across uncut borders.
  std::vector<char> east(std::size_t(g) * std::size_t(g), 0);
  std::queue<std::pair<int, int>> q;
  for (int y = 0; y < g; ++y) east[std::size_t(y) * std::size_t(g) + std::size_t(g - 1)] = 1, q.push({g - 1, y});
  while (!q.empty()) {
    const auto [x, y] = q.front();
    q.pop();
    const auto visit = [&](int nx, int ny, bool blocked) {
      if (nx < 0 || ny < 0 || nx >= g || ny >= g || blocked) return;
      char& e = east[std::size_t(ny) * std::size_t(g) + std::size_t(nx)];
      if (!e) e = 1, q.push({nx, ny});
    };
    visit(x - 1, y, cut_v[node(x, y)]);
    visit(x + 1, y, cut_v[node(x + 1, y)]);
    visit(x, y - 1, cut_h[node(x, y)]);
    visit(x, y + 1, cut_h[node(x, y + 1)]);
  }
  const auto is_east = [&](Point2 p) {
    const int x = std::clamp(int(p.x * g), 0, g - 1), y = std::clamp(int(p.y * g), 0, g - 1);
    return east[std::size_t(y) * std::size_t(g) + std::size_t(x)] != 0;
  };
  std::vector<RankedPoint> out;
  for (const auto& p : tile)
    if (!is_east(p.p)) out.push_back(p);
  for (const auto& p : source)
    if (is_east(p.p)) out.push_back(p);
  return out;
}

std::vector<Point2> progressive_order(std::vector<RankedPoint> pts, std::uint64_t seed) {
  // Interleave the source rankings, ties in random order.
  SplitMix64 rng(seed);
  std::vector<std::pair<std::uint64_t, std::size_t>> key;
  for (std::size_t i = 0; i < pts.size(); ++i)
    key.emplace_back((std::uint64_t(pts[i].rank) << 32) | (rng.next() >> 32), i);
  std::sort(key.begin(), key.end());
  std::vector<Point2> order;
  for (const auto& k : key) order.push_back(pts[k.second].p);
  // Fig. 5: rank i goes to the first point (in the interleaved order) farther than alpha / sqrt(i)
  // from every point ranked before it; the others keep their order.
  constexpr double kAlpha = 0.5;
  const std::size_t n = order.size();
  PointGrid grid(0, 0, 1, 1, kAlpha / std::sqrt(double(n)), true);
  grid.insert(0, order[0]);
  for (std::size_t i = 1; i < n; ++i) {
    const double t = kAlpha / std::sqrt(double(i));
    const int rings = int(std::ceil(t / grid.cell()));
    std::size_t pick = i;
    for (std::size_t j = i; j < n; ++j) {
      bool far = true;
      grid.for_near(order[j], rings, [&](int id) {
        const Point2 d = grid.delta(order[j], order[std::size_t(id)]);
        if (d.x * d.x + d.y * d.y <= t * t) far = false;
      });
      if (far) {
        pick = j;
        break;
      }
    }
    std::rotate(order.begin() + std::ptrdiff_t(i), order.begin() + std::ptrdiff_t(pick),
                order.begin() + std::ptrdiff_t(pick + 1));
    grid.insert(int(i), order[i]);
  }
  return order;
}

}  // namespace tilekit::points::recursive
