#pragma once
// The tile-per-cell formulation: one variable per grid cell, whose values are the tiles of
// the set. Works for every problem solve() accepts: Wang or corner sets (a corner tile is a
// Wang tile whose edge colours are pairs of corner colours, thesis sec. 2.9), torus or
// bounded rectangle, packing (each tile once) or tiling (tiles repeat).
//
// Domains are bitsets over the tiles. A cell's domain is the intersection of the tiles whose
// edges match each placed neighbour (one precomputed mask per edge and colour) and, for
// packings, the unused tiles. Forward checking: placing a tile fails at once when a free
// neighbour's domain becomes empty.
//
// Translations of a packing torus are broken by fixing tile 0 at cell (0,0): every packing
// has exactly one translate with tile 0 there, and no packing is its own translate (each tile
// occurs once), so each leaf stands for rows*cols packings (multiplicity()).
//
// With a class period P > 0 (colour-quotient lifts, solver/colour_lift_model.hpp) each tile is used
// once per residue class of cells (r mod P, c mod P) instead of once overall: the unused tiles
// are kept per class, forward checking also visits the free cells of the placed tile's class,
// and a leaf stands for the (rows/P)(cols/P) translates by multiples of P.
#include <cstdint>
#include <memory>
#include <set>
#include <utility>
#include <vector>

#include "solver/model.hpp"
#include "solver/problem.hpp"
#include "solver/search_stats.hpp"

namespace tilekit {

class CellModel {
 public:
  enum class Ordering { Static, MostConstrained };
  CellModel(const TilingProblem& problem, bool break_translation, Ordering ordering, int class_period = 0);

  int branch(std::vector<int>& values);
  bool assign(int cell, int tile);
  void unassign(int cell, int tile);
  void set_value_seed(std::uint64_t seed);
  Tiling tiling() const;
  std::uint64_t multiplicity() const { return break_translation_ ? std::uint64_t(cells_ / classes_) : 1; }

  // Propagations (free domains checked by forward checking) and prunes (forward-check,
  // class-check); solver/search_stats.hpp.
  ModelStats& stats() { return stats_; }

  int cells() const { return cells_; }
  int tiles() const { return tiles_; }

 private:
  struct Tables;  // immutable, shared by every copy
  void rebuild_masks();
  // Writes the domain of `cell` into dom (words_ words); returns its size.
  int domain(int cell, std::uint64_t* dom) const;
  bool domain_empty(int cell) const;

  std::shared_ptr<const Tables> t_;
  int cells_ = 0, tiles_ = 0, words_ = 0, classes_ = 1;
  bool break_translation_ = false, packing_ = false;
  Ordering ordering_;
  std::vector<int> perm_;             // internal value -> tile number in the set (value order)
  std::vector<int> label_;            // internal value*4 + dir -> edge label (dir: N E S W)
  std::vector<std::uint64_t> masks_;  // (dir*labels + label)*words_: values whose dir edge == label
  std::vector<std::uint64_t> avail_;  // class*words_: values still usable (packing) or valid (tiling)
  std::vector<int> tile_;             // cell -> internal value or -1
  int assigned_ = 0, fixed_ = 0;
  int first_free_ = 0;  // every cell below it is assigned (where the MRV scan starts)
  // Most constrained first, incrementally: (domain size, cell) of the free cells next to a
  // placed tile, and each cell's key in it (-1: not in it). See the constructor.
  void refresh(int cell);
  void refresh_around(int cell);
  bool incremental_ = false;
  std::set<std::pair<int, int>> frontier_;
  std::vector<int> frontier_key_;
  mutable std::vector<std::uint64_t> scratch_;
  ModelStats stats_;
};

static_assert(SearchModel<CellModel>);

}  // namespace tilekit
