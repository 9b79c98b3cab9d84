#include "solver/fill_sat.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <vector>

#include "base/error.hpp"
#include "base/run_control.hpp"
#include "base/signals.hpp"

namespace tilekit {

namespace {

// The cell beside `c` in direction d (0 N, 1 E, 2 S, 3 W), or -1 past a border of a bounded map.
int neighbour(const FillMapRequest& req, int c, int d) {
  static constexpr int dr[4] = {-1, 0, 1, 0}, dc[4] = {0, 1, 0, -1};
  int r = c / req.cols + dr[d], k = c % req.cols + dc[d];
  if (!req.torus && (r < 0 || r >= req.rows || k < 0 || k >= req.cols)) return -1;
  r = (r + req.rows) % req.rows;
  k = (k + req.cols) % req.cols;
  return r * req.cols + k;
}

void check_request(const FillMapRequest& req) {
  if (!req.rules) throw InputError("a fill needs a tile set");
  if (req.rows < 1 || req.cols < 1) throw RequestError("size", "`size` must be at least 1x1");
  const std::uint64_t n = std::uint64_t(req.rows) * std::uint64_t(req.cols), T = std::uint64_t(req.rules->tiles());
  if (n * T * T > kMaxFillCnfWork || n * T >= (std::uint64_t(1) << 30))
    throw RequestError(
        "sat", fmt::format("`sat`: a {}x{} map of {} tiles is too large a CNF (cells x tiles^2 above 2^28)", req.cols,
                           req.rows, T));
  if (!req.fixed.empty() && req.fixed.size() != n) throw InputError("the fixed cells do not match the map's size");
  for (int f : req.fixed)
    if (f < -1 || f >= int(T)) throw InputError(fmt::format("fixed tile {} is not in the set", f));
}

}  // namespace

CnfBuilder fill_cnf(const FillMapRequest& req) {
  check_request(req);
  const FillRules& rules = *req.rules;
  const int n = req.rows * req.cols, T = rules.tiles();
  CnfBuilder cnf;
  const int first = cnf.new_vars(n * T);
  auto x = [&](int c, int t) { return first + c * T + t; };
  std::vector<int> lits;
  for (int c = 0; c < n; ++c) {
    lits.clear();
    for (int t = 0; t < T; ++t) lits.push_back(x(c, t));
    cnf.exactly_one(lits);
  }
  // Each boundary between a cell and its east (d = 1) or south (d = 2) neighbour carries one class
  // of tiles allowed beyond it: the classes are the distinct sets allowed(t, d).
  for (int d : {1, 2}) {
    std::vector<std::vector<std::uint64_t>> classes;  // the distinct masks
    std::vector<int> class_of(std::size_t(T), -1);
    for (int t = 0; t < T; ++t) {
      std::vector<std::uint64_t> m(rules.mask(t, d), rules.mask(t, d) + rules.words());
      auto it = std::find(classes.begin(), classes.end(), m);
      class_of[std::size_t(t)] = int(it - classes.begin());
      if (it == classes.end()) classes.push_back(std::move(m));
    }
    const int K = int(classes.size());
    for (int c = 0; c < n; ++c) {
      const int nb = neighbour(req, c, d);
      if (nb < 0) continue;
      const int y = cnf.new_vars(K);
      lits.clear();
      for (int k = 0; k < K; ++k) lits.push_back(y + k);
      cnf.exactly_one(lits);
      for (int t = 0; t < T; ++t) cnf.clause({-x(c, t), y + class_of[std::size_t(t)]});
      for (int u = 0; u < T; ++u) {
        lits.assign(1, -x(nb, u));
        for (int k = 0; k < K; ++k)
          if ((classes[std::size_t(k)][std::size_t(u) >> 6] >> (u & 63)) & 1u) lits.push_back(y + k);
        cnf.clause(lits);
      }
    }
  }
  for (int c = 0; c < int(req.fixed.size()); ++c)
    if (req.fixed[std::size_t(c)] >= 0) cnf.clause({x(c, req.fixed[std::size_t(c)])});
  if (req.cover) {
    for (int t = 0; t < T; ++t) {
      lits.clear();
      for (int c = 0; c < n; ++c) lits.push_back(x(c, t));
      cnf.clause(lits);
    }
    if (req.torus && req.fixed.empty()) cnf.clause({x(0, 0)});
  }
  return cnf;
}

std::string fill_cnf_text(const FillMapRequest& req, std::uint64_t* variables, std::uint64_t* clauses) {
  const CnfBuilder cnf = fill_cnf(req);
  if (variables) *variables = cnf.variables();
  if (clauses) *clauses = cnf.clauses();
  const int T = req.rules->tiles();
  return fmt::format(
             "c tilekit fill: a {}x{} map{}, {} tiles{}{}\n"
             "c variable 1 + cell * {} + tile: the cell (row-major, cell = row * {} + column) holds the tile;\n"
             "c the variables above {} are the boundaries' classes and the at-most-one encoding's\n",
             req.cols, req.rows, req.torus ? " on a torus" : "", T, req.cover ? ", every tile at least once" : "",
             req.cover && req.torus && req.fixed.empty() ? " (tile 0 at cell 0)" : "", T, req.cols,
             std::uint64_t(req.rows) * std::uint64_t(req.cols) * std::uint64_t(T)) +
         cnf.dimacs();
}

FillMapOutcome fill_by_sat(const FillMapRequest& req) {
  const auto t0 = std::chrono::steady_clock::now();
  const CnfBuilder cnf = fill_cnf(req);
  const Deadline deadline(req.run.time_limit, t0);
  StopToken token;
  auto stop = [&] { return req.run.cancelled() || poll_stop(token, deadline, req.run.catch_signals); };
  const SatRun run =
      run_cadical(cnf, deadline.limited() ? std::max(1.0, deadline.seconds_left()) : 0, req.run.seed, stop);
  FillMapOutcome out;
  const int n = req.rows * req.cols, T = req.rules->tiles();
  out.blocks = 1;
  out.window = {0, 0, req.rows, req.cols};
  if (run.status == SatRun::Status::Satisfiable) {
    out.found = true;
    out.map.assign(std::size_t(n), -1);
    for (int c = 0; c < n; ++c)
      for (int t = 0; t < T; ++t)
        if (run.value[std::size_t(1 + c * T + t)]) {
          if (out.map[std::size_t(c)] >= 0) throw std::logic_error("cadical's model puts two tiles in one cell");
          out.map[std::size_t(c)] = t;
        }
    for (int t : out.map)
      if (t < 0) throw std::logic_error("cadical's model leaves a cell empty");
  } else if (run.status == SatRun::Status::Unsatisfiable) {
    out.proved_impossible = true;
    if (!req.fixed.empty()) out.map = req.fixed;
  } else {
    out.signal = req.run.catch_signals ? SignalCatcher::caught() : 0;
    out.interrupted = run.stopped && out.signal != 0;
    out.timed_out = !out.interrupted;
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace tilekit
