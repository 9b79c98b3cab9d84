#include "solver/lattice_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <numeric>

#include "base/error.hpp"

namespace tilekit {

struct LatticeModel::Tables {
  TilingProblem problem;
  int vars = 0, max_radix = 0;
  std::vector<int> radix;                     // var -> number of colours
  std::vector<std::array<int, 4>> cell_vars;  // cell -> its four variables, in index digit order
  std::array<int, 4> digit_radix{};
  std::vector<int> allowed;                     // tile index -> tile number in the set, or -1
  std::vector<int> var_cells_start, var_cells;  // CSR: var -> cells containing it
  std::vector<int> order;                       // branching order of the free variables
  std::vector<int> used_base;                   // cell -> class * tiles (offset into used_)
};

LatticeModel::LatticeModel(const TilingProblem& p, bool break_translation, int class_period) {
  auto t = std::make_shared<Tables>();
  t->problem = p;
  const TileSet& set = p.set;
  const bool wang = set.kind() == TileKind::Wang;
  const int R = p.rows, K = p.cols;
  cells_ = R * K;
  packing_ = p.packing;
  break_translation_ = break_translation && p.packing && p.torus;
  if (class_period > 0) {
    assert(p.torus && p.packing && R % class_period == 0 && K % class_period == 0);
    class_period_ = class_period;
    classes_ = class_period * class_period;
  }
  t->used_base.resize(std::size_t(cells_));
  for (int cell = 0; cell < cells_; ++cell) {
    const int r = cell / K, c = cell % K;
    const int cls = class_period > 0 ? (r % class_period) * class_period + c % class_period : 0;
    t->used_base[std::size_t(cell)] = cls * int(set.size());
  }
  const int ch = int(set.horizontal_radix()), cv = int(set.vertical_radix());
  t->cell_vars.resize(std::size_t(cells_));
  if (!wang) {
    // pegs: torus R x K points, bounded (R+1) x (K+1)
    int pr = p.torus ? R : R + 1, pc = p.torus ? K : K + 1;
    t->vars = pr * pc;
    t->radix.assign(std::size_t(t->vars), ch);
    auto peg = [&](int r, int c) { return (r % pr) * pc + (c % pc); };
    for (int r = 0; r < R; ++r)
      for (int c = 0; c < K; ++c)  // digits NE, SE, SW, NW (thesis eq. 2.5)
        t->cell_vars[std::size_t(r * K + c)] = {peg(r, c + 1), peg(r + 1, c + 1), peg(r + 1, c), peg(r, c)};
    t->digit_radix = {ch, ch, ch, ch};
  } else {
    // edges: h(r,c) = N edge of cell (r,c), v(r,c) = W edge of cell (r,c)
    int hr = p.torus ? R : R + 1, vc = p.torus ? K : K + 1;
    int nh = hr * K;
    t->vars = nh + R * vc;
    t->radix.assign(std::size_t(t->vars), cv);
    std::fill(t->radix.begin(), t->radix.begin() + nh, ch);
    auto h = [&](int r, int c) { return (r % hr) * K + c; };
    auto v = [&](int r, int c) { return nh + r * vc + (c % vc); };
    for (int r = 0; r < R; ++r)
      for (int c = 0; c < K; ++c)  // digits N, E, S, W (thesis eq. 2.2)
        t->cell_vars[std::size_t(r * K + c)] = {h(r, c), v(r, c + 1), h(r + 1, c), v(r, c)};
    t->digit_radix = {ch, cv, ch, cv};
  }
  t->max_radix = std::max(ch, cv);
  std::size_t total = 1;
  for (int d : t->digit_radix) total *= std::size_t(d);
  // One entry per tile index: (C_h C_v)^2 or C^4; the limit is C = 90.
  if (total > kMaxModelTable)
    throw RequestError("formulation",
                       fmt::format("the {} model needs a table of {} entries for these colours (limit {}); use "
                                   "`formulation` cell",
                                   wang ? "edges" : "pegs", total, kMaxModelTable));
  t->allowed.assign(total, -1);
  for (std::size_t k = 0; k < set.size(); ++k) {
    assert(set.index_of(k) < total);  // a tile's index is its digits in the radices above
    t->allowed[set.index_of(k)] = int(k);
  }
  // var -> cells (CSR)
  std::vector<std::vector<int>> vc(std::size_t(t->vars));
  for (int cell = 0; cell < cells_; ++cell)
    for (int v : t->cell_vars[std::size_t(cell)]) {
      auto& l = vc[std::size_t(v)];
      if (std::find(l.begin(), l.end(), cell) == l.end()) l.push_back(cell);
    }
  t->var_cells_start.push_back(0);
  for (auto& l : vc) {
    t->var_cells.insert(t->var_cells.end(), l.begin(), l.end());
    t->var_cells_start.push_back(int(t->var_cells.size()));
  }
  // Fixed variables (translation breaking): cell (0,0) holds tile number 0.
  std::vector<std::pair<int, int>> fixed;
  if (break_translation_) {
    TileIndex i = set.index_of(0);
    std::array<int, 4> digit{};
    for (int d = 3; d >= 0; --d) {
      digit[std::size_t(d)] = int(i % TileIndex(t->digit_radix[std::size_t(d)]));
      i /= TileIndex(t->digit_radix[std::size_t(d)]);
    }
    for (int d = 0; d < 4; ++d) {
      int v = t->cell_vars[0][std::size_t(d)];
      if (std::none_of(fixed.begin(), fixed.end(), [&](auto& f) { return f.first == v; }))
        fixed.push_back({v, digit[std::size_t(d)]});
    }
  }
  std::vector<char> seen(std::size_t(t->vars), 0);
  for (auto& f : fixed) seen[std::size_t(f.first)] = 1;
  for (int cell = 0; cell < cells_; ++cell)
    for (int v : t->cell_vars[std::size_t(cell)])
      if (!seen[std::size_t(v)]) {
        seen[std::size_t(v)] = 1;
        t->order.push_back(v);
      }
  for (int v = 0; v < t->vars; ++v)  // bounded grids have no unused variables, but be safe
    if (!seen[std::size_t(v)]) t->order.push_back(v);
  t_ = std::move(t);
  value_.assign(std::size_t(t_->vars), -1);
  missing_.assign(std::size_t(cells_), 0);
  for (int cell = 0; cell < cells_; ++cell) {
    auto cv4 = t_->cell_vars[std::size_t(cell)];
    std::sort(cv4.begin(), cv4.end());
    missing_[std::size_t(cell)] = int(std::unique(cv4.begin(), cv4.end()) - cv4.begin());
  }
  marked_.assign(std::size_t(cells_), 0);
  used_.assign(set.size() * std::size_t(classes_), 0);
  fixed_ = int(fixed.size());
  for (auto& f : fixed) assign(f.first, f.second);
  set_value_seed(0);
}

void LatticeModel::set_value_seed(std::uint64_t seed) {
  const Tables& t = *t_;
  perm_.assign(std::size_t(t.vars * t.max_radix), 0);
  SplitMix64 rng(mix_seed(seed));
  for (int v = 0; v < t.vars; ++v) {
    int* p = &perm_[std::size_t(v * t.max_radix)];
    std::iota(p, p + t.radix[std::size_t(v)], 0);
    if (seed) shuffle(p, p + t.radix[std::size_t(v)], rng);
  }
}

int LatticeModel::cell_index(int cell) const {
  const auto& cv = t_->cell_vars[std::size_t(cell)];
  int i = 0;
  for (int d = 0; d < 4; ++d) i = i * t_->digit_radix[std::size_t(d)] + value_[std::size_t(cv[std::size_t(d)])];
  return i;
}

bool LatticeModel::cell_has_option(int cell) const {
  const Tables& t = *t_;
  const auto& cv = t.cell_vars[std::size_t(cell)];
  int free_var = -1;
  for (int v : cv)
    if (value_[std::size_t(v)] < 0) free_var = v;
  assert(free_var >= 0);  // called only for a cell with exactly one distinct free variable
  for (int x = 0; x < t.radix[std::size_t(free_var)]; ++x) {
    int i = 0;
    for (int d = 0; d < 4; ++d) {
      int v = cv[std::size_t(d)];
      i = i * t.digit_radix[std::size_t(d)] + (v == free_var ? x : value_[std::size_t(v)]);
    }
    int k = t.allowed[std::size_t(i)];
    if (k >= 0 && !(packing_ && used_[std::size_t(t.used_base[std::size_t(cell)] + k)])) return true;
  }
  return false;
}

int LatticeModel::branch(std::vector<int>& values) {
  values.clear();
  const Tables& t = *t_;
  if (assigned_ - fixed_ == int(t.order.size())) return -1;
  int var = t.order[std::size_t(assigned_ - fixed_)];
  const int* p = &perm_[std::size_t(var * t.max_radix)];
  values.assign(p, p + t.radix[std::size_t(var)]);
  return var;
}

bool LatticeModel::assign(int var, int x) {
  const Tables& t = *t_;
  // A free variable gets a colour within its radix (the engine's LIFO discipline).
  assert(var >= 0 && var < t.vars && value_[std::size_t(var)] < 0);
  assert(x >= 0 && x < t.radix[std::size_t(var)]);
  value_[std::size_t(var)] = x;
  ++assigned_;
  bool ok = true;
  const int* b = &t.var_cells[std::size_t(t.var_cells_start[std::size_t(var)])];
  const int* e = &t.var_cells[std::size_t(t.var_cells_start[std::size_t(var) + 1])];
  for (const int* c = b; c != e; ++c) {
    if (--missing_[std::size_t(*c)] != 0 || !ok) continue;
    int k = t.allowed[std::size_t(cell_index(*c))];
    if (k >= 0) k += t.used_base[std::size_t(*c)];
    if (k < 0) {
      ok = false;
      stats_.prune(Prune::NoSuchTile);
    } else if (packing_ && used_[std::size_t(k)]) {
      ok = false;
      stats_.prune(Prune::TileUsed);
    } else if (packing_) {
      used_[std::size_t(k)] = 1;
      marked_[std::size_t(*c)] = 1;
    }
  }
  if (!ok) return false;
  for (const int* c = b; c != e; ++c) {  // forward checking
    if (missing_[std::size_t(*c)] != 1) continue;
    ++stats_.propagations;
    if (!cell_has_option(*c)) {
      stats_.prune(Prune::ForwardCheck);
      return false;
    }
  }
  return true;
}

void LatticeModel::unassign(int var, int x) {
  const Tables& t = *t_;
  assert(var >= 0 && var < t.vars && value_[std::size_t(var)] == x && assigned_ > 0);  // LIFO undo
  (void)x;
  const int* b = &t.var_cells[std::size_t(t.var_cells_start[std::size_t(var)])];
  const int* e = &t.var_cells[std::size_t(t.var_cells_start[std::size_t(var) + 1])];
  for (const int* c = b; c != e; ++c) {
    if (missing_[std::size_t(*c)] == 0 && marked_[std::size_t(*c)]) {
      assert(used_[std::size_t(t.used_base[std::size_t(*c)] + t.allowed[std::size_t(cell_index(*c))])]);  // marked cells own their tile
      used_[std::size_t(t.used_base[std::size_t(*c)] + t.allowed[std::size_t(cell_index(*c))])] = 0;
      marked_[std::size_t(*c)] = 0;
    }
    ++missing_[std::size_t(*c)];
  }
  value_[std::size_t(var)] = -1;
  --assigned_;
}

Tiling LatticeModel::tiling() const {
  const TileSet& set = t_->problem.set;
  Tiling out(set.kind(), set.horizontal_radix(), t_->problem.rows, t_->problem.cols, t_->problem.torus);
  if (set.kind() == TileKind::Wang) out.vertical_colours = set.vertical_radix();
  for (int c = 0; c < cells_; ++c) out.cells[std::size_t(c)] = TileIndex(cell_index(c));
  return out;
}

}  // namespace tilekit
