// The imposed-group search model: forward checking on orbit availability, most-constrained-
// first branching and partial-pattern counts (see impose_model.hpp for why). This file holds
// what the engine calls during the search; impose_model_build.cpp builds the tables and checks
// the incremental state against a recomputation.
#include "solver/impose_model.hpp"

#include <algorithm>
#include <bit>
#include <cassert>

#include "base/random.hpp"

namespace tilekit {

void ImposeModel::tight_add(int site) {
  if (tight_cnt_[std::size_t(site)]++ == 0) {
    tight_pos_[std::size_t(site)] = int(tight_list_.size());
    tight_list_.push_back(site);
  }
}

void ImposeModel::tight_remove(int site) {
  assert(tight_cnt_[std::size_t(site)] > 0);
  if (--tight_cnt_[std::size_t(site)] == 0) {
    int pos = tight_pos_[std::size_t(site)];
    int last = tight_list_.back();
    tight_list_[std::size_t(pos)] = last;
    tight_pos_[std::size_t(last)] = pos;
    tight_list_.pop_back();
    tight_pos_[std::size_t(site)] = -1;
  }
}

int ImposeModel::lone_unassigned(int cell) const {
  const unsigned free = ~unsigned(assigned_slots_[std::size_t(cell)]) & 15u;
  if (!free) return -1;
  const int* sites = &t_->slot_site[std::size_t(cell) * 4];
  const int lone = sites[std::countr_zero(free)];
  for (unsigned rest = free; rest; rest &= rest - 1)
    if (sites[std::countr_zero(rest)] != lone) return -1;
  return lone;
}

std::uint32_t ImposeModel::tile_of(int cell) const {
  assert(assigned_slots_[std::size_t(cell)] == 15);
  const std::size_t base = std::size_t(cell) * 4;
  const std::uint32_t* w = &t_->slot_weight[base];
  const std::uint8_t* c = &colour_[base];
  return w[0] * c[0] + w[1] * c[1] + w[2] * c[2] + w[3] * c[3];
}

int ImposeModel::pattern_key(int cell, const Pattern& p) const {
  const std::uint8_t* c = &colour_[std::size_t(cell) * 4];
  int code = 0;
  for (int j = 0; j < p.n; ++j) code += int(p.mul[std::size_t(j)]) * c[p.slots[std::size_t(j)]];
  return t_->pattern_class[std::size_t(p.offset + code)];
}

// Applies one occurrence of a just-assigned site; revert_occurrence() is its exact inverse (and
// runs in the reverse order: the pattern classes touched here are pushed on trail_ and popped
// there). Returns false when a partial-pattern count now exceeds the unused orbits with that
// pattern (the state is still fully applied, so the caller reverts it).
bool ImposeModel::apply_occurrence(const Occurrence& o, int site, int value) {
  const Tables& t = *t_;
  const std::size_t base = std::size_t(o.cell) * 4;
  for (unsigned rest = unsigned(o.mask); rest; rest &= rest - 1) {
    const unsigned j = unsigned(std::countr_zero(rest));
    colour_[base + j] = t.slot_perm[base + j][value];
  }
  assert((assigned_slots_[std::size_t(o.cell)] & o.mask) == 0);
  assigned_slots_[std::size_t(o.cell)] |= std::uint8_t(o.mask);
  bool ok = true;
  const int after = (cu_[std::size_t(o.cell)] -= o.mult);
  assert(after >= 0);
  if (after == 0) {
    tight_remove(site);
    if (t.domain.packing) {
      used_[std::size_t(t.domain.orbit_of[tile_of(o.cell)])] = 1;
      for (const auto& p : t.patterns) {
        const int key = pattern_key(o.cell, p);
        trail_.push_back(key);
        if (!(p.mask & o.mask)) --demand_[std::size_t(key)];
        if (--avail_[std::size_t(key)] < demand_[std::size_t(key)]) ok = false;
      }
    }
  } else {
    const int u = lone_unassigned(o.cell);
    if (u >= 0) tight_add(u);
    for (const auto& p : t.patterns) {
      if (!(p.mask & o.mask) || !pattern_assigned(o.cell, p)) continue;
      const int key = pattern_key(o.cell, p);
      trail_.push_back(key);
      if (++demand_[std::size_t(key)] > avail_[std::size_t(key)]) ok = false;
    }
  }
  return ok;
}

void ImposeModel::revert_occurrence(const Occurrence& o, int site) {
  const Tables& t = *t_;
  const auto& pats = t.patterns;
  if (cu_[std::size_t(o.cell)] == 0) {
    if (t.domain.packing) {
      for (auto p = pats.rbegin(); p != pats.rend(); ++p) {
        const int key = trail_.back();
        trail_.pop_back();
        if (!(p->mask & o.mask)) ++demand_[std::size_t(key)];
        ++avail_[std::size_t(key)];
      }
      used_[std::size_t(t.domain.orbit_of[tile_of(o.cell)])] = 0;
    }
    tight_add(site);
  } else {
    for (auto p = pats.rbegin(); p != pats.rend(); ++p) {
      if (!(p->mask & o.mask) || !pattern_assigned(o.cell, *p)) continue;
      const int key = trail_.back();
      trail_.pop_back();
      --demand_[std::size_t(key)];
      assert(demand_[std::size_t(key)] >= 0);
    }
    const int u = lone_unassigned(o.cell);
    if (u >= 0) tight_remove(u);
  }
  assigned_slots_[std::size_t(o.cell)] &= std::uint8_t(~o.mask);
  cu_[std::size_t(o.cell)] += o.mult;
  assert(cu_[std::size_t(o.cell)] <= 4);
}

void ImposeModel::revert_site(int site, int upto) {
  for (int k = upto - 1; k >= t_->occ_start[std::size_t(site)]; --k) revert_occurrence(t_->occ[std::size_t(k)], site);
}

namespace {
std::uint64_t assignment_key(int site, int value) {
  return mix_seed(std::uint64_t(std::uint32_t(site)) << 8 | std::uint64_t(std::uint32_t(value)));
}
}  // namespace

// The tile of an occurrence's cell once the site takes `value` (the other slots are assigned).
std::uint32_t ImposeModel::tile_with(const Occurrence& o, int value) const {
  const Tables& t = *t_;
  const std::size_t base = std::size_t(o.cell) * 4;
  std::uint32_t idx = 0;
  for (std::size_t j = 0; j < 4; ++j)
    idx += t.slot_weight[base + j] * (o.mask >> j & 1 ? t.slot_perm[base + j][value] : colour_[base + j]);
  return idx;
}

bool ImposeModel::assign(int site, int value) {
  const Tables& t = *t_;
  assert(site >= 0 && site < t.domain.num_sites);
  assert(val_[std::size_t(site)] < 0 && "a site is assigned once on any path");
  assert(value >= 0 && std::uint32_t(value) < t.domain.site_colours[std::size_t(site)]);
  val_[std::size_t(site)] = value;
  ++assigned_;
  const int first = t.occ_start[std::size_t(site)], last = t.occ_start[std::size_t(site) + 1];
  for (int k = first; k < last; ++k) {
    const Occurrence& o = t.occ[std::size_t(k)];
    bool ok = true;
    if (cu_[std::size_t(o.cell)] == o.mult) {
      // This occurrence completes the cell: its tile orbit must be usable and unused.
      const int orbit = t.domain.orbit_of[tile_with(o, value)];
      if (orbit < 0) {
        ok = false;
        stats_.prune(Prune::NoSuchTile);
      } else if (t.domain.packing && used_[std::size_t(orbit)]) {
        ok = false;
        stats_.prune(Prune::OrbitUsed);
      }
    }
    if (ok) ++stats_.propagations;  // the cell's pattern counts are revised
    if (ok && !apply_occurrence(o, site, value)) {
      revert_occurrence(o, site);
      ok = false;
      stats_.prune(Prune::PatternCount);
    }
    if (!ok) {  // undo what this assignment did; the engine's unassign() is then a no-op
      revert_site(site, k);
      val_[std::size_t(site)] = -1;
      --assigned_;
      return false;
    }
  }
  hash_ ^= assignment_key(site, value);
  return true;
}

void ImposeModel::unassign(int site, int value) {
  if (val_[std::size_t(site)] < 0) return;  // the assign failed and undid itself
  assert(val_[std::size_t(site)] == value && "unassign undoes the latest assign");
  revert_site(site, t_->occ_start[std::size_t(site) + 1]);
  val_[std::size_t(site)] = -1;
  --assigned_;
  hash_ ^= assignment_key(site, value);
}

std::uint64_t ImposeModel::cell_mask(int cell, int site, std::uint64_t mask) const {
  const Tables& t = *t_;
  std::uint32_t partial = 0;
  const std::uint8_t* perms[4];
  std::uint32_t weights[4];
  int nu = 0;
  const std::size_t base = std::size_t(cell) * 4;
  const unsigned assigned = assigned_slots_[std::size_t(cell)];
  for (std::size_t j = 0; j < 4; ++j) {
    if (assigned >> j & 1) {
      partial += t.slot_weight[base + j] * colour_[base + j];
    } else {
      assert(t.slot_site[base + j] == site && "a tight cell has one unassigned site");
      perms[nu] = t.slot_perm[base + j];
      weights[nu++] = t.slot_weight[base + j];
    }
  }
  std::uint64_t out = 0;
  for (std::uint64_t rest = mask; rest; rest &= rest - 1) {
    int v = std::countr_zero(rest);
    std::uint32_t idx = partial;
    for (int j = 0; j < nu; ++j) idx += weights[j] * perms[j][v];
    int orbit = t.domain.orbit_of[idx];
    if (orbit >= 0 && !(t.domain.packing && used_[std::size_t(orbit)])) out |= std::uint64_t(1) << v;
  }
  return out;
}

std::uint64_t ImposeModel::site_mask(int site) const {
  const Tables& t = *t_;
  std::uint32_t nv = t.domain.site_colours[std::size_t(site)];
  std::uint64_t mask = nv == 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << nv) - 1;
  if (tight_cnt_[std::size_t(site)] == 0) return mask;
  for (int k = t.occ_start[std::size_t(site)]; k < t.occ_start[std::size_t(site) + 1] && mask; ++k) {
    const Occurrence& o = t.occ[std::size_t(k)];
    if (cu_[std::size_t(o.cell)] == o.mult) mask = cell_mask(o.cell, site, mask);
  }
  return mask;
}

