#include "solver/impose_search.hpp"

#include <algorithm>
#include <bit>
#include <cassert>

namespace tilekit {

SymmetricSearch::SymmetricSearch(const SymmetricModel& model, const SymmetricSearchConfig& config)
    : m_(model), cfg_(config), rng_(config.seed * 0x9E3779B97F4A7C15ULL + 0x2545F4914F6CDD1DULL) {
  const int ns = m_.num_sites;
  const int nc = int(m_.cells.size());
  std::vector<std::vector<Occurrence>> per_site;
  per_site.resize(std::size_t(ns));
  slot_perm_.resize(std::size_t(nc) * 4);
  slot_site_.resize(std::size_t(nc) * 4);
  slot_weight_.resize(std::size_t(nc) * 4);
  for (int c = 0; c < nc; ++c) {
    for (int k = 0; k < 4; ++k) {
      const auto& s = m_.cells[std::size_t(c)][std::size_t(k)];
      slot_perm_[std::size_t(c * 4 + k)] = m_.perm_tables[std::size_t(s.perm)].data();
      slot_site_[std::size_t(c * 4 + k)] = s.site;
      slot_weight_[std::size_t(c * 4 + k)] = s.weight;
      auto& list = per_site[std::size_t(s.site)];
      if (!list.empty() && list.back().cell == c) ++list.back().mult;
      else {
        bool found = false;
        for (auto& o : list)
          if (o.cell == c) {
            ++o.mult;
            found = true;
          }
        if (!found) list.push_back({c, 1});
      }
    }
  }
  occ_start_.push_back(0);
  for (const auto& list : per_site) {
    occ_.insert(occ_.end(), list.begin(), list.end());
    occ_start_.push_back(int(occ_.size()));
  }
  stack_.resize(std::size_t(ns) + 1);
  build_patterns();
  reset();
}

void SymmetricSearch::build_patterns() {
  if (!m_.packing) return;
  const bool wang = m_.kind == TileKind::Wang;
  auto slot_class = [&](int j) { return wang && (j == 1 || j == 3) ? 1 : 0; };  // Wang E, W: vertical
  auto radix = [&](int j) { return slot_class(j) ? m_.cv : m_.ch; };
  auto tile_colours = [&](std::uint32_t t) -> std::array<Colour, 4> {
    if (wang) {
      WangTile w = wang_tile(t, m_.ch, m_.cv);
      return {w.n, w.e, w.s, w.w};
    }
    CornerTile c = corner_tile(t, m_.ch);
    return {c.ne, c.se, c.sw, c.nw};
  };
  int classes = 0;
  std::vector<std::uint32_t> orbit_rep(std::size_t(m_.num_orbits), ~0u);
  for (std::uint32_t t = 0; t < m_.orbit_of.size(); ++t)
    if (m_.orbit_of[t] >= 0 && orbit_rep[std::size_t(m_.orbit_of[t])] == ~0u) orbit_rep[std::size_t(m_.orbit_of[t])] = t;
  for (int mask = 1; mask < 16; ++mask) {
    int n = std::popcount(unsigned(mask));
    if (!(cfg_.pattern_sizes >> n & 1) || n > 3) continue;
    Pattern p;
    p.mask = mask;
    std::uint32_t size = 1;
    for (int j = 0; j < 4; ++j)
      if (mask >> j & 1) {
        p.slots[std::size_t(p.n)] = j;
        p.mul[std::size_t(p.n++)] = size;
        size *= radix(j);
      }
    p.offset = int(pattern_class_.size());
    // Class of each code: least code over the group's images, numbered compactly.
    std::vector<int> least(size);
    for (std::uint32_t code = 0; code < size; ++code) {
      std::uint32_t best = code;
      for (std::size_t e = 0; e < m_.group_order; ++e) {
        std::uint32_t img = 0, rest = code;
        for (int j = 0; j < p.n; ++j) {
          std::uint32_t r = radix(p.slots[std::size_t(j)]);
          Colour c = rest % r;
          rest /= r;
          img += p.mul[std::size_t(j)] * m_.perm_tables[e * 2 + std::size_t(slot_class(p.slots[std::size_t(j)]))][c];
        }
        best = std::min(best, img);
      }
      least[code] = int(best);
    }
    std::vector<int> id(size, -1);
    for (std::uint32_t code = 0; code < size; ++code) {
      int& k = id[std::size_t(least[code])];
      if (k < 0) k = classes++;
      pattern_class_.push_back(k);
    }
    avail_init_.resize(std::size_t(classes), 0);
    for (std::uint32_t t : orbit_rep) {
      auto col = tile_colours(t);
      std::uint32_t code = 0;
      for (int j = 0; j < p.n; ++j) code += p.mul[std::size_t(j)] * col[std::size_t(p.slots[std::size_t(j)])];
      ++avail_init_[std::size_t(pattern_class_[std::size_t(p.offset) + code])];
    }
    patterns_.push_back(p);
  }
  avail_.resize(avail_init_.size());
  demand_.resize(avail_init_.size());
}

void SymmetricSearch::reset() {
  val_.assign(std::size_t(m_.num_sites), -1);
  cu_.assign(m_.cells.size(), 4);
  used_.assign(std::size_t(m_.num_orbits), 0);
  tight_cnt_.assign(std::size_t(m_.num_sites), 0);
  tight_pos_.assign(std::size_t(m_.num_sites), -1);
  tight_list_.clear();
  std::copy(avail_init_.begin(), avail_init_.end(), avail_.begin());
  std::fill(demand_.begin(), demand_.end(), 0);
  assigned_ = 0;
  for (int c = 0; c < int(m_.cells.size()); ++c) {
    int u = lone_unassigned(c);  // a cell whose four slots are one site (tiny tori)
    if (u >= 0) tight_add(u);
  }
}

std::uint64_t SymmetricSearch::next_random() {
  // xorshift64*
  rng_ ^= rng_ >> 12;
  rng_ ^= rng_ << 25;
  rng_ ^= rng_ >> 27;
  return rng_ * 0x2545F4914F6CDD1DULL;
}

void SymmetricSearch::tight_add(int site) {
  if (tight_cnt_[std::size_t(site)]++ == 0) {
    tight_pos_[std::size_t(site)] = int(tight_list_.size());
    tight_list_.push_back(site);
  }
}

void SymmetricSearch::tight_remove(int site) {
  if (--tight_cnt_[std::size_t(site)] == 0) {
    int pos = tight_pos_[std::size_t(site)];
    int last = tight_list_.back();
    tight_list_[std::size_t(pos)] = last;
    tight_pos_[std::size_t(last)] = pos;
    tight_list_.pop_back();
    tight_pos_[std::size_t(site)] = -1;
  }
}

int SymmetricSearch::lone_unassigned(int cell) const {
  int lone = -1;
  for (int k = 0; k < 4; ++k) {
    int s = slot_site_[std::size_t(cell * 4 + k)];
    if (val_[std::size_t(s)] >= 0) continue;
    if (lone >= 0 && lone != s) return -1;
    lone = s;
  }
  return lone;
}

std::uint32_t SymmetricSearch::tile_of(int cell) const {
  std::uint32_t idx = 0;
  const int base = cell * 4;
  for (int j = 0; j < 4; ++j)
    idx += slot_weight_[std::size_t(base + j)] *
           slot_perm_[std::size_t(base + j)][val_[std::size_t(slot_site_[std::size_t(base + j)])]];
  return idx;
}

int SymmetricSearch::pattern_key(int cell, const Pattern& p) const {
  int code = 0;
  for (int j = 0; j < p.n; ++j) {
    int slot = cell * 4 + p.slots[j];
    code += int(p.mul[j]) * slot_perm_[std::size_t(slot)][val_[std::size_t(slot_site_[std::size_t(slot)])]];
  }
  return pattern_class_[std::size_t(p.offset + code)];
}

bool SymmetricSearch::pattern_assigned(int cell, const Pattern& p) const {
  for (int j = 0; j < p.n; ++j)
    if (val_[std::size_t(slot_site_[std::size_t(cell * 4 + p.slots[j])])] < 0) return false;
  return true;
}

int SymmetricSearch::site_slots(int cell, int site) const {
  int mask = 0;
  for (int j = 0; j < 4; ++j)
    if (slot_site_[std::size_t(cell * 4 + j)] == site) mask |= 1 << j;
  return mask;
}

// Applies one occurrence of a just-assigned site; revert_occurrence() is its exact inverse.
// Returns false when a partial-pattern count now exceeds the unused orbits with that pattern
// (the state is still fully applied, so the caller reverts it).
bool SymmetricSearch::apply_occurrence(int site, const Occurrence& o) {
  bool ok = true;
  int after = (cu_[std::size_t(o.cell)] -= o.mult);
  int mine = patterns_.empty() ? 0 : site_slots(o.cell, site);
  if (after == 0) {
    tight_remove(site);
    if (m_.packing) {
      used_[std::size_t(m_.orbit_of[tile_of(o.cell)])] = 1;
      for (const auto& p : patterns_) {
        int key = pattern_key(o.cell, p);
        if (!(p.mask & mine)) --demand_[std::size_t(key)];
        if (--avail_[std::size_t(key)] < demand_[std::size_t(key)]) ok = false;
      }
    }
  } else {
    int u = lone_unassigned(o.cell);
    if (u >= 0) tight_add(u);
    for (const auto& p : patterns_) {
      if (!(p.mask & mine) || !pattern_assigned(o.cell, p)) continue;
      int key = pattern_key(o.cell, p);
      if (++demand_[std::size_t(key)] > avail_[std::size_t(key)]) ok = false;
    }
  }
  return ok;
}

void SymmetricSearch::revert_occurrence(int site, const Occurrence& o) {
  int mine = patterns_.empty() ? 0 : site_slots(o.cell, site);
  if (cu_[std::size_t(o.cell)] == 0) {
    if (m_.packing) {
      for (const auto& p : patterns_) {
        int key = pattern_key(o.cell, p);
        if (!(p.mask & mine)) ++demand_[std::size_t(key)];
        ++avail_[std::size_t(key)];
      }
      used_[std::size_t(m_.orbit_of[tile_of(o.cell)])] = 0;
    }
    tight_add(site);
  } else {
    int u = lone_unassigned(o.cell);
    if (u >= 0) tight_remove(u);
    for (const auto& p : patterns_) {
      if (!(p.mask & mine) || !pattern_assigned(o.cell, p)) continue;
      --demand_[std::size_t(pattern_key(o.cell, p))];
    }
  }
  cu_[std::size_t(o.cell)] += o.mult;
}

bool SymmetricSearch::assign(int site, int v) {
  val_[std::size_t(site)] = v;
  ++assigned_;
  const int first = occ_start_[std::size_t(site)], last = occ_start_[std::size_t(site) + 1];
  for (int k = first; k < last; ++k) {
    const auto& o = occ_[std::size_t(k)];
    bool ok = true;
    if (cu_[std::size_t(o.cell)] == o.mult) {
      // This occurrence completes the cell: its tile orbit must be usable and unused.
      int orbit = m_.orbit_of[tile_of(o.cell)];
      ok = orbit >= 0 && !(m_.packing && used_[std::size_t(orbit)]);
    }
    if (ok) ok = apply_occurrence(site, o) ? true : (revert_occurrence(site, o), false);
    if (!ok) {
      for (int j = k - 1; j >= first; --j) revert_occurrence(site, occ_[std::size_t(j)]);
      val_[std::size_t(site)] = -1;
      --assigned_;
      return false;
    }
  }
  return true;
}

void SymmetricSearch::unassign(int site) {
  for (int k = occ_start_[std::size_t(site) + 1] - 1; k >= occ_start_[std::size_t(site)]; --k)
    revert_occurrence(site, occ_[std::size_t(k)]);
  val_[std::size_t(site)] = -1;
  --assigned_;
}

std::uint64_t SymmetricSearch::cell_mask(int cell, int site, std::uint64_t mask) const {
  std::uint32_t partial = 0;
  const std::uint8_t* perms[4];
  std::uint32_t weights[4];
  int nu = 0;
  const int base = cell * 4;
  for (int j = 0; j < 4; ++j) {
    int s = slot_site_[std::size_t(base + j)];
    if (s == site) {
      perms[nu] = slot_perm_[std::size_t(base + j)];
      weights[nu++] = slot_weight_[std::size_t(base + j)];
    } else {
      partial += slot_weight_[std::size_t(base + j)] * slot_perm_[std::size_t(base + j)][val_[std::size_t(s)]];
    }
  }
  std::uint64_t out = 0;
  for (std::uint64_t rest = mask; rest; rest &= rest - 1) {
    int v = std::countr_zero(rest);
    std::uint32_t idx = partial;
    for (int j = 0; j < nu; ++j) idx += weights[j] * perms[j][v];
    int orbit = m_.orbit_of[idx];
    if (orbit >= 0 && !(m_.packing && used_[std::size_t(orbit)])) out |= std::uint64_t(1) << v;
  }
  return out;
}

bool SymmetricSearch::select(Frame& f) {
  int best = -1, best_count = 65;
  std::uint64_t best_mask = 0;
  for (int u : tight_list_) {
    std::uint32_t nv = m_.site_colours[std::size_t(u)];
    std::uint64_t mask = nv == 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << nv) - 1;
    for (int k = occ_start_[std::size_t(u)]; k < occ_start_[std::size_t(u) + 1] && mask; ++k) {
      const auto& o = occ_[std::size_t(k)];
      if (cu_[std::size_t(o.cell)] == o.mult) mask = cell_mask(o.cell, u, mask);
    }
    if (!mask) return false;  // forward checking: no unused orbit left for this cell
    int count = std::popcount(mask);
    bool better = cfg_.most_constrained ? (count < best_count || (count == best_count && u < best)) : (best < 0 || u < best);
    if (better) {
      best = u;
      best_count = count;
      best_mask = mask;
    }
  }
  if (best < 0 || !cfg_.most_constrained) {
    // No tight site (or scanline order): the first unassigned site in scanline order.
    int first = 0;
    while (val_[std::size_t(first)] >= 0) ++first;
    if (best != first) {
      best = first;
      std::uint32_t nv = m_.site_colours[std::size_t(first)];
      best_mask = nv == 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << nv) - 1;
      if (tight_cnt_[std::size_t(first)] > 0)
        for (int k = occ_start_[std::size_t(first)]; k < occ_start_[std::size_t(first) + 1]; ++k) {
          const auto& o = occ_[std::size_t(k)];
          if (cu_[std::size_t(o.cell)] == o.mult) best_mask = cell_mask(o.cell, first, best_mask);
        }
      if (!best_mask) return false;
    }
  }
  f.site = best;
  f.n = 0;
  f.i = 0;
  f.assigned = false;
  for (std::uint64_t rest = best_mask; rest; rest &= rest - 1) f.vals[f.n++] = std::uint8_t(std::countr_zero(rest));
  if (cfg_.random_values)
    for (int i = f.n - 1; i > 0; --i) std::swap(f.vals[i], f.vals[next_random() % std::uint64_t(i + 1)]);
  return true;
}

