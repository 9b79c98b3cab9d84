#pragma once
// The lattice formulations: the variables are colours on the lattice, not tiles.
//  - pegs (corner tiles): one colour per lattice point; cell (r,c) holds the tile whose
//    corners are the pegs (r,c),(r,c+1),(r+1,c),(r+1,c+1). A corner packing is thus a
//    (C^2,C^2;2,2)_C de Bruijn torus: every 2x2 window of pegs occurs exactly once.
//  - edges (Wang tiles): one colour per edge; cell (r,c) holds the tile with N = h(r,c),
//    E = v(r,c+1), S = h(r+1,c), W = v(r,c).
// Matching is then automatic; the constraints are "each cell's four colours form a tile of the
// set" and, for packings, "no tile twice". Variables are assigned in the order that completes
// cells scanline by scanline; forward checking fails as soon as a cell with one free colour has
// no colour left that gives an allowed, unused tile. Translations of a packing torus are
// broken like in CellModel (tile 0 fixed at cell (0,0)).
//
// With a class period P > 0 (colour-quotient lifts, solver/colour_lift_model.hpp) "no tile twice"
// becomes "no tile twice within a residue class of cells (r mod P, c mod P)": the packing
// condition of a lift quotient. Fixing tile 0 at (0,0) then breaks the translations by multiples
// of P (which map classes to themselves), so a leaf stands for (R/P)(K/P) quotients.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "solver/model.hpp"
#include "solver/problem.hpp"
#include "solver/search_stats.hpp"

namespace tilekit {

class LatticeModel {
 public:
  LatticeModel(const TilingProblem& problem, bool break_translation, int class_period = 0);

  int branch(std::vector<int>& values);
  bool assign(int var, int value);
  void unassign(int var, int value);
  void set_value_seed(std::uint64_t seed);
  Tiling tiling() const;
  std::uint64_t multiplicity() const { return break_translation_ ? std::uint64_t(cells_ / classes_) : 1; }
  // Propagations and prunes (no-such-tile, tile-used, forward-check); solver/search_stats.hpp.
  ModelStats& stats() { return stats_; }
  int class_period() const { return class_period_; }

 private:
  ModelStats stats_;
  struct Tables;
  int cell_index(int cell) const;        // all four colours assigned
  bool cell_has_option(int cell) const;  // exactly one colour free

  std::shared_ptr<const Tables> t_;
  int cells_ = 0, classes_ = 1, class_period_ = 0;
  bool break_translation_ = false, packing_ = false;
  std::vector<int> value_;      // var -> colour or -1
  std::vector<int> missing_;    // cell -> free colours among its four
  std::vector<char> marked_;    // cell -> its tile is marked used
  std::vector<char> used_;      // class * tiles + tile number -> used (packing)
  std::vector<int> order_pos_;  // (unused vars) order of branching
  std::vector<int> perm_;       // var*max_radix + k -> k-th colour tried
  int assigned_ = 0, fixed_ = 0;
};

static_assert(SearchModel<LatticeModel>);

}  // namespace tilekit
