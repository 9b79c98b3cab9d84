#pragma once
// De Bruijn tori and window lift quotients as CNF for cadical (window_sat.cpp describes the
// encoding): `pack --kind window --formulation sat`, first mode only.
#include <cstdint>
#include <string>

#include "solver/problem.hpp"
#include "solver/window_lift.hpp"
#include "solver/window_model.hpp"

namespace tilekit {

// The most window variables (cells x windows per class) a CNF may have: 2^23, about 75 M clauses
// for 3x3 windows. The (512,512;3,3)_4 lift quotient needs 2^27 and is refused (InputError).
inline constexpr std::uint64_t kMaxWindowCnfIndicators = std::uint64_t(1) << 23;

// Solves `problem` (or, with `lift`, its lift quotient, then lifts) with cadical and validates
// the torus found. Called by solve() for window problems with formulation "sat".
// With ties (an imposed group, the row-difference lift), only tori that keep them: each tied
// symbol's value literals are equivalent to its orbit's first symbol's.
SearchResult solve_window_sat(const TilingProblem& problem, const WindowLiftProblem* lift, const SymbolTies& ties,
                              const SearchOptions& options, const std::string& fingerprint);

// The CNF of a window problem whose classes are residues mod (period_rows, period_cols) (0: the
// whole torus is one class), for tests and benchmarks.
std::string window_cnf(const TilingProblem& quotient, int period_rows, int period_cols,
                       std::uint64_t* variables = nullptr, std::uint64_t* clauses = nullptr);

}  // namespace tilekit
