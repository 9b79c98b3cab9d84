#include "aperiodic/prune.hpp"

#include <algorithm>
#include <cstdlib>
#include <functional>

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/strong_components.hpp>
#include <fmt/format.h>

#include <map>
#include <set>
#include <unordered_map>
#include <unordered_set>

#include "base/error.hpp"
#include "base/signals.hpp"

namespace tilekit {

namespace {

std::uint64_t key(Colour a, Colour b) { return (std::uint64_t(a) << 32) | b; }

template <class T>
std::vector<T> pick(const std::vector<T>& v, const std::vector<std::size_t>& idx) {
  std::vector<T> out;
  out.reserve(idx.size());
  for (std::size_t k : idx) out.push_back(v[k]);
  return out;
}

}  // namespace

std::vector<std::size_t> surroundable(const std::vector<WangTile>& w) {
  // Neighbour candidates, deduplicated by the colours the rest of the patch looks at.
  std::unordered_map<Colour, std::set<std::pair<Colour, Colour>>> north_of, south_of, east_of, west_of;
  std::unordered_set<std::uint64_t> es, ws, en, wn;  // diagonal tiles by the two colours they must show
  for (const WangTile& t : w) {
    north_of[t.s].insert({t.w, t.e});  // candidate N neighbour of a tile with n == t.s
    south_of[t.n].insert({t.w, t.e});  // S neighbour of a tile with s == t.n
    east_of[t.w].insert({t.n, t.s});   // E neighbour of a tile with e == t.w
    west_of[t.e].insert({t.n, t.s});   // W neighbour of a tile with w == t.e
    es.insert(key(t.e, t.s));          // NW diagonal: e = N.w, s = W.n
    ws.insert(key(t.w, t.s));          // NE diagonal: w = N.e, s = E.n
    en.insert(key(t.e, t.n));          // SW diagonal: e = S.w, n = W.s
    wn.insert(key(t.w, t.n));          // SE diagonal: w = S.e, n = E.s
  }
  static const std::set<std::pair<Colour, Colour>> none;
  auto get = [](auto& m, Colour c) -> const std::set<std::pair<Colour, Colour>>& {
    auto it = m.find(c);
    return it == m.end() ? none : it->second;
  };
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < w.size(); ++k) {
    const WangTile& t = w[k];
    bool found = false;
    for (auto [nw_, ne_] : get(north_of, t.n)) {          // N neighbour's (w, e)
      for (auto [wn_, ws_] : get(west_of, t.w)) {         // W neighbour's (n, s)
        if (!es.count(key(nw_, wn_))) continue;
        for (auto [en_, es_] : get(east_of, t.e)) {       // E neighbour's (n, s)
          if (!ws.count(key(ne_, en_))) continue;
          for (auto [sw_, se_] : get(south_of, t.s)) {    // S neighbour's (w, e)
            if (en.count(key(sw_, ws_)) && wn.count(key(se_, es_))) {
              found = true;
              break;
            }
          }
          if (found) break;
        }
        if (found) break;
      }
      if (found) break;
    }
    if (found) out.push_back(k);
  }
  return out;
}

std::vector<std::size_t> surroundable(const std::vector<WangTile>& w, int patch_radius) {
  if (patch_radius <= 1) return surroundable(w);
  // A backtracking search per tile for a (2R+1) x (2R+1) patch with the tile in the middle; cells
  // are filled nearest the middle first, each against the neighbours already placed.
  const int side = 2 * patch_radius + 1;
  std::vector<std::pair<int, int>> order;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) order.emplace_back(y, x);
  const int c = patch_radius;
  std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) {
    const int da = std::max(std::abs(a.first - c), std::abs(a.second - c));
    return da < std::max(std::abs(b.first - c), std::abs(b.second - c));
  });
  std::vector<std::size_t> out;
  std::vector<int> grid(std::size_t(side * side), -1);
  std::uint64_t calls = 0;
  std::function<bool(std::size_t)> place = [&](std::size_t i) {
    if (i == order.size()) return true;
    if (++calls % (1u << 16) == 0) throw_if_interrupted();  // one tile's search can take minutes
    const auto [y, x] = order[i];
    auto at = [&](int yy, int xx) {
      return yy < 0 || xx < 0 || yy >= side || xx >= side ? -1 : grid[std::size_t(yy * side + xx)];
    };
    const int n = at(y - 1, x), s = at(y + 1, x), we = at(y, x - 1), e = at(y, x + 1);
    for (std::size_t k = 0; k < w.size(); ++k) {
      const WangTile& t = w[k];
      if ((n >= 0 && w[std::size_t(n)].s != t.n) || (s >= 0 && w[std::size_t(s)].n != t.s) ||
          (we >= 0 && w[std::size_t(we)].e != t.w) || (e >= 0 && w[std::size_t(e)].w != t.e))
        continue;
      grid[std::size_t(y * side + x)] = int(k);
      if (place(i + 1)) return true;
    }
    grid[std::size_t(y * side + x)] = -1;
    return false;
  };
  for (std::size_t k = 0; k < w.size(); ++k) {
    throw_if_interrupted();
    std::fill(grid.begin(), grid.end(), -1);
    grid[std::size_t(c * side + c)] = int(k);
    if (place(1)) out.push_back(k);
  }
  return out;
}

