#include "solver/impose_sat.hpp"

#include <algorithm>
#include <unordered_map>

#include "solver/sat_cnf.hpp"

namespace tilekit {

namespace {

void build_symmetric_cnf(const FundamentalDomain& m, CnfBuilder& cnf) {
  std::vector<int> first_var(std::size_t(m.num_sites));
  for (int s = 0; s < m.num_sites; ++s) first_var[std::size_t(s)] = cnf.new_vars(int(m.site_colours[std::size_t(s)]));
  auto x = [&](int s, int v) { return first_var[std::size_t(s)] + v; };
  for (int s = 0; s < m.num_sites; ++s) {
    std::vector<int> lits;
    for (int v = 0; v < int(m.site_colours[std::size_t(s)]); ++v) lits.push_back(x(s, v));
    cnf.exactly_one(lits);
  }
  std::unordered_map<std::uint64_t, int> w;  // (cell, orbit) -> variable
  std::vector<std::vector<int>> per_orbit(std::size_t(m.num_orbits));
  for (std::size_t c = 0; c < m.cells.size(); ++c) {
    const auto& slots = m.cells[c];
    std::vector<int> sites;
    for (const auto& sl : slots)
      if (std::find(sites.begin(), sites.end(), sl.site) == sites.end()) sites.push_back(sl.site);
    std::vector<int> val(sites.size(), 0);
    for (;;) {
      std::uint32_t idx = 0;
      for (const auto& sl : slots) {
        int v = val[std::size_t(std::find(sites.begin(), sites.end(), sl.site) - sites.begin())];
        idx += sl.weight * m.perm_tables[std::size_t(sl.perm)][std::size_t(v)];
      }
      std::vector<int> lits;
      for (std::size_t k = 0; k < sites.size(); ++k) lits.push_back(-x(sites[k], val[k]));
      int orbit = m.orbit_of[idx];
      if (orbit >= 0 && m.packing) {
        auto key = std::uint64_t(c) * std::uint64_t(m.num_orbits) + std::uint64_t(orbit);
        auto [it, fresh] = w.try_emplace(key, 0);
        if (fresh) {
          it->second = cnf.new_var();
          per_orbit[std::size_t(orbit)].push_back(it->second);
        }
        lits.push_back(it->second);
        cnf.clause(lits);
      } else if (orbit < 0) {
        cnf.clause(lits);  // this window is not a tile of the set
      }
      std::size_t k = 0;
      while (k < sites.size() && ++val[k] == int(m.site_colours[std::size_t(sites[k])])) val[k++] = 0;
      if (k == sites.size()) break;
    }
  }
  if (m.packing) {
    // Each orbit on at most one cell, and (redundant, for propagation) on at least one; each
    // cell shows exactly one orbit, so w[cell][.] is exactly the cell's window orbit.
    for (const auto& lits : per_orbit) {
      cnf.at_most_one(lits);
      cnf.clause(lits);
    }
    std::vector<std::vector<int>> per_cell(m.cells.size());
    for (const auto& [key, var] : w) per_cell[std::size_t(key / std::uint64_t(m.num_orbits))].push_back(var);
    for (auto& lits : per_cell) {
      std::sort(lits.begin(), lits.end());
      cnf.at_most_one(lits);
    }
  }
}

}  // namespace

std::string symmetric_cnf(const FundamentalDomain& m, std::uint64_t* variables, std::uint64_t* clauses) {
  CnfBuilder cnf;
  build_symmetric_cnf(m, cnf);
  if (variables) *variables = cnf.variables();
  if (clauses) *clauses = cnf.clauses();
  return cnf.dimacs();
}

SatOutcome solve_symmetric_sat(const FundamentalDomain& model, double time_limit, std::uint64_t seed,
                               const std::function<bool()>& stop) {
  CnfBuilder cnf;
  build_symmetric_cnf(model, cnf);
  SatRun run = run_cadical(cnf, std::max(1.0, time_limit), seed, stop);
  SatOutcome out;
  out.variables = cnf.variables();
  out.clauses = cnf.clauses();
  out.solver = run.command;
  out.seconds = run.seconds;
  out.status = run.status == SatRun::Status::Satisfiable     ? SatOutcome::Status::Satisfiable
               : run.status == SatRun::Status::Unsatisfiable ? SatOutcome::Status::Unsatisfiable
                                                             : SatOutcome::Status::Unknown;
  if (out.status == SatOutcome::Status::Satisfiable) {
    out.values.assign(std::size_t(model.num_sites), -1);
    int var = 1;  // the site variables come first, one block of colours per site
    for (int s = 0; s < model.num_sites; ++s)
      for (std::uint32_t v = 0; v < model.site_colours[std::size_t(s)]; ++v, ++var)
        if (run.value[std::size_t(var)]) out.values[std::size_t(s)] = int(v);
  }
  return out;
}

}  // namespace tilekit
