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
// Ties in general (SymbolTies below): the row-difference lift over a known torus sets whole
// columns at once.
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
#include "solver/search_stats.hpp"

namespace tilekit {

// Symbols set together (one decision of the search sets a whole orbit): orbit members are
// (variable, map) pairs, the map sending the decided symbol x to images[map * C + x]. Empty
// orbits: every symbol alone.
struct SymbolTies {
  std::vector<std::vector<std::pair<int, int>>> orbits;  // per orbit; its first member is decided (identity map)
  std::vector<int> images;                               // map * C + x -> symbol
  bool break_translations = true;  // the ties commute with translations: fix the zero window at (0,0)
};

// An imposed group's orbits of torus cells (elements: the group's, identity first).
SymbolTies group_ties(const TilingProblem& problem, const std::vector<GroupElement>& elements);

// The row-difference lift over a known torus A ((K-1) x L windows, r x s, over the same C
// symbols): B(i+1, j) - B(i, j) = A(i mod r, j mod s) (mod C), so column j of B is its top symbol
// c(j) plus the running sums of A's column j mod s, and one decision sets a whole column. B's
// K x L window at (i,j) is its top row and A's window at (i mod r, j mod s) (the differences), a
// bijection; so B is a de Bruijn torus exactly when, for each cell of A, the top rows over the
// cells of B above it are all C^L rows. (Fan, Fan, Ma & Siu 1985 build binary de Bruijn tori this
// way.) Throws InputError when A does not fit: other windows or symbols, sides that do not divide
// B's, or column sums over B's R rows that are not 0 mod C.
SymbolTies row_difference_ties(const TilingProblem& problem, const Tiling& base);

class WindowModel {
 public:
  // `problem.set` is complete_window_set(C, K, L) on an R x S torus (check_window_torus_shape()
  // holds). Periods 0 mean one class (the whole torus); otherwise they divide R and S and each
  // class has C^(KL) cells.
  explicit WindowModel(const TilingProblem& problem, int period_rows = 0, int period_cols = 0,
                       const SymbolTies& ties = {});

  int branch(std::vector<int>& values);
  bool assign(int var, int value);
  void unassign(int var, int value);
  void set_value_seed(std::uint64_t seed);
  Tiling tiling() const;
  std::uint64_t multiplicity() const { return break_translations_ ? std::uint64_t(cells_ / classes_) : 1; }
  // Propagations and prunes (tile-used: a window twice, forward-check); solver/search_stats.hpp.
  ModelStats& stats() { return stats_; }
  // A leaf's translates: by every cell (1, 1), or by multiples of the class periods.
  std::pair<int, int> translation_steps() const { return {period_rows_, period_cols_}; }

 private:
  ModelStats stats_;
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
  bool infeasible_ = false;       // the fixed zero window contradicts the ties: no solution
  bool break_translations_ = true;
};

static_assert(SearchModel<WindowModel>);

}  // namespace tilekit
