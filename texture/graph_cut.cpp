#include "texture/graph_cut.hpp"

// GCC 12 at -O3 reports a false -Wmaybe-uninitialized inside Boost.Graph's edge iterator (an
// optional<pair<iterator, iterator>> it reads only when set).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/boykov_kolmogorov_max_flow.hpp>
#include <cassert>
#include <cmath>
#include <vector>

#include "texture/exemplar.hpp"

namespace tilekit {

namespace {

using Traits = boost::adjacency_list_traits<boost::vecS, boost::vecS, boost::directedS>;
using Graph = boost::adjacency_list<
    boost::vecS, boost::vecS, boost::directedS,
    boost::property<boost::vertex_color_t, boost::default_color_type,
                    boost::property<boost::vertex_distance_t, long,
                                    boost::property<boost::vertex_predecessor_t, Traits::edge_descriptor>>>,
    boost::property<boost::edge_capacity_t, std::int64_t,
                    boost::property<boost::edge_residual_capacity_t, std::int64_t,
                                    boost::property<boost::edge_reverse_t, Traits::edge_descriptor>>>>;

constexpr double kScale = 16.0;                // capacities are integers: M in units of 1/16
constexpr std::int64_t kInfinite = 1ll << 40;  // forced pixels

class Builder {
 public:
  explicit Builder(std::size_t vertices) : g_(vertices) {}
  void add(std::size_t u, std::size_t v, std::int64_t cap_uv, std::int64_t cap_vu) {
    auto e = boost::add_edge(u, v, g_).first, r = boost::add_edge(v, u, g_).first;
    boost::put(boost::edge_capacity, g_, e, cap_uv);
    boost::put(boost::edge_capacity, g_, r, cap_vu);
    boost::put(boost::edge_reverse, g_, e, r);
    boost::put(boost::edge_reverse, g_, r, e);
  }
  Graph& graph() { return g_; }

 private:
  Graph g_;
};

}  // namespace

GraphCutResult graph_cut_merge(const Image& a, const Image& b, const std::vector<std::uint8_t>& region,
                               const std::vector<std::uint8_t>& forced, double keep_cost,
                               const std::function<float(std::size_t, std::size_t)>& extra, float colour_weight) {
  const std::int64_t keep = std::int64_t(std::llround(keep_cost * kScale));
  const int w = a.width, h = a.height;
  assert(b.width == w && b.height == h && region.size() == std::size_t(w) * std::size_t(h));
  assert(forced.size() == region.size());
  std::vector<int> node(region.size(), -1);
  int nodes = 0;
  for (std::size_t i = 0; i < region.size(); ++i)
    if (region[i]) node[i] = nodes++;
  const std::size_t source = std::size_t(nodes), sink = source + 1;
  Builder gb(std::size_t(nodes) + 2);
  // The cost of a seam between neighbours s and t = s + (dx, dy): the steps it would show, A(s)
  // next to B(t) and B(s) next to A(t), whichever side takes which patch.
  auto cost = [&](int x, int y, int dx, int dy) {
    const int x1 = x + dx, y1 = y + dy;
    float m = colour_distance(a.at(x, y), b.at(x1, y1)) + colour_distance(b.at(x, y), a.at(x1, y1));
    if (extra) {
      const std::size_t s = std::size_t(y) * std::size_t(w) + std::size_t(x),
                        t = std::size_t(y1) * std::size_t(w) + std::size_t(x1);
      m = colour_weight * m + extra(s, t) + extra(t, s);
    }
    return std::int64_t(std::llround(double(m) * kScale));
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
      if (node[i] < 0) continue;
      assert(x >= 1 && y >= 1 && x + 2 < w && y + 2 < h);
      const std::size_t s = std::size_t(node[i]);
      if (forced[i])
        gb.add(source, s, kInfinite, 0);
      else if (keep > 0)
        gb.add(source, s, keep, 0);
      // Each undirected neighbour pair once (right and down); a neighbour outside the region
      // keeps A, so taking B here cuts that pair: a link to the sink (and from the left/top too).
      for (auto [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
        const std::size_t j = std::size_t(y + dy) * std::size_t(w) + std::size_t(x + dx);
        const std::int64_t m = cost(x, y, dx, dy);
        if (node[j] >= 0)
          gb.add(s, std::size_t(node[j]), m, m);
        else
          gb.add(s, sink, m, 0);
      }
      for (auto [dx, dy] : {std::pair{-1, 0}, std::pair{0, -1}}) {
        const std::size_t j = std::size_t(y + dy) * std::size_t(w) + std::size_t(x + dx);
        if (node[j] < 0) gb.add(s, sink, cost(x + dx, y + dy, -dx, -dy), 0);
      }
    }
  Graph& g = gb.graph();
  const std::int64_t flow = boost::boykov_kolmogorov_max_flow(g, source, sink);
  GraphCutResult r;
  r.nodes = nodes;
  r.cost = double(flow) / kScale;
  r.take_new.assign(region.size(), 0);
  // The source side of a minimum cut is what the source still reaches through edges with residual
  // capacity: those pixels take B. (The colour map the algorithm leaves is not used: its source
  // tree was seen to miss forced pixels, whose source edges can never be saturated.)
  auto residual = boost::get(boost::edge_residual_capacity, g);
  std::vector<std::uint8_t> reached(std::size_t(nodes) + 2, 0);
  std::vector<std::size_t> stack{source};
  reached[source] = 1;
  while (!stack.empty()) {
    const std::size_t u = stack.back();
    stack.pop_back();
    for (auto [e, end] = boost::out_edges(u, g); e != end; ++e) {
      const std::size_t v = boost::target(*e, g);
      if (!reached[v] && boost::get(residual, *e) > 0) {
        reached[v] = 1;
        stack.push_back(v);
      }
    }
  }
  for (std::size_t i = 0; i < region.size(); ++i)
    if (node[i] >= 0 && reached[std::size_t(node[i])]) r.take_new[i] = 1;
  return r;
}

}  // namespace tilekit
