#pragma once
// A fill request (solver/fill_search.hpp) as CNF, solved by the SAT solver CaDiCaL
// (solver/sat_cnf.hpp): `tilekit fill --sat`, and `--cnf F` writes the same CNF for any solver.
// It decides a whole map in one run, so an UNSAT answer refutes every map of the request; the
// blob sheet's minimality (docs/guide/fill.md) is settled this way.
//
// The direct encoding of the CSP (Walsh 2000, "SAT v CSP"), its adjacency through the edges'
// colours as Wang tiles have them (generalised to any rules):
//   variable 1 + c * T + t: cell c (row-major) holds tile t (T tiles);
//   each cell exactly one tile (one clause, and at most one: solver/sat_cnf.hpp's encoding);
//   each boundary between a cell and its east (south) neighbour exactly one class k, the classes
//     being the distinct sets S_k = allowed(t, east) (for a Wang set: the edge colours);
//     x(c,t) -> y(k of t); x(east of c, u) -> some y(k) with u in S_k. So the tile beyond the
//     boundary is one allowed beside t, for any rules, with two-literal clauses for Wang sets;
//   fixed cells as unit clauses; with `cover`, each tile in some cell, and on a torus without
//     fixed cells tile 0 at cell 0 (every sheet has a translate so: fill_map()'s rule).
// The map a model decodes to is checked by the caller's validator, as every fill is.
#include <cstdint>
#include <string>

#include "solver/fill_search.hpp"
#include "solver/sat_cnf.hpp"

namespace tilekit {

// The most cells x tiles^2 a CNF may take (about the support clauses' literals): 2^28.
inline constexpr std::uint64_t kMaxFillCnfWork = std::uint64_t(1) << 28;

// The CNF of `req` (rules, size, torus, fixed, cover). RequestError for a request too large for it.
CnfBuilder fill_cnf(const FillMapRequest& req);

// DIMACS text of fill_cnf(req) with comment lines that say what the variables mean.
std::string fill_cnf_text(const FillMapRequest& req, std::uint64_t* variables = nullptr,
                          std::uint64_t* clauses = nullptr);

// One cadical run over fill_cnf(req) with the run's seed, time limit and signals. found: the map;
// UNSAT: proved_impossible with the whole map as the window; neither: timed_out or interrupted.
FillMapOutcome fill_by_sat(const FillMapRequest& req);

}  // namespace tilekit