std::vector<std::size_t> in_transducer_scc(const std::vector<WangTile>& w, bool rows) {
  using Graph = boost::adjacency_list<boost::vecS, boost::vecS, boost::directedS>;
  std::map<Colour, std::size_t> state;
  auto id = [&](Colour c) { return state.emplace(c, state.size()).first->second; };
  std::vector<std::pair<std::size_t, std::size_t>> arcs;
  for (const WangTile& t : w) arcs.emplace_back(id(rows ? t.w : t.n), id(rows ? t.e : t.s));
  Graph g(state.size());
  for (auto [u, v] : arcs) boost::add_edge(u, v, g);
  std::vector<int> comp(state.size());
  if (!state.empty()) boost::strong_components(g, comp.data());
  std::vector<std::size_t> out;
  // An edge u -> v lies on a cycle iff v reaches u, i.e. both ends share a component.
  for (std::size_t k = 0; k < arcs.size(); ++k)
    if (comp[arcs[k].first] == comp[arcs[k].second]) out.push_back(k);
  return out;
}

Soundness after_pruning(Soundness s, const PruneReport& r) {
  return s == Soundness::Conjugate && r.removed_by_scc > 0 ? Soundness::Lifts : s;
}

PruneReport prune_wang(const std::vector<WangTile>& tiles, int radius, int patch_radius) {
  if (radius < 0) throw RequestError("prune", fmt::format("`prune` radius must be >= 0, got {}", radius));
  PruneReport rep;
  rep.before = tiles.size();
  std::vector<std::size_t> alive(tiles.size());
  for (std::size_t k = 0; k < alive.size(); ++k) alive[k] = k;
  for (bool changed = true; changed;) {
    changed = false;
    ++rep.passes;
    for (int r = 0; r < radius; ++r) {
      auto keep = surroundable(pick(tiles, alive));
      if (keep.size() == alive.size()) break;
      rep.removed_by_surround += alive.size() - keep.size();
      alive = pick(alive, keep);
      changed = true;
    }
    if (patch_radius > 1 && !changed) {
      // The larger patches once the 3x3 rounds are done (their search is the costly one).
      auto keep = surroundable(pick(tiles, alive), patch_radius);
      if (keep.size() != alive.size()) {
        rep.removed_by_surround += alive.size() - keep.size();
        alive = pick(alive, keep);
        changed = true;
      }
    }
    for (bool rows : {true, false}) {
      auto keep = in_transducer_scc(pick(tiles, alive), rows);
      if (keep.size() == alive.size()) continue;
      rep.removed_by_scc += alive.size() - keep.size();
      alive = pick(alive, keep);
      changed = true;
    }
  }
  rep.after = alive.size();
  rep.kept = std::move(alive);
  return rep;
}

TileSet prune_via_wang(const TileSet& set,
                       const std::function<PruneReport(const std::vector<WangTile>&)>& prune_wang_tiles,
                       PruneReport* report) {
  PruneReport rep;
  TileSet out;
  if (set.kind() == TileKind::Wang) {
    rep = prune_wang_tiles(set.wang_tiles());
    out = TileSet::wang(pick(set.wang_tiles(), rep.kept), set.name(), set.source());
  } else {
    // thesis 2.9: the equivalent Wang set has the same tilings, tile for tile.
    rep = prune_wang_tiles(corner_to_wang(set).wang_tiles());
    out = TileSet::corner(pick(set.corner_tiles(), rep.kept), set.name(), set.source());
  }
  if (report) *report = rep;
  return out;
}

TileSet prune(const TileSet& set, int radius, PruneReport* report, int patch_radius) {
  return prune_via_wang(
      set, [&](const std::vector<WangTile>& tiles) { return prune_wang(tiles, radius, patch_radius); }, report);
}

}  // namespace tilekit
