#include "solver/window_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <numeric>

#include "base/error.hpp"
#include "tilesets/window_torus.hpp"

namespace tilekit {

struct WindowModel::Tables {
  int rows = 0, cols = 0, window_rows = 0, window_cols = 0, digits = 0;
  int colours = 0;
  std::uint32_t windows = 0;                // C^(KL)
  std::vector<int> cell_vars;               // cell * digits + d -> the variable of digit d (row-major)
  std::vector<std::uint32_t> weight;        // digit d -> C^(digits-1-d)
  std::vector<int> var_cells_start;         // CSR: var -> (cell, digit) pairs of the windows holding it
  std::vector<std::pair<int, int>> var_cells;
  std::vector<std::uint32_t> used_base;     // cell -> class * windows
  std::vector<int> order;                   // branching order of the free orbits (their first symbol)
  std::vector<int> orbit_start;             // CSR: orbit representative -> (var, element) pairs
  std::vector<std::pair<int, int>> orbit;   // the representative first (identity)
  std::vector<int> rep;                     // var -> its orbit's representative
  std::vector<int> image;                   // element * C + symbol -> its image
};

SymbolTies group_ties(const TilingProblem& p, const std::vector<GroupElement>& elements) {
  const int R = p.rows, S = p.cols, C = int(p.set.horizontal_radix());
  SymbolTies ties;
  ties.images.resize(elements.size() * std::size_t(C));
  for (std::size_t g = 0; g < elements.size(); ++g)
    for (int x = 0; x < C; ++x) ties.images[g * std::size_t(C) + std::size_t(x)] = int(elements[g].ph[std::size_t(x)]);
  std::vector<char> seen(std::size_t(R) * std::size_t(S), 0);
  for (int v = 0; v < R * S; ++v) {
    if (seen[std::size_t(v)]) continue;
    ties.orbits.emplace_back();
    for (std::size_t g = 0; g < elements.size(); ++g) {
      const int u = ((v / S + elements[g].dr) % R) * S + (v % S + elements[g].dc) % S;
      assert(!seen[std::size_t(u)]);  // the group acts freely on cells (|orbit| = |G|)
      seen[std::size_t(u)] = 1;
      ties.orbits.back().push_back({u, int(g)});
    }
  }
  return ties;
}

SymbolTies row_difference_ties(const TilingProblem& p, const Tiling& a) {
  const TileSet& set = p.set;
  const int R = p.rows, S = p.cols, C = int(set.horizontal_radix());
  if (a.kind != TileKind::Window || a.window_rows != set.window_rows() - 1 || a.window_cols != set.window_cols() ||
      int(a.colours) != C || !a.torus || R % a.rows != 0 || S % a.cols != 0)
    throw InputError(fmt::format("the row-difference lift of {}x{} windows over {} symbols on {}x{} needs a torus with "
                                 "{}x{} windows over {} symbols whose sides divide {}x{}",
                                 set.window_rows(), set.window_cols(), C, R, S, set.window_rows() - 1,
                                 set.window_cols(), C, R, S));
  const std::vector<Colour> d = pegs_of_window_torus(a);
  SymbolTies ties;
  ties.break_translations = false;  // translations by other than multiples of A's sides change the differences
  ties.images.resize(std::size_t(C) * std::size_t(C));
  for (int m = 0; m < C; ++m)
    for (int x = 0; x < C; ++x) ties.images[std::size_t(m * C + x)] = (x + m) % C;  // map m: add m
  for (int j = 0; j < S; ++j) {
    ties.orbits.emplace_back();
    int sum = 0;  // B(i, j) - B(0, j)
    for (int i = 0; i < R; ++i) {
      ties.orbits.back().push_back({i * S + j, sum});
      sum = (sum + int(d[std::size_t(i % a.rows) * std::size_t(a.cols) + std::size_t(j % a.cols)])) % C;
    }
    if (sum != 0)
      throw InputError(fmt::format("the row-difference lift: column {} of the base sums to {} mod {} over {} rows, so "
                                   "the lifted columns do not close on the {}x{} torus",
                                   j % a.cols, sum, C, R, R, S));
  }
  return ties;
}

WindowModel::WindowModel(const TilingProblem& p, int period_rows, int period_cols, const SymbolTies& given) {
  const TileSet& set = p.set;
  if (set.kind() != TileKind::Window)
    throw RequestError("kind", "the window model searches window tori (`kind` window)");
  auto t = std::make_shared<Tables>();
  t->rows = p.rows, t->cols = p.cols;
  t->window_rows = set.window_rows(), t->window_cols = set.window_cols();
  t->digits = t->window_rows * t->window_cols;
  t->colours = int(set.horizontal_radix());
  t->windows = std::uint32_t(set.size());
  cells_ = p.rows * p.cols;
  if (period_rows > 0) {
    if (t->window_rows > p.rows || t->window_cols > p.cols || p.rows % period_rows != 0 || p.cols % period_cols != 0 ||
        std::uint64_t(p.rows / period_rows) * std::uint64_t(p.cols / period_cols) != t->windows)
      throw InputError(fmt::format("a {}x{} torus in classes mod {}x{} does not hold each of the {} windows once per "
                                   "class",
                                   p.rows, p.cols, period_rows, period_cols, t->windows));
    period_rows_ = period_rows, period_cols_ = period_cols;
    classes_ = period_rows * period_cols;
  } else {
    check_window_torus_shape(std::uint32_t(t->colours), t->window_rows, t->window_cols, t->rows, t->cols);
  }
  if (std::uint64_t(classes_) * t->windows > kMaxModelTable)
    throw InputError(fmt::format("the window model needs {} x {} used-window flags (limit {})", classes_, t->windows,
                                 kMaxModelTable));
  const int D = t->digits, R = t->rows, S = t->cols;
  t->weight.assign(std::size_t(D), 1);
  for (int d = D - 2; d >= 0; --d) t->weight[std::size_t(d)] = t->weight[std::size_t(d) + 1] * std::uint32_t(t->colours);
  t->cell_vars.resize(std::size_t(cells_) * std::size_t(D));
  t->used_base.resize(std::size_t(cells_));
  std::vector<std::vector<std::pair<int, int>>> holders(static_cast<std::size_t>(cells_));
  for (int r = 0; r < R; ++r)
    for (int c = 0; c < S; ++c) {
      const int cell = r * S + c;
      for (int a = 0; a < t->window_rows; ++a)
        for (int b = 0; b < t->window_cols; ++b) {
          const int d = a * t->window_cols + b, v = ((r + a) % R) * S + (c + b) % S;
          t->cell_vars[std::size_t(cell) * std::size_t(D) + std::size_t(d)] = v;
          holders[std::size_t(v)].push_back({cell, d});
        }
      const int cls = classes_ > 1 ? (r % period_rows_) * period_cols_ + c % period_cols_ : 0;
      t->used_base[std::size_t(cell)] = std::uint32_t(cls) * t->windows;
    }
  t->var_cells_start.push_back(0);
  for (const auto& h : holders) {
    t->var_cells.insert(t->var_cells.end(), h.begin(), h.end());
    t->var_cells_start.push_back(int(t->var_cells.size()));
  }
  // Orbits of tied symbols (each symbol alone without ties); the first member is decided.
  const int C = t->colours;
  SymbolTies alone;
  if (given.orbits.empty()) {
    alone.images.resize(std::size_t(C));
    for (int x = 0; x < C; ++x) alone.images[std::size_t(x)] = x;
    for (int v = 0; v < cells_; ++v) alone.orbits.push_back({{v, 0}});
  }
  const SymbolTies& ties = given.orbits.empty() ? alone : given;
  break_translations_ = ties.break_translations;
  t->image = ties.images;
  t->rep.assign(std::size_t(cells_), -1);
  t->orbit_start.assign(std::size_t(cells_) + 1, 0);
  std::vector<std::vector<std::pair<int, int>>> orbits(static_cast<std::size_t>(cells_));
  for (const auto& o : ties.orbits) {
    assert(!o.empty() && t->image[std::size_t(o.front().second) * std::size_t(C)] == 0);  // decided: identity
    for (const auto& [u, map] : o) {
      assert(t->rep[std::size_t(u)] < 0);  // every symbol in one orbit
      t->rep[std::size_t(u)] = o.front().first;
    }
    orbits[std::size_t(o.front().first)] = o;
  }
  for (int v = 0; v < cells_; ++v) {
    assert(t->rep[std::size_t(v)] >= 0);
    t->orbit.insert(t->orbit.end(), orbits[std::size_t(v)].begin(), orbits[std::size_t(v)].end());
    t->orbit_start[std::size_t(v) + 1] = int(t->orbit.size());
  }
  // Translation breaking: the zero window at cell (0,0), i.e. its K x L symbols are 0.
  std::vector<char> fixed(std::size_t(cells_), 0);
  if (break_translations_)
    for (int d = 0; d < D; ++d) fixed[std::size_t(t->rep[std::size_t(t->cell_vars[std::size_t(d)])])] = 1;
  for (int v = 0; v < cells_; ++v)
    if (t->rep[std::size_t(v)] == v && !fixed[std::size_t(v)]) t->order.push_back(v);
  t_ = std::move(t);
  value_.assign(std::size_t(cells_), -1);
  missing_.assign(std::size_t(cells_), D);
  used_.assign(std::size_t(classes_) * t_->windows, 0);
  marked_.assign(std::size_t(cells_), 0);
  for (int d = 0; d < D && break_translations_ && !infeasible_; ++d) {
    const int v = t_->cell_vars[std::size_t(d)], r = t_->rep[std::size_t(v)];
    if (value_[std::size_t(v)] >= 0) {  // set through another symbol of its orbit
      infeasible_ = value_[std::size_t(v)] != 0;
      continue;
    }
    // the representative's symbol that gives v the symbol 0
    const int g = [&] {
      for (int k = t_->orbit_start[std::size_t(r)]; k < t_->orbit_start[std::size_t(r) + 1]; ++k)
        if (t_->orbit[std::size_t(k)].first == v) return t_->orbit[std::size_t(k)].second;
      return 0;
    }();
    int x = 0;
    while (t_->image[std::size_t(g) * std::size_t(C) + std::size_t(x)] != 0) ++x;
    ++fixed_;
    infeasible_ = !assign(r, x);
  }
  set_value_seed(0);
}

void WindowModel::set_value_seed(std::uint64_t seed) {
  const int C = t_->colours;
  perm_.assign(std::size_t(cells_) * std::size_t(C), 0);
  SplitMix64 rng(mix_seed(seed));
  for (int v = 0; v < cells_; ++v) {
    int* p = &perm_[std::size_t(v) * std::size_t(C)];
    std::iota(p, p + C, 0);
    if (seed) shuffle(p, p + C, rng);
  }
}

std::uint32_t WindowModel::window_of(int cell) const {
  const Tables& t = *t_;
  const int* cv = &t.cell_vars[std::size_t(cell) * std::size_t(t.digits)];
  std::uint32_t w = 0;
  for (int d = 0; d < t.digits; ++d) w += std::uint32_t(value_[std::size_t(cv[d])]) * t.weight[std::size_t(d)];
  return w;
}

bool WindowModel::cell_has_option(int cell) const {
  const Tables& t = *t_;
  const int* cv = &t.cell_vars[std::size_t(cell) * std::size_t(t.digits)];
  std::uint32_t base = t.used_base[std::size_t(cell)], step = 0;
  for (int d = 0; d < t.digits; ++d) {
    const int x = value_[std::size_t(cv[d])];
    if (x < 0)
      step = t.weight[std::size_t(d)];
    else
      base += std::uint32_t(x) * t.weight[std::size_t(d)];
  }
  assert(step > 0);  // called only for a window with exactly one free symbol
  for (int x = 0; x < t.colours; ++x, base += step)
    if (!used_[base]) return true;
  return false;
}

int WindowModel::branch(std::vector<int>& values) {
  values.clear();
  const Tables& t = *t_;
  if (infeasible_) return 0;  // no values: the root has no child
  if (assigned_ - fixed_ == int(t.order.size())) return -1;
  const int var = t.order[std::size_t(assigned_ - fixed_)];
  const int* p = &perm_[std::size_t(var) * std::size_t(t.colours)];
  values.assign(p, p + t.colours);
  return var;
}

bool WindowModel::set_symbol(int var, int x, bool ok) {
  const Tables& t = *t_;
  value_[std::size_t(var)] = x;
  const auto* b = &t.var_cells[std::size_t(t.var_cells_start[std::size_t(var)])];
  const auto* e = &t.var_cells[std::size_t(t.var_cells_start[std::size_t(var) + 1])];
  for (const auto* h = b; h != e; ++h) {
    const int cell = h->first;
    if (--missing_[std::size_t(cell)] != 0 || !ok) continue;
    const std::uint32_t k = t.used_base[std::size_t(cell)] + window_of(cell);
    if (used_[k]) {
      ok = false;
      stats_.prune(Prune::TileUsed);  // the window is already on the torus
    } else {
      used_[k] = 1;
      marked_[std::size_t(cell)] = 1;
    }
  }
  return ok;
}

bool WindowModel::assign(int var, int x) {
  const Tables& t = *t_;
  // A free orbit gets a symbol below C (the engine's LIFO discipline).
  assert(var >= 0 && var < cells_ && t.rep[std::size_t(var)] == var && value_[std::size_t(var)] < 0 && x >= 0 &&
         x < t.colours);
  ++assigned_;
  const int first = t.orbit_start[std::size_t(var)], last = t.orbit_start[std::size_t(var) + 1];
  bool ok = true;
  for (int k = first; k < last; ++k) {
    const auto [v, g] = t.orbit[std::size_t(k)];
    ok = set_symbol(v, t.image[std::size_t(g) * std::size_t(t.colours) + std::size_t(x)], ok);
  }
  if (!ok) return false;
  for (int k = first; k < last; ++k) {  // forward checking
    const int v = t.orbit[std::size_t(k)].first;
    const auto* b = &t.var_cells[std::size_t(t.var_cells_start[std::size_t(v)])];
    const auto* e = &t.var_cells[std::size_t(t.var_cells_start[std::size_t(v) + 1])];
    for (const auto* h = b; h != e; ++h) {
      if (missing_[std::size_t(h->first)] != 1) continue;
      ++stats_.propagations;
      if (!cell_has_option(h->first)) {
        stats_.prune(Prune::ForwardCheck);
        return false;
      }
    }
  }
  return true;
}

void WindowModel::unassign(int var, int x) {
  const Tables& t = *t_;
  assert(var >= 0 && var < cells_ && value_[std::size_t(var)] == x && assigned_ > 0);  // LIFO undo
  (void)x;
  for (int k = t.orbit_start[std::size_t(var) + 1]; k-- > t.orbit_start[std::size_t(var)];) {
    const int v = t.orbit[std::size_t(k)].first;
    const auto* b = &t.var_cells[std::size_t(t.var_cells_start[std::size_t(v)])];
    const auto* e = &t.var_cells[std::size_t(t.var_cells_start[std::size_t(v) + 1])];
    for (const auto* h = b; h != e; ++h) {
      const int cell = h->first;
      if (missing_[std::size_t(cell)] == 0 && marked_[std::size_t(cell)]) {
        const std::uint32_t w = t.used_base[std::size_t(cell)] + window_of(cell);
        assert(used_[w]);  // a marked cell owns its window
        used_[w] = 0;
        marked_[std::size_t(cell)] = 0;
      }
      ++missing_[std::size_t(cell)];
    }
    value_[std::size_t(v)] = -1;
  }
  --assigned_;
}

Tiling WindowModel::tiling() const {
  const Tables& t = *t_;
  std::vector<Colour> pegs(value_.begin(), value_.end());
  return window_torus_from_pegs(pegs, t.rows, t.cols, std::uint32_t(t.colours), t.window_rows, t.window_cols);
}

}  // namespace tilekit
