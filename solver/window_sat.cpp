// De Bruijn tori (and window lift quotients) as CNF for cadical.
//   - x(v, s): symbol v of the torus is s; one Boolean per symbol when C = 2, else one per value
//     with exactly one true.
//   - y(cell, w): the window at `cell` is w: y implies each of its K*L symbol literals, and the
//     K*L literals together imply y.
//   - every class of cells (the whole torus, or a residue class mod the lift's periods) holds
//     every window exactly once: one clause over y(., w) per class and window, and at most one
//     of them (sequential counter, Sinz 2005). "At least once" alone would do (a class has as
//     many cells as there are windows), but the at-most-one with the implied y propagates a
//     repeated window as soon as its symbols are set (cadical found nothing in 300 s without).
//   - the zero window sits at cell (0,0) (translations, as in the engine).
//   - tied symbols (an imposed group: x(v, s) <-> x(v + t, pi(s)); the row-difference lift: a
//     column is its top symbol plus fixed sums) as equivalences of their value literals.
// Binary 3x3 windows on 16x32: 512 symbol and 262,144 window variables, 3.6 M clauses.
#include <fmt/format.h>

#include <optional>

#include "base/error.hpp"
#include "solver/sat_cnf.hpp"
#include "solver/window_sat.hpp"
#include "tilesets/window_torus.hpp"

namespace tilekit {

namespace {

struct WindowCnf {
  CnfBuilder cnf;
  int rows = 0, cols = 0, K = 0, L = 0, first_symbol_var = 1;
  std::uint32_t C = 0;
  int lit(int v, int s) const {  // "symbol v is s"
    if (C == 2) return s ? first_symbol_var + v : -(first_symbol_var + v);
    return first_symbol_var + v * int(C) + s;
  }
};

WindowCnf build_window_cnf(const TilingProblem& q, int period_rows, int period_cols, bool fix_zero_window = true) {
  WindowCnf e;
  const TileSet& set = q.set;
  e.rows = q.rows, e.cols = q.cols, e.K = set.window_rows(), e.L = set.window_cols(), e.C = set.horizontal_radix();
  const int cells = e.rows * e.cols, D = e.K * e.L, windows = int(set.size());
  if (period_rows == 0) period_rows = period_cols = 1;  // one class: the whole torus
  if (std::uint64_t(cells) * std::uint64_t(windows) > kMaxWindowCnfIndicators)
    throw RequestError(
        "formulation",
        fmt::format("the CNF would need {} x {} window variables (limit {}): use the engine (`formulation` "
                    "auto)",
                    cells, windows, kMaxWindowCnfIndicators));
  e.first_symbol_var = e.cnf.new_vars(e.C == 2 ? cells : cells * int(e.C));
  if (e.C != 2)
    for (int v = 0; v < cells; ++v) {
      std::vector<int> lits;
      for (int s = 0; s < int(e.C); ++s) lits.push_back(e.lit(v, s));
      e.cnf.exactly_one(lits);
    }
  const int classes = period_rows * period_cols;
  std::vector<std::vector<int>> per_class_window(std::size_t(classes) * std::size_t(windows));
  std::vector<int> digit(static_cast<std::size_t>(D)), var(static_cast<std::size_t>(D));
  for (int r = 0; r < e.rows; ++r)
    for (int c = 0; c < e.cols; ++c) {
      for (int a = 0; a < e.K; ++a)
        for (int b = 0; b < e.L; ++b) var[std::size_t(a * e.L + b)] = ((r + a) % e.rows) * e.cols + (c + b) % e.cols;
      const int first_y = e.cnf.new_vars(windows);
      const int cls = (r % period_rows) * period_cols + c % period_cols;
      std::vector<int> back(static_cast<std::size_t>(D) + 1);
      for (int w = 0; w < windows; ++w) {
        int x = w;
        for (int d = D - 1; d >= 0; --d, x /= int(e.C)) digit[std::size_t(d)] = x % int(e.C);
        for (int d = 0; d < D; ++d) {
          e.cnf.clause({-(first_y + w), e.lit(var[std::size_t(d)], digit[std::size_t(d)])});
          back[std::size_t(d)] = -e.lit(var[std::size_t(d)], digit[std::size_t(d)]);
        }
        back[std::size_t(D)] = first_y + w;  // the symbols that spell w imply y (propagates a used window)
        e.cnf.clause(back);
        per_class_window[std::size_t(cls) * std::size_t(windows) + std::size_t(w)].push_back(first_y + w);
      }
      if (r == 0 && c == 0 && fix_zero_window) e.cnf.clause({first_y});  // the zero window at (0,0)
    }
  for (const auto& lits : per_class_window) e.cnf.exactly_one(lits);
  return e;
}

Tiling decode(const WindowCnf& e, const std::vector<char>& value) {
  std::vector<Colour> pegs(std::size_t(e.rows) * std::size_t(e.cols));
  for (std::size_t v = 0; v < pegs.size(); ++v) {
    if (e.C == 2) {
      pegs[v] = value[std::size_t(e.first_symbol_var) + v] ? 1 : 0;
      continue;
    }
    int s = 0;
    while (s < int(e.C) && !value[std::size_t(e.lit(int(v), s))]) ++s;
    if (s == int(e.C)) throw std::logic_error("the SAT model leaves a symbol without a value");
    pegs[v] = Colour(s);
  }
  return window_torus_from_pegs(pegs, e.rows, e.cols, e.C, e.K, e.L);
}

}  // namespace

std::string window_cnf(const TilingProblem& quotient, int period_rows, int period_cols, std::uint64_t* variables,
                       std::uint64_t* clauses) {
  WindowCnf e = build_window_cnf(quotient, period_rows, period_cols);
  if (variables) *variables = e.cnf.variables();
  if (clauses) *clauses = e.cnf.clauses();
  return e.cnf.dimacs();
}

SearchResult solve_window_sat(const TilingProblem& problem, const WindowLiftProblem* lift, const SymbolTies& ties,
                              const SearchOptions& o, const std::string& fingerprint) {
  std::optional<WindowCnf> e;
  auto build = [&]() -> const CnfBuilder& {
    e = lift ? build_window_cnf(lift->quotient, lift->base.rows, lift->base.cols)
             : build_window_cnf(problem, 0, 0, ties.orbits.empty() || ties.break_translations);
    for (const auto& orbit : ties.orbits)  // tied symbols: x(first, s) <-> x(u, image of s)
      for (std::size_t k = 1; k < orbit.size(); ++k) {
        const auto [u, map] = orbit[k];
        for (int s = e->C == 2 ? 1 : 0; s < int(e->C); ++s) {
          const int a = e->lit(orbit.front().first, s),
                    b = e->lit(u, ties.images[std::size_t(map) * e->C + std::size_t(s)]);
          e->cnf.clause({-a, b});
          e->cnf.clause({a, -b});
        }
      }
    return e->cnf;
  };
  auto decoded = [&](const std::vector<char>& value) {
    Tiling a = decode(*e, value);
    return lift ? window_colour_lift(lift->base, a) : a;
  };
  return solve_by_sat(problem, o, fingerprint, {"torus", "window", "torus", "not a de Bruijn torus"}, build, decoded);
}

}  // namespace tilekit
