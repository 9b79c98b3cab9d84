// Strip pruning (aperiodic/prune.hpp): tiles on cycles of the k-row strip transducer.
#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "aperiodic/chain.hpp"
#include "aperiodic/prune.hpp"
#include "base/error.hpp"

namespace tilekit {

namespace {

template <class T>
std::vector<T> pick(const std::vector<T>& v, const std::vector<std::size_t>& idx) {
  std::vector<T> out;
  out.reserve(idx.size());
  for (std::size_t k : idx) out.push_back(v[k]);
  return out;
}

}  // namespace

std::vector<std::size_t> in_periodic_strips(const std::vector<WangTile>& tiles, int k, bool columns, bool top,
                                            std::size_t max_transitions) {
  if (k < 1) throw InputError(fmt::format("strip pruning needs k >= 1, got {}", k));
  // Orient the set so that the wanted row is the top row of a strip of rows: columns are the rows
  // of the transposed set (as in TransducerChain), the bottom row is the top row of the set turned
  // half round.
  std::vector<WangTile> t;
  for (WangTile x : tiles) {
    if (columns) x = WangTile{x.w, x.s, x.e, x.n};
    if (!top) x = WangTile{x.s, x.w, x.n, x.e};
    t.push_back(x);
  }
  // The row transducer with the tile's position as output, numbered as TransducerChain numbers
  // states and labels (dense, increasing), so that it composes with the chain's levels.
  std::vector<Colour> state, label;
  for (const WangTile& x : t) state.push_back(x.w), state.push_back(x.e), label.push_back(x.n), label.push_back(x.s);
  for (auto* v : {&state, &label}) {
    std::sort(v->begin(), v->end());
    v->erase(std::unique(v->begin(), v->end()), v->end());
  }
  auto id = [](const std::vector<Colour>& v, Colour c) {
    return std::uint32_t(std::lower_bound(v.begin(), v.end(), c) - v.begin());
  };
  Transducer row;
  row.states = std::uint32_t(state.size());
  for (std::uint32_t i = 0; i < t.size(); ++i) row.transitions.push_back({id(state, t[i].w), id(label, t[i].s), i, id(state, t[i].e)});
  row.finalize();
  Transducer product;
  if (k == 1) {
    product = row;
  } else {
    TransducerChain chain(t, false, true);
    while (chain.k() < k - 1 && !chain.finite()) {
      if (chain.level(chain.k()).product_transitions > max_transitions) break;
      chain.extend({});
    }
    if (chain.finite()) return {};  // no strip of k - 1 rows: no tile lies on a cycle
    if (chain.k() < k - 1) k = chain.k() + 1;  // over the budget: the filter of a lower level
    product = compose(chain.level(chain.k()).t, row, std::uint32_t(label.size())).t;
  }
  trim_to_components(product);
  std::set<std::size_t> used;
  for (const Transition& e : product.transitions) used.insert(e.out);
  return {used.begin(), used.end()};
}

PruneReport prune_strips_wang(const std::vector<WangTile>& tiles, int max_k, std::size_t max_transitions) {
  if (max_k < 1) throw InputError(fmt::format("strip pruning needs k >= 1, got {}", max_k));
  PruneReport rep;
  rep.before = tiles.size();
  std::vector<std::size_t> alive(tiles.size());
  for (std::size_t i = 0; i < alive.size(); ++i) alive[i] = i;
  for (bool changed = true; changed && !alive.empty();) {
    changed = false;
    ++rep.passes;
    for (int k = 1; k <= max_k && !alive.empty(); ++k)
      for (bool columns : {false, true})
        for (bool top : {true, false}) {
          if (alive.empty()) break;
          std::vector<std::size_t> keep = in_periodic_strips(pick(tiles, alive), k, columns, top, max_transitions);
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

TileSet prune_strips(const TileSet& set, int max_k, PruneReport* report) {
  return prune_via_wang(
      set, [&](const std::vector<WangTile>& tiles) { return prune_strips_wang(tiles, max_k); }, report);
}

}  // namespace tilekit
