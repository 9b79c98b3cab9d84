#pragma once
// The same fundamental-domain subspace as ImposeModel, encoded as CNF and solved by the
// external SAT solver CaDiCaL (Debian package `cadical`, installed by scripts/setup.sh). The
// portfolio runs it as candidate "sat:SPEC" beside "SPEC" and its statistics keep whichever
// wins per problem: the CNF with clause learning beats plain DFS on some subspaces, DFS on
// others.
//
// Encoding (direct encoding of a CSP): x[s][v] "site s has colour v", exactly one per site;
// for every representative cell and every tile t whose orbit o is usable, the conjunction of
// the four slot literals that spell t implies w[cell][o]; a tile outside the set is forbidden
// by a clause; for a packing each orbit has at most one cell with w[cell][o] (sequential
// counter, Sinz 2005) and at least one; each cell has at most one w, so w[cell][.] is exactly
// the window's orbit and the "at least one" clauses are sound (they add pigeonhole propagation).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "solver/impose_domain.hpp"
#include "solver/sat_cnf.hpp"  // sat_solver_available()

namespace tilekit {

struct SatOutcome {
  enum class Status { Satisfiable, Unsatisfiable, Unknown } status = Status::Unknown;
  std::vector<int> values;  // site values when satisfiable
  std::uint64_t variables = 0, clauses = 0;
  double seconds = 0;
  std::string solver;  // the command line used
};

// The CNF in DIMACS text.
std::string symmetric_cnf(const FundamentalDomain& model, std::uint64_t* variables = nullptr,
                          std::uint64_t* clauses = nullptr);

// Writes the CNF to a temporary file, runs cadical with a time limit (seconds, >= 1) and seed,
// and decodes the model. `stop` (may be empty) is polled every 10 ms and ends the solver early
// (status Unknown). Throws InputError when cadical is missing.
SatOutcome solve_symmetric_sat(const FundamentalDomain& model, double time_limit, std::uint64_t seed,
                               const std::function<bool()>& stop = {});

}  // namespace tilekit
