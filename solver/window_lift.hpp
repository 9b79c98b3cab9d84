#pragma once
// Colour-quotient lifts of window tori as a subspace the one engine searches (the theorem is in
// tilesets/window_torus.hpp): a de Bruijn torus over C = k*m symbols is sought as
// A(i,j) = B(i mod R_B, j mod S_B) + m*E(i,j), B a known (R_B,S_B;K,L)_m torus, so the search runs
// over E (k symbols, R x S) with "every k-window once per residue class mod (R_B, S_B)"
// (WindowModel's class periods) and lifts every leaf, which the validator then checks.
//
// SPEC (`pack --kind window --lift SPEC`): "M" or "m=M,base=FILE" (solver/colour_lift_model.hpp);
// without base= the base is a stored or constructed torus over M symbols with the same windows
// whose sides divide the torus's (tilesets/window_torus.hpp, construct_window_torus()).
//
// SPEC "rows=FILE" is the row-difference lift instead (solver/window_model.hpp,
// row_difference_ties()): B(i+1,j) - B(i,j) = A(i mod r, j mod s) with A the (K-1) x L torus in
// FILE over the same C symbols; the search decides B's top row.
#include <cstdint>
#include <memory>
#include <string>
#include <utility>

#include "solver/colour_lift_model.hpp"
#include "solver/problem.hpp"
#include "solver/window_model.hpp"
#include "tilesets/window_torus.hpp"

namespace tilekit {

struct WindowLiftProblem {
  bool row_difference = false;  // "rows=FILE": the row-difference lift (then spec.base_file is A)
  LiftSpec spec;
  Tiling base;           // B: a de Bruijn torus over m symbols (checked by the validator)
  std::string base_how;  // where B came from
  std::uint32_t colours = 0, quotient_colours = 0;  // C and k
  TilingProblem quotient;  // every k-window, R x S torus, packed per residue class mod B's sides
};

// Throws InputError when C is not k*m with k >= 2, no base torus fits or the base file is not one.
WindowLiftProblem make_window_lift_problem(const TilingProblem& problem, const std::string& spec);

// The ties of the row-difference lift (empty for a colour lift).
SymbolTies window_lift_ties(const TilingProblem& problem, const WindowLiftProblem& lift);

// The colour lift's quotient model whose leaves are lifted (the row-difference lift needs no
// wrapper: it is WindowModel with window_lift_ties()).
class WindowLiftModel {
 public:
  explicit WindowLiftModel(const WindowLiftProblem& p)
      : e_(p.quotient, p.base.rows, p.base.cols), base_(std::make_shared<const Tiling>(p.base)) {}
  int branch(std::vector<int>& values) { return e_.branch(values); }
  bool assign(int var, int value) { return e_.assign(var, value); }
  void unassign(int var, int value) { e_.unassign(var, value); }
  void set_value_seed(std::uint64_t seed) { e_.set_value_seed(seed); }
  Tiling tiling() const { return window_colour_lift(*base_, e_.tiling()); }  // A = B + m*E
  std::uint64_t multiplicity() const { return e_.multiplicity(); }
  ModelStats& stats() { return e_.stats(); }
  std::pair<int, int> translation_steps() const { return e_.translation_steps(); }

 private:
  WindowModel e_;
  std::shared_ptr<const Tiling> base_;
};

static_assert(SearchModel<WindowLiftModel>);

}  // namespace tilekit