int ImposeModel::branch(std::vector<int>& values) {
  const Tables& t = *t_;
  values.clear();
  if (assigned_ == t.domain.num_sites) return -1;
  const bool mcf = t.ordering == Ordering::MostConstrained;
  int best = -1, best_count = 65;
  std::uint64_t best_mask = 0;
  for (int u : tight_list_) {
    std::uint64_t mask = site_mask(u);
    if (!mask) return u;  // forward checking: no unused orbit left for a cell; a dead end
    int count = std::popcount(mask);
    if (mcf ? (count < best_count || (count == best_count && u < best)) : (best < 0 || u < best)) {
      best = u;
      best_count = count;
      best_mask = mask;
    }
  }
  if (best < 0 || !mcf) {
    // No tight site (or scanline order): the first unassigned site in scan order.
    int first = 0;
    while (val_[std::size_t(first)] >= 0) ++first;
    if (best != first) {
      best = first;
      best_mask = site_mask(first);
      if (!best_mask) return first;
    }
  }
  for (std::uint64_t rest = best_mask; rest; rest &= rest - 1) values.push_back(std::countr_zero(rest));
  if (value_seed_) {
    // Seeded order, a function of the seed and the assignment only (replayable).
    SplitMix64 rng(mix_seed(value_seed_ ^ hash_));
    shuffle(values.begin(), values.end(), rng);
  }
  return best;
}

Tiling ImposeModel::tiling() const {
  assert(assigned_ == t_->domain.num_sites);
  return t_->domain.to_tiling(val_);
}

}  // namespace tilekit
