#include "solver/impose_solve.hpp"

#include <fmt/format.h>

#include <chrono>
#include <iostream>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "solver/impose_model.hpp"
#include "solver/impose_sat.hpp"
#include "solver/impose_search.hpp"
#include "solver/luby.hpp"
#include "base/error.hpp"
#include "tilesets/validator.hpp"

namespace tilekit {
namespace {

using Clock = std::chrono::steady_clock;

// Every solution leaves through here: the independent validator and the invariance check.
Tiling checked(const SymmetricModel& model, const ImposedGroup& group, const TileSet& set,
               const std::vector<int>& values) {
  Tiling t = model.to_tiling(values);
  ValidationReport rep = validate(t, &set);
  if (!rep.valid || (model.packing && !rep.packing))
    throw std::logic_error("symmetric search produced a tiling the validator rejects: " +
                           (rep.errors.empty() ? std::string("not a packing") : rep.errors.front()));
  if (!group.is_invariant(t)) throw std::logic_error("symmetric search produced a tiling that is not invariant");
  return t;
}

}  // namespace

ImposedGroup build_group(const TilingProblem& problem, const std::string& spec) {
  return ImposedGroup::build(parse_group_spec(spec), problem.set.kind(), problem.set.horizontal_radix(),
                             problem.set.vertical_radix(), problem.rows, problem.cols, problem.packing);
}

SymmetricResult solve_symmetric(TileKind kind, std::uint32_t colours, const std::string& spec,
                                const SearchOptions& options, const SymmetricControl& control) {
  TilingProblem p = complete_packing_problem(kind, colours);
  return solve_symmetric(p, build_group(p, spec), options, control);
}

SymmetricResult solve_symmetric(const TilingProblem& problem, const ImposedGroup& group, const SearchOptions& options,
                                const SymmetricControl& control) {
  if (options.threads < 1) throw InputError("--threads must be at least 1");
  if (options.time_limit < 0) throw InputError("--time-limit must not be negative");
  const auto t0 = Clock::now();
  const SymmetricModel model = SymmetricModel::build(problem, group);
  const auto deadline = options.time_limit > 0
                            ? t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(options.time_limit))
                            : Clock::time_point::max();
  SymmetricResult out;
  out.group = group.to_json();
  out.sites = model.num_sites;
  SearchResult& res = out.result;
  res.formulation = problem.set.kind() == TileKind::Corner ? "pegs" : "edges";
  res.threads = options.mode == SearchMode::First ? options.threads : 1;

  if (options.mode != SearchMode::First) {
    // Exhaustive enumeration of the fundamental domain: one G-invariant solution per leaf.
    SymmetricSearchConfig cfg;
    cfg.random_values = false;
    cfg.most_constrained = control.most_constrained;
    cfg.pattern_sizes = control.pattern_sizes;
    SymmetricSearch search(model, cfg);
    std::function<void(const std::vector<int>&)> each = [&](const std::vector<int>& values) {
      if (options.mode == SearchMode::All || options.on_solution) {
        Tiling t = checked(model, group, problem.set, values);
        if (options.on_solution) options.on_solution(t);
      }
    };
    auto outcome = search.run(0, control.stop, deadline, each);
    res.complete = outcome == SymmetricSearch::Outcome::Exhausted;
    res.solutions = search.solutions();
    res.nodes = search.nodes();
    res.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    return out;
  }

  if (control.sat) {
    // The same subspace as CNF for cadical (impose_sat.hpp); one solver process.
    double limit = options.time_limit > 0 ? options.time_limit : 1e6;
    SatOutcome sat = solve_symmetric_sat(model, limit, options.seed);
    res.formulation = "sat-" + res.formulation;
    res.threads = 1;
    if (sat.status == SatOutcome::Status::Satisfiable) {
      res.found.push_back(checked(model, group, problem.set, sat.values));
      res.solutions = 1;
      if (options.on_solution) options.on_solution(res.found.back());
    }
    res.complete = sat.status == SatOutcome::Status::Unsatisfiable;
    res.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    return out;
  }

  // First mode: independent seeded restarting searches, first found wins.
  std::atomic<bool> found{false};
  std::atomic<std::uint64_t> nodes{0}, restarts{0};
  std::mutex mu;
  std::vector<int> winner;
  bool exhausted = false;
  const std::uint64_t unit = control.luby_unit ? control.luby_unit : std::uint64_t(50) * std::uint64_t(model.num_sites) + 1000;
  auto worker = [&](int tid) {
    SymmetricSearchConfig cfg;
    cfg.seed = options.seed * 1000003ULL + std::uint64_t(tid);
    cfg.most_constrained = control.most_constrained;
    cfg.pattern_sizes = control.pattern_sizes;
    SymmetricSearch search(model, cfg);
    // Polls `found`; the external stop flag is folded into it by the monitor below.
    std::uint64_t last_nodes = 0;
    for (std::uint64_t i = 1;; ++i) {
      std::uint64_t limit = control.restarts ? unit * luby(i) : 0;
      auto outcome = search.run(limit, &found, deadline);
      nodes += search.nodes() - last_nodes;
      last_nodes = search.nodes();
      if (outcome == SymmetricSearch::Outcome::Solution) {
        std::lock_guard<std::mutex> lock(mu);
        if (!found.exchange(true)) winner = search.values();
        return;
      }
      if (outcome == SymmetricSearch::Outcome::Exhausted) {
        std::lock_guard<std::mutex> lock(mu);
        exhausted = true;  // the whole subspace holds no solution
        found = true;      // stop the others
        return;
      }
      if (outcome == SymmetricSearch::Outcome::Stopped) return;
      ++restarts;
    }
  };
  std::vector<std::thread> pool;
  for (int tid = 0; tid < options.threads; ++tid) pool.emplace_back(worker, tid);
  // Monitor: external stop, progress lines.
  auto last_report = Clock::now();
  for (;;) {
    {
      std::lock_guard<std::mutex> lock(mu);
      if (found.load()) break;
    }
    if (control.stop && control.stop->load()) {
      found = true;
      break;
    }
    if (Clock::now() >= deadline) break;
    if (options.progress && Clock::now() - last_report > std::chrono::seconds(5)) {
      last_report = Clock::now();
      std::cerr << fmt::format("impose {}: {:.0f} s, {} nodes, {} restarts\n", group.spec_text(),
                               std::chrono::duration<double>(last_report - t0).count(), nodes.load(), restarts.load());
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  for (auto& th : pool) th.join();
  res.nodes = nodes.load();
  out.restarts = restarts.load();
  if (!winner.empty()) {
    res.found.push_back(checked(model, group, problem.set, winner));
    res.solutions = 1;
    if (options.on_solution) options.on_solution(res.found.back());
  }
  res.complete = exhausted && winner.empty();
  res.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return out;
}

}  // namespace tilekit
