#pragma once
// CNF plumbing shared by the SAT encodings (imposed groups: impose_sat.*, colour lifts:
// colour_lift_sat.cpp, window tori: window_sat.cpp): a DIMACS clause builder with the cardinality
// encodings they use, a runner for the external SAT solver CaDiCaL (Debian package `cadical`,
// installed by scripts/setup.sh) that a time limit or a stop request (signals) ends by killing the
// solver process, and one run of it as a search of the engine (solve_by_sat).
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include "solver/problem.hpp"

namespace tilekit {

class CnfBuilder {
 public:
  int new_var() { return next_var_++; }
  int new_vars(int n) {  // the first of n consecutive variables
    const int first = next_var_;
    next_var_ += n;
    return first;
  }
  void clause(std::initializer_list<int> lits);
  void clause(const std::vector<int>& lits);
  // At most one of lits: pairwise up to 6 literals, else the sequential counter (Sinz 2005,
  // 3n clauses and n - 1 auxiliary variables).
  void at_most_one(const std::vector<int>& lits);
  void exactly_one(const std::vector<int>& lits) {
    clause(lits);
    at_most_one(lits);
  }
  std::uint64_t variables() const { return std::uint64_t(next_var_ - 1); }
  std::uint64_t clauses() const { return clauses_; }
  std::string dimacs() const;  // "p cnf V C" header and the clauses

 private:
  int next_var_ = 1;
  std::uint64_t clauses_ = 0;
  std::string text_;
};

struct SatRun {
  enum class Status { Satisfiable, Unsatisfiable, Unknown } status = Status::Unknown;
  std::vector<char> value;  // value[v] for variables 1..V when satisfiable (value[0] unused)
  bool stopped = false;     // ended by the stop request (not by the solver or its time limit)
  double seconds = 0;
  std::string command;      // the solver command line
};

// Whether `cadical` is on PATH.
bool sat_solver_available();

// Runs cadical on the CNF (a temporary file, removed afterwards) with `seed`, a time limit in
// seconds (0 = none) and `stop` polled every 20 ms (may be empty). Throws InputError when cadical
// is missing or cannot be started.
SatRun run_cadical(const CnfBuilder& cnf, double time_limit, std::uint64_t seed, const std::function<bool()>& stop);

// What the messages of solve_by_sat call its results.
struct SatNames {
  const char* finds;     // "sat finds one FINDS" (packing, torus)
  const char* cnf;       // the encoding: "the CNF CNF produced ..." (lift, window)
  const char* produced;  // what the decoded assignment is (tiling, torus)
  const char* invalid;   // the validator's complaint when it names none (not a packing, ...)
};

// One cadical run as a search of the engine: --mode first, one job, resumable by its identity
// only (a checkpoint holds the fingerprint and the time spent; a resume starts cadical again).
// `build` makes the CNF (timed with the run, so within the time limit); `decode` turns a
// satisfying assignment into the tiling, which the independent validator must accept as a
// packing of `problem`.
SearchResult solve_by_sat(const TilingProblem& problem, const SearchOptions& o, const std::string& fingerprint,
                          const SatNames& names, const std::function<const CnfBuilder&()>& build,
                          const std::function<Tiling(const std::vector<char>&)>& decode);

}  // namespace tilekit
