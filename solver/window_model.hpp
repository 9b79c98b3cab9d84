#pragma once
// The window model: de Bruijn tori (perfect maps) with K x L windows over C symbols as a model of
// the one engine (tilesets/window_torus.hpp). The variables are the R*S symbols P(r,c) of the
// torus; cell (r,c) is the window whose top-left symbol is P(r,c). The constraint is "no window
// twice" (the torus has exactly C^(KL) cells, so no window is missing either). Variables are
// assigned in scanline order; a window is checked when its last symbol is set, and forward
// checking fails as soon as a window with one free symbol has no value left that makes an unused
// window. It is the pegs formulation of LatticeModel with K x L windows instead of 2 x 2 corners.
//
// Translations are broken as in the other models: the all-zero window sits at cell (0,0), so a
// leaf stands for its R*S translates (all distinct: the zero window moves).
//
// Under an imposed group (solver/impose_group.hpp: torus translations t paired with symbol
// permutations pi, P(x + t) = pi(P(x))) the variables are one symbol per orbit of torus cells:
// assigning it sets the whole orbit. A group element other than the identity moves every window
// to a different one (pi has no fixed point), so the windows come in orbits of |G| and the search
// covers a fundamental domain (as solver/impose_model.hpp does for corner and Wang packings).
//
// With class periods (P_r, P_c) (colour-quotient lifts of window tori, window_torus.hpp) "no
// window twice" holds within each residue class of cells (r mod P_r, c mod P_c): the packing
// condition of a lift quotient. Fixing the zero window at (0,0) then breaks only the translations
// by multiples of the periods, so a leaf stands for (R/P_r)(S/P_c) quotients.
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "solver/impose_group.hpp"
#include "solver/model.hpp"
#include "solver/problem.hpp"

namespace tilekit {

class WindowModel {
 public:
  // `problem.set` is complete_window_set(C, K, L) on an R x S torus (check_window_torus_shape()
  // holds). Periods 0 mean one class (the whole torus); otherwise they divide R and S and each
  // class has C^(KL) cells.
  // `group`: the elements of an imposed group (identity first; empty: none).
  explicit WindowModel(const TilingProblem& problem, int period_rows = 0, int period_cols = 0,
                       const std::vector<GroupElement>& group = {});

  int branch(std::vector<int>& values);
  bool assign(int var, int value);
  void unassign(int var, int value);
  void set_value_seed(std::uint64_t seed);
  Tiling tiling() const;
  std::uint64_t multiplicity() const { return std::uint64_t(cells_ / classes_); }
  // A leaf's translates: by every cell (1, 1), or by multiples of the class periods.
  std::pair<int, int> translation_steps() const { return {period_rows_, period_cols_}; }

 private:
  struct Tables;
  std::uint32_t window_of(int cell) const;  // all its symbols assigned
  bool cell_has_option(int cell) const;     // exactly one symbol free
  bool set_symbol(int var, int x, bool ok);  // one symbol of an orbit: its windows counted and checked

  std::shared_ptr<const Tables> t_;
  int cells_ = 0, classes_ = 1, period_rows_ = 1, period_cols_ = 1;
  std::vector<int> value_;      // var -> symbol or -1
  std::vector<int> missing_;    // cell -> free symbols of its window
  std::vector<char> used_;      // class * windows + window -> used
  std::vector<char> marked_;    // cell -> its window is marked used
  std::vector<int> perm_;       // var * C + k -> k-th symbol tried
  int assigned_ = 0, fixed_ = 0;  // orbits
  bool infeasible_ = false;       // the fixed zero window contradicts the group: no solution
};

static_assert(SearchModel<WindowModel>);

}  // namespace tilekit
