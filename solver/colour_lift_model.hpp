#pragma once
// Colour-quotient lifts as a subspace the one engine searches.
//
// A packing over C = k*m colours is sought in the form A = B + m*E (every corner or edge colour):
// B is a known packing over m colours on the m^2 x m^2 torus (period P = m^2), E a k-colour
// tiling of the k^2 P x k^2 P torus. A is a packing exactly when, on each residue class of cells
// mod P, E's tiles are every k-colour tile exactly once (proof: tilesets/construct_lift.cpp), so
// the search runs over E: the lattice model (pegs for corner tiles, edges for Wang tiles) of the
// complete k-colour set with the packing condition per class (LatticeModel's class period), and
// every leaf is lifted to A and checked by the independent validator like any other solution.
// A leaf stands for the k^4 translates of E by multiples of P (each lifts to a packing).
//
// SPEC (`pack --lift SPEC`): "M" or "m=M" with M the base colour count, optionally followed by
// ",base=FILE" (a packing file over M colours; default: construct_packing(kind, M), i.e. the
// stored, closed-form or lifted packing). C must be a multiple k*M with k >= 2.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "solver/cell_model.hpp"
#include "solver/lattice_model.hpp"
#include "solver/problem.hpp"
#include "tilesets/constructions.hpp"

namespace tilekit {

struct LiftSpec {
  std::uint32_t base_colours = 0;  // m
  std::string base_file;           // "" = construct_packing(kind, m)
  std::string text() const;        // normalised spec, e.g. "m=4" or "m=4,base=b.json"
};

// Throws InputError naming --lift and the problem. base=FILE is the last field and runs to the
// end of the text, so a file name may hold commas ("m=2,base=a,b.json" is the file "a,b.json").
LiftSpec parse_lift_spec(const std::string& text);

// The spec with a relative base file made absolute (as the current directory resolves it), so
// that a checkpoint that stores the spec resumes from any directory; other specs unchanged.
std::string lift_with_absolute_base(const std::string& text);

struct LiftProblem {
  LiftSpec spec;
  Tiling base;              // B: a packing over m colours (checked by the validator)
  std::string base_how;     // where B came from ("stored", "debruijn-triangular", a file, ...)
  std::uint32_t colours = 0, quotient_colours = 0;  // C and k
  int period = 0;           // P = m^2
  TilingProblem quotient;   // the complete k-colour set on the k^2 P torus (packing per class)
};

// Throws InputError when C is not k*m with k >= 2, no packing over m colours is known or the
// base file is not one.
LiftProblem make_lift_problem(TileKind kind, std::uint32_t colours, const LiftSpec& spec);

// The quotient searched by `Inner` (LatticeModel: pegs/edges in scanline order, or CellModel:
// tile per cell, most constrained first), both with the packing condition per residue class.
template <class Inner>
class LiftModelOf {
 public:
  LiftModelOf(const LiftProblem& p, Inner inner)
      : e_(std::move(inner)), base_(std::make_shared<const Tiling>(p.base)), period_(p.period) {}

  int branch(std::vector<int>& values) { return e_.branch(values); }
  bool assign(int var, int value) { return e_.assign(var, value); }
  void unassign(int var, int value) { e_.unassign(var, value); }
  void set_value_seed(std::uint64_t seed) { e_.set_value_seed(seed); }
  Tiling tiling() const { return colour_lift(*base_, e_.tiling()); }  // A = B + m*E
  Tiling quotient() const { return e_.tiling(); }
  std::uint64_t multiplicity() const { return e_.multiplicity(); }
  ModelStats& stats() { return e_.stats(); }
  // A leaf's other solutions are its translates by multiples of the period (solve.cpp).
  int translation_step() const { return period_; }

 private:
  Inner e_;
  std::shared_ptr<const Tiling> base_;
  int period_ = 1;
};

// The two quotient models (formulations "lift" and "lift-cell").
inline LiftModelOf<LatticeModel> lift_lattice_model(const LiftProblem& p) {
  return {p, LatticeModel(p.quotient, true, p.period)};
}
inline LiftModelOf<CellModel> lift_cell_model(const LiftProblem& p) {
  return {p, CellModel(p.quotient, true, CellModel::Ordering::MostConstrained, p.period)};
}
using LiftModel = LiftModelOf<LatticeModel>;

static_assert(SearchModel<LiftModelOf<LatticeModel>> && SearchModel<LiftModelOf<CellModel>>);

// The lift searched as CNF by cadical (lift_sat.cpp): first mode only; the result is validated
// like the engine's. Called by solve() for `--lift SPEC --formulation sat`.
SearchResult solve_lift_sat(const LiftProblem& lift, const TilingProblem& problem, const SearchOptions& options,
                            const std::string& fingerprint);

// The CNF of the lift quotient (direct encoding; see lift_sat.cpp), for tests and benchmarks.
std::string lift_cnf(const LiftProblem& lift, std::uint64_t* variables = nullptr, std::uint64_t* clauses = nullptr);

}  // namespace tilekit