SymmetricSearch::Outcome SymmetricSearch::run(std::uint64_t node_limit, const std::atomic<bool>* stop,
                                              std::chrono::steady_clock::time_point deadline,
                                              const std::function<void(const std::vector<int>&)>& each) {
  reset();
  if (m_.num_sites == 0) return Outcome::Exhausted;
  const std::uint64_t start_nodes = nodes_;
  int depth = 0;
  if (!select(stack_[0])) return Outcome::Exhausted;
  for (;;) {
    Frame& f = stack_[std::size_t(depth)];
    if (f.assigned) {
      unassign(f.site);
      f.assigned = false;
    }
    if (f.i == f.n) {
      if (depth == 0) return Outcome::Exhausted;
      --depth;
      continue;
    }
    int v = f.vals[f.i++];
    ++nodes_;
    if ((nodes_ & 4095) == 0) {
      if (stop && stop->load(std::memory_order_relaxed)) return Outcome::Stopped;
      if (std::chrono::steady_clock::now() >= deadline) return Outcome::Stopped;
    }
    if (node_limit && nodes_ - start_nodes >= node_limit) return Outcome::NodeLimit;
    if (!assign(f.site, v)) continue;  // assign() undid itself
    f.assigned = true;
    if (assigned_ == m_.num_sites) {
      ++solutions_;
      if (!each) return Outcome::Solution;
      each(val_);
      continue;
    }
    if (!select(stack_[std::size_t(depth) + 1])) continue;
    ++depth;
  }
}

}  // namespace tilekit
