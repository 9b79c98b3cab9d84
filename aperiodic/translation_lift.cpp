#include "aperiodic/translation_lift.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <deque>
#include <map>
#include <set>
#include <unordered_set>

namespace tilekit {

namespace {

// One row transducer edge: a tile seen as a transition `from -> to` with a label.
struct Edge {
  std::size_t from, to, label;
};

// Vertices of a digraph that lie on or reach a cycle (forward = true), or that are reached
// from a cycle (forward = false): repeatedly drop vertices with no out- (in-) edge left.
std::vector<bool> infinite_side(std::size_t n, const std::vector<std::pair<std::size_t, std::size_t>>& arcs,
                                bool forward) {
  std::vector<std::size_t> degree(n, 0);
  std::vector<std::vector<std::size_t>> back(n);
  for (auto [u, v] : arcs) {
    if (!forward) std::swap(u, v);
    ++degree[u];
    back[v].push_back(u);
  }
  std::vector<bool> alive(n, true);
  std::deque<std::size_t> dead;
  for (std::size_t v = 0; v < n; ++v)
    if (degree[v] == 0) dead.push_back(v), alive[v] = false;
  while (!dead.empty()) {
    std::size_t v = dead.front();
    dead.pop_front();
    for (std::size_t u : back[v])
      if (alive[u] && --degree[u] == 0) alive[u] = false, dead.push_back(u);
  }
  return alive;
}

}  // namespace

LiftReport translation_lift_impl(const std::vector<WangTile>& tiles, bool horizontal,
                                 const std::vector<CornerTile>* corner, std::size_t max_states);

LiftReport translation_lift(const std::vector<WangTile>& tiles, bool horizontal, std::size_t max_states) {
  return translation_lift_impl(tiles, horizontal, nullptr, max_states);
}

LiftReport translation_lift(const std::vector<WangTile>& tiles, bool horizontal, const std::vector<CornerTile>& corner,
                            std::size_t max_states) {
  return translation_lift_impl(tiles, horizontal, &corner, max_states);
}

LiftReport translation_lift_impl(const std::vector<WangTile>& tiles, bool horizontal,
                                 const std::vector<CornerTile>* corner, std::size_t max_states) {
  LiftReport rep;
  // Dense states and labels.
  std::map<Colour, std::size_t> state_id;
  std::map<std::pair<Colour, Colour>, std::size_t> label_id;
  std::vector<Edge> edges;
  for (const WangTile& t : tiles) {
    Colour from = horizontal ? t.w : t.n, to = horizontal ? t.e : t.s;
    std::pair<Colour, Colour> lab = horizontal ? std::pair{t.n, t.s} : std::pair{t.w, t.e};
    std::size_t f = state_id.emplace(from, state_id.size()).first->second;
    std::size_t g = state_id.emplace(to, state_id.size()).first->second;
    std::size_t l = label_id.emplace(lab, label_id.size()).first->second;
    edges.push_back({f, g, l});
  }
  const std::size_t nv = state_id.size();
  std::vector<std::vector<std::size_t>> by_label(label_id.size()), out_of(nv);
  for (std::size_t k = 0; k < edges.size(); ++k) by_label[edges[k].label].push_back(k), out_of[edges[k].from].push_back(k);

  // The label graph H of the corner set's rows: sigma -> tau when two consecutive tiles
  // (a then b, a.e == b.w) carry these labels. These are exactly the corner tiles.
  std::set<std::pair<std::size_t, std::size_t>> harcs;
  if (corner) {
    // A given corner set: its tiles are the arcs (labels unknown to the Wang set cannot lift).
    for (const CornerTile& c : *corner) {
      auto l1 = horizontal ? std::pair{c.nw, c.sw} : std::pair{c.nw, c.ne};
      auto l2 = horizontal ? std::pair{c.ne, c.se} : std::pair{c.sw, c.se};
      for (auto l : {l1, l2})
        if (!label_id.count(l)) {
          label_id.emplace(l, label_id.size());
          by_label.emplace_back();
        }
      harcs.emplace(label_id[l1], label_id[l2]);
    }
  } else {
    for (const Edge& a : edges)
      for (std::size_t kb : out_of[a.to]) harcs.emplace(a.label, edges[kb].label);
  }
  const std::size_t nl = label_id.size();
  std::vector<std::pair<std::size_t, std::size_t>> harc_list(harcs.begin(), harcs.end());
  std::vector<std::vector<std::size_t>> hnext(nl);
  for (auto [s, t] : harc_list) hnext[s].push_back(t);
  auto hfwd = infinite_side(nl, harc_list, true), hbwd = infinite_side(nl, harc_list, false);

  // Subset construction: (last label, set of transducer states the word can end in).
  // Reaching an empty set on a word that extends both ways in H proves a corner row with
  // no lift; exhausting the states without one proves every row lifts (compactness).
  using State = std::pair<std::size_t, std::vector<bool>>;
  std::set<State> seen;
  std::deque<State> todo;
  for (std::size_t s = 0; s < nl; ++s) {
    if (!hbwd[s]) continue;
    std::vector<bool> set(nv, false);
    for (std::size_t k : by_label[s]) set[edges[k].to] = true;
    if (seen.insert({s, set}).second) todo.push_back({s, set});
  }
  rep.lifts = true;
  while (!todo.empty() && rep.lifts) {
    if (seen.size() > max_states) {
      rep.decided = false;
      rep.lifts = false;
      break;
    }
    auto [s, set] = todo.front();
    todo.pop_front();
    for (std::size_t t : hnext[s]) {
      std::vector<bool> next(nv, false);
      bool any = false;
      for (std::size_t k : by_label[t])
        if (set[edges[k].from]) next[edges[k].to] = true, any = true;
      if (!any) {
        if (hfwd[t]) rep.lifts = false;
        continue;
      }
      if (seen.insert({t, next}).second) todo.push_back({t, std::move(next)});
    }
  }
  rep.states = seen.size();

  // Injectivity: the label product graph on state pairs; an off-diagonal edge pair (a != b,
  // same label) on a bi-infinite path gives two different rows with the same labels.
  std::vector<std::pair<std::size_t, std::size_t>> parcs;
  std::vector<bool> off_diagonal;
  for (std::size_t l = 0; l < nl; ++l)
    for (std::size_t ka : by_label[l])
      for (std::size_t kb : by_label[l]) {
        parcs.emplace_back(edges[ka].from * nv + edges[kb].from, edges[ka].to * nv + edges[kb].to);
        off_diagonal.push_back(ka != kb);
      }
  auto pfwd = infinite_side(nv * nv, parcs, true), pbwd = infinite_side(nv * nv, parcs, false);
  rep.injective = true;
  for (std::size_t k = 0; k < parcs.size(); ++k)
    if (off_diagonal[k] && pbwd[parcs[k].first] && pfwd[parcs[k].second]) rep.injective = false;

  const char* dir = horizontal ? "row" : "column";
  if (!rep.decided)
    rep.detail = fmt::format("{} lift check gave up after {} subset states", dir, seen.size());
  else
    rep.detail = fmt::format("every corner {} {} to a Wang {}; the map on {}s is {}", dir,
                             rep.lifts ? "lifts" : "does NOT lift", dir, dir,
                             rep.injective ? "injective" : "not injective");
  return rep;
}

}  // namespace tilekit
