#include "solver/impose_search.hpp"

#include <algorithm>
#include <bit>
#include <cassert>

namespace tilekit {

std::uint64_t luby(std::uint64_t i) {
  // Luby, Sinclair, Zuckerman (1993): t_i = 2^(k-1) if i = 2^k - 1, else t_{i - 2^(k-1) + 1}.
  for (;;) {
    std::uint64_t k = 1;
    while ((std::uint64_t(1) << k) - 1 < i) ++k;
    if ((std::uint64_t(1) << k) - 1 == i) return std::uint64_t(1) << (k - 1);
    i = i - (std::uint64_t(1) << (k - 1)) + 1;
  }
}

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
  reset();
}

void SymmetricSearch::reset() {
  val_.assign(std::size_t(m_.num_sites), -1);
  cu_.assign(m_.cells.size(), 4);
  used_.assign(std::size_t(m_.num_orbits), 0);
  tight_cnt_.assign(std::size_t(m_.num_sites), 0);
  tight_pos_.assign(std::size_t(m_.num_sites), -1);
  tight_list_.clear();
  trail_.clear();
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

bool SymmetricSearch::assign(int site, int v) {
  val_[std::size_t(site)] = v;
  ++assigned_;
  bool ok = true;
  for (int k = occ_start_[std::size_t(site)]; k < occ_start_[std::size_t(site) + 1]; ++k) {
    const auto& o = occ_[std::size_t(k)];
    int after = (cu_[std::size_t(o.cell)] -= o.mult);
    if (after == 0) {
      tight_remove(site);
      if (!ok) continue;
      std::uint32_t idx = 0;
      const int base = o.cell * 4;
      for (int j = 0; j < 4; ++j)
        idx += slot_weight_[std::size_t(base + j)] *
               slot_perm_[std::size_t(base + j)][val_[std::size_t(slot_site_[std::size_t(base + j)])]];
      int orbit = m_.orbit_of[idx];
      if (orbit < 0 || (m_.packing && used_[std::size_t(orbit)])) {
        ok = false;
        continue;
      }
      if (m_.packing) {
        used_[std::size_t(orbit)] = 1;
        trail_.push_back(orbit);
      }
    } else {
      int u = lone_unassigned(o.cell);
      if (u >= 0) tight_add(u);
    }
  }
  return ok;
}

void SymmetricSearch::unassign(int site) {
  for (int k = occ_start_[std::size_t(site) + 1] - 1; k >= occ_start_[std::size_t(site)]; --k) {
    const auto& o = occ_[std::size_t(k)];
    if (cu_[std::size_t(o.cell)] == 0) {
      tight_add(site);
    } else {
      int u = lone_unassigned(o.cell);
      if (u >= 0) tight_remove(u);
    }
    cu_[std::size_t(o.cell)] += o.mult;
  }
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
  f.trail_mark = std::uint32_t(trail_.size());
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
      while (trail_.size() > f.trail_mark) {
        used_[std::size_t(trail_.back())] = 0;
        trail_.pop_back();
      }
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
    f.assigned = true;
    if (!assign(f.site, v)) continue;  // unassigned at the top of the loop
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
