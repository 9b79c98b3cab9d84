// Building the imposed-group model's shared tables (occurrences of every site in the
// representative cells, slot permutations and weights, partial-pattern classes) and
// check_state(), the recomputation the tests compare the incremental state with. The search
// operations are in impose_model.cpp.
#include <algorithm>
#include <bit>
#include <cassert>

#include "base/random.hpp"
#include "solver/impose_model.hpp"  // IWYU pragma: associated

namespace tilekit {

ImposeModel::ImposeModel(FundamentalDomain domain, Ordering ordering, unsigned pattern_sizes) {
  auto t = std::make_shared<Tables>();
  t->domain = std::move(domain);
  t->ordering = ordering;
  const FundamentalDomain& m = t->domain;
  const int ns = m.num_sites;
  const int nc = int(m.cells.size());
  std::vector<std::vector<Occurrence>> per_site(static_cast<std::size_t>(ns));
  t->slot_perm.resize(std::size_t(nc) * 4);
  t->slot_site.resize(std::size_t(nc) * 4);
  t->slot_weight.resize(std::size_t(nc) * 4);
  for (int c = 0; c < nc; ++c)
    for (int k = 0; k < 4; ++k) {
      const auto& s = m.cells[std::size_t(c)][std::size_t(k)];
      assert(s.site >= 0 && s.site < ns);
      t->slot_perm[std::size_t(c * 4 + k)] = m.perm_tables[std::size_t(s.perm)].data();
      t->slot_site[std::size_t(c * 4 + k)] = s.site;
      t->slot_weight[std::size_t(c * 4 + k)] = s.weight;
      auto& list = per_site[std::size_t(s.site)];
      auto it = std::find_if(list.begin(), list.end(), [&](const Occurrence& o) { return o.cell == c; });
      if (it == list.end())
        list.push_back({c, 1, 1 << k});
      else
        ++it->mult, it->mask |= 1 << k;
    }
  t->occ_start.push_back(0);
  for (const auto& list : per_site) {
    t->occ.insert(t->occ.end(), list.begin(), list.end());
    t->occ_start.push_back(int(t->occ.size()));
  }
  if (m.packing) build_patterns(*t, pattern_sizes);
  t_ = std::move(t);

  val_.assign(std::size_t(ns), -1);
  cu_.assign(std::size_t(nc), 4);
  colour_.assign(std::size_t(nc) * 4, 0);
  assigned_slots_.assign(std::size_t(nc), 0);
  used_.assign(std::size_t(m.num_orbits), 0);
  tight_cnt_.assign(std::size_t(ns), 0);
  tight_pos_.assign(std::size_t(ns), -1);
  avail_ = t_->avail_init;
  demand_.assign(avail_.size(), 0);
  for (int c = 0; c < nc; ++c) {
    int u = lone_unassigned(c);  // a cell whose four slots are one site (tiny tori)
    if (u >= 0) tight_add(u);
  }
}

void ImposeModel::build_patterns(Tables& t, unsigned pattern_sizes) {
  const FundamentalDomain& m = t.domain;
  const bool wang = m.kind == TileKind::Wang;
  auto slot_class = [&](int j) { return wang && (j == 1 || j == 3) ? 1 : 0; };  // Wang E, W: vertical
  auto radix = [&](int j) { return slot_class(j) ? m.cv : m.ch; };
  auto tile_colours = [&](std::uint32_t tile) -> std::array<Colour, 4> {
    if (wang) {
      WangTile w = wang_tile(tile, m.ch, m.cv);
      return {w.n, w.e, w.s, w.w};
    }
    CornerTile c = corner_tile(tile, m.ch);
    return {c.ne, c.se, c.sw, c.nw};
  };
  int classes = 0;
  std::vector<std::uint32_t> orbit_rep(std::size_t(m.num_orbits), ~0u);
  for (std::uint32_t tile = 0; tile < m.orbit_of.size(); ++tile)
    if (m.orbit_of[tile] >= 0 && orbit_rep[std::size_t(m.orbit_of[tile])] == ~0u)
      orbit_rep[std::size_t(m.orbit_of[tile])] = tile;
  for (int mask = 1; mask < 16; ++mask) {
    int n = std::popcount(unsigned(mask));
    if (!(pattern_sizes >> n & 1) || n > 3) continue;
    Pattern p;
    p.mask = mask;
    std::uint32_t size = 1;
    for (int j = 0; j < 4; ++j)
      if (mask >> j & 1) {
        p.slots[std::size_t(p.n)] = j;
        p.mul[std::size_t(p.n++)] = size;
        size *= radix(j);
      }
    p.offset = int(t.pattern_class.size());
    // Class of each code: least code over the group's images, numbered compactly.
    std::vector<int> least(size);
    for (std::uint32_t code = 0; code < size; ++code) {
      std::uint32_t best = code;
      for (std::size_t e = 0; e < m.group_order; ++e) {
        std::uint32_t img = 0, rest = code;
        for (int j = 0; j < p.n; ++j) {
          std::uint32_t r = radix(p.slots[std::size_t(j)]);
          Colour c = rest % r;
          rest /= r;
          img += p.mul[std::size_t(j)] * m.perm_tables[e * 2 + std::size_t(slot_class(p.slots[std::size_t(j)]))][c];
        }
        best = std::min(best, img);
      }
      least[code] = int(best);
    }
    std::vector<int> id(size, -1);
    for (std::uint32_t code = 0; code < size; ++code) {
      int& k = id[std::size_t(least[code])];
      if (k < 0) k = classes++;
      t.pattern_class.push_back(k);
    }
    t.avail_init.resize(std::size_t(classes), 0);
    for (std::uint32_t tile : orbit_rep) {
      auto col = tile_colours(tile);
      std::uint32_t code = 0;
      for (int j = 0; j < p.n; ++j) code += p.mul[std::size_t(j)] * col[std::size_t(p.slots[std::size_t(j)])];
      ++t.avail_init[std::size_t(t.pattern_class[std::size_t(p.offset) + code])];
    }
    t.patterns.push_back(p);
  }
}

bool ImposeModel::check_state() const {
  // Recomputes what assign()/unassign() maintain incrementally (too slow for the search).
  const Tables& t = *t_;
  const FundamentalDomain& m = t.domain;
  std::vector<int> cu(m.cells.size(), 0);
  std::vector<std::uint8_t> used(std::size_t(m.num_orbits), 0);
  std::vector<int> tight(std::size_t(m.num_sites), 0);
  int assigned = 0;
  for (int v : val_) assigned += v >= 0;
  if (assigned != assigned_) return false;
  for (std::size_t c = 0; c < m.cells.size(); ++c) {  // the per-cell caches against the site values
    unsigned mask = 0;
    for (std::size_t j = 0; j < 4; ++j) {
      const int v = val_[std::size_t(t.slot_site[c * 4 + j])];
      if (v < 0) continue;
      mask |= 1u << j;
      if (colour_[c * 4 + j] != t.slot_perm[c * 4 + j][v]) return false;
    }
    if (mask != assigned_slots_[c]) return false;
  }
  for (std::size_t c = 0; c < m.cells.size(); ++c) {
    for (std::size_t j = 0; j < 4; ++j) cu[c] += val_[std::size_t(t.slot_site[c * 4 + j])] < 0;
    if (cu[c] == 0 && m.packing) used[std::size_t(m.orbit_of[tile_of(int(c))])] = 1;
    int lone = lone_unassigned(int(c));
    if (lone >= 0) ++tight[std::size_t(lone)];
  }
  if (cu != cu_ || used != used_ || tight != tight_cnt_) return false;
  for (std::size_t i = 0; i < tight_list_.size(); ++i)
    if (tight_pos_[std::size_t(tight_list_[i])] != int(i)) return false;
  std::vector<int> avail = t.avail_init, demand(avail.size(), 0);
  for (std::size_t c = 0; c < m.cells.size() && m.packing; ++c)
    for (const auto& p : t.patterns) {
      if (!pattern_assigned(int(c), p)) continue;
      int key = pattern_key(int(c), p);
      if (cu[c] == 0)
        --avail[std::size_t(key)];
      else
        ++demand[std::size_t(key)];
    }
  return avail == avail_ && demand == demand_ && trail_.size() <= t.patterns.size() * 4 * m.cells.size();
}

}  // namespace tilekit
