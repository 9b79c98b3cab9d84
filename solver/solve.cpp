// solve(): checks a problem and its options, picks a model (formulation; the fundamental
// domain under an imposed group) and runs the one parallel engine on it; counts solutions and
// orbits, emits validated solutions (and, under a group, checks them invariant).
#include "solver/solve.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>

#include "base/error.hpp"
#include "base/hash.hpp"
#include "base/parallel.hpp"
#include "base/parse.hpp"
#include "solver/cell_model.hpp"
#include "solver/impose_domain.hpp"
#include "solver/impose_model.hpp"
#include "solver/impose_sat.hpp"
#include "solver/lattice_model.hpp"
#include "solver/colour_lift_model.hpp"
#include "solver/parallel_search.hpp"
#include "solver/symmetry.hpp"
#include "solver/window_lift.hpp"
#include "solver/window_model.hpp"
#include "solver/window_sat.hpp"
#include "tilesets/validator.hpp"
#include "tilesets/window_torus.hpp"

namespace tilekit {

namespace {

// Luby unit under a group: nodes per site of the fundamental domain, plus a floor.
constexpr std::uint64_t kRestartPerSite = 50, kRestartFloor = 1000;

struct Route;

struct Plan {
  const Route* route = nullptr;  // the model that runs (kRoutes)
  std::string formulation;       // its name (route->name), in results and fingerprints
  std::string ordering;
  bool restarts = false;
  std::uint64_t restart_base = 0;
  std::size_t subproblems = 0;
  std::optional<ImposedGroup> group;  // options.impose
  std::optional<FundamentalDomain> domain;
  std::shared_ptr<const LiftProblem> lift;  // options.lift: the subspace searched
  bool window = false;                      // a de Bruijn torus (window set)
  std::shared_ptr<const WindowLiftProblem> window_lift;  // a window torus with options.lift
  std::chrono::steady_clock::time_point started;         // when solve() began (the setup phase)
};

// ---- the routes: which model runs a search ------------------------------------------------
// A search walks a subspace (all of it, the invariants of an imposed group, a colour-quotient
// lift, or a window torus, which has subspaces of its own) in a formulation; each pair that
// runs is one row of kRoutes, as the portfolio's candidate families are rows of its kFamilies.
// To add a model, write its runner and add a row.
enum class Subspace { Whole, Imposed, Lift, Window };

using RouteRun = SearchResult (*)(const TilingProblem&, const SearchOptions&, Plan&);

struct Route {
  Subspace subspace;
  Formulation formulation;
  std::optional<TileKind> kind;  // the tile kind it needs (none: any)
  const char* name;              // SearchResult::formulation and the fingerprint's
  RouteRun run;
};

SearchResult run_cell(const TilingProblem&, const SearchOptions&, Plan&);
SearchResult run_lattice(const TilingProblem&, const SearchOptions&, Plan&);
SearchResult run_imposed(const TilingProblem&, const SearchOptions&, Plan&);
SearchResult run_sat(const TilingProblem&, const SearchOptions&, Plan&);
SearchResult run_lift(const TilingProblem&, const SearchOptions&, Plan&);
SearchResult run_lift_cell(const TilingProblem&, const SearchOptions&, Plan&);
SearchResult run_lift_sat(const TilingProblem&, const SearchOptions&, Plan&);
SearchResult run_window(const TilingProblem&, const SearchOptions&, Plan&);
SearchResult run_window_sat(const TilingProblem&, const SearchOptions&, Plan&);

constexpr Route kRoutes[] = {
    {Subspace::Whole, Formulation::Cell, std::nullopt, "cell", run_cell},
    {Subspace::Whole, Formulation::Pegs, TileKind::Corner, "pegs", run_lattice},
    {Subspace::Whole, Formulation::Edges, TileKind::Wang, "edges", run_lattice},
    {Subspace::Imposed, Formulation::Pegs, TileKind::Corner, "pegs", run_imposed},
    {Subspace::Imposed, Formulation::Edges, TileKind::Wang, "edges", run_imposed},
    {Subspace::Imposed, Formulation::Sat, std::nullopt, "sat", run_sat},
    {Subspace::Lift, Formulation::Pegs, std::nullopt, "lift", run_lift},  // the lift's pegs or edges
    {Subspace::Lift, Formulation::Edges, std::nullopt, "lift", run_lift},
    {Subspace::Lift, Formulation::Cell, std::nullopt, "lift-cell", run_lift_cell},
    {Subspace::Lift, Formulation::Sat, std::nullopt, "sat", run_lift_sat},
    {Subspace::Window, Formulation::Pegs, std::nullopt, "pegs", run_window},  // a symbol per peg
    {Subspace::Window, Formulation::Sat, std::nullopt, "sat", run_window_sat},
};

// The formulation `auto` stands for.
Formulation auto_formulation(Subspace s, TileKind kind) {
  switch (s) {
    // Measured (BENCHMARKS.md, bench_solver): the tile-per-cell model is fastest on every packing
    // problem we timed (C=2 counts, C=3 first packings); pegs/edges only win on counts of
    // unconstrained tilings, where most-constrained-first cell search is close and far more
    // robust on restrictive (e.g. aperiodic) sets.
    case Subspace::Whole:
      return Formulation::Cell;
    // Under a group the model is the fundamental domain of pegs (corner) or edges (Wang).
    case Subspace::Imposed:
      return kind == TileKind::Wang ? Formulation::Edges : Formulation::Pegs;
    case Subspace::Lift:
      return Formulation::Pegs;
    case Subspace::Window:
      return Formulation::Pegs;
  }
  return Formulation::Cell;
}

// The route of a subspace and formulation, or an InputError saying which formulations it takes.
const Route& pick_route(Subspace s, Formulation asked, TileKind kind) {
  const Formulation f = asked == Formulation::Auto ? auto_formulation(s, kind) : asked;
  for (const Route& r : kRoutes)
    if (r.subspace == s && r.formulation == f && (!r.kind || *r.kind == kind)) return r;
  if (s == Subspace::Window)
    throw RequestError("formulation", fmt::format("window tori are searched over their symbols (`formulation` pegs, "
                                                  "i.e. auto) or as CNF (sat), not '{}'",
                                                  formulation_name(asked)));
  if (s == Subspace::Imposed && f == Formulation::Cell)
    throw RequestError("impose",
                       "`impose` searches the pegs (corner) or edges (Wang) of a fundamental domain, not cells");
  if (f == Formulation::Sat)
    throw RequestError("formulation",
                       "the sat formulation encodes an imposed group's or a lift's subspace: give `impose` or `lift`");
  if (f == Formulation::Pegs) throw InputError("the pegs formulation is for corner tiles; use edges for Wang tiles");
  if (f == Formulation::Edges) throw InputError("the edges formulation is for Wang tiles; use pegs for corner tiles");
  throw std::logic_error(fmt::format("no route for formulation '{}'", formulation_name(asked)));
}

void use_route(Plan& pl, const Route& r) {
  pl.route = &r;
  pl.formulation = r.name;
}

// A model's leaf stands for its translates by multiples of these steps (rows, columns; lifts:
// the period).
template <SearchModel M>
std::pair<int, int> translation_steps(const M& m) {
  if constexpr (requires { m.translation_steps(); })
    return m.translation_steps();
  else if constexpr (requires { m.translation_step(); })
    return {m.translation_step(), m.translation_step()};
  else
    return {1, 1};
}

const char* mode_name(SearchMode m) {
  return m == SearchMode::First ? "first" : m == SearchMode::Count ? "count" : "all";
}

// Window tori (de Bruijn tori, tilesets/window_torus.hpp): the window model over the symbols
// (formulation pegs), optionally a lift quotient (options.lift), or the same as CNF (sat).
void plan_window(const TilingProblem& p, const SearchOptions& o, Plan& pl) {
  const TileSet& set = p.set;
  if (!p.packing || !p.torus) throw InputError("a window torus holds every window once: a packing of a torus");
  check_window_torus_shape(set.horizontal_radix(), set.window_rows(), set.window_cols(), p.rows, p.cols);
  pl.window = true;
  if (!o.impose.empty() && !o.lift.empty())
    throw RequestError("impose", "`impose` and `lift` are separate subspaces: give one of them");
  if (!o.impose.empty()) pl.group = build_group(p, o.impose);
  if (!o.lift.empty())
    pl.window_lift = std::make_shared<const WindowLiftProblem>(make_window_lift_problem(p, o.lift));
  use_route(pl, pick_route(Subspace::Window, o.formulation, set.kind()));
  if (pl.ordering == "auto") pl.ordering = pl.route->formulation == Formulation::Sat ? "cadical" : "static";
  if (pl.ordering != "static" && pl.ordering != "cadical")
    throw RequestError(
        "ordering",
        fmt::format("window tori are searched in scanline order (`ordering` static), not '{}'", o.ordering));
  pl.restarts = o.mode == SearchMode::First && o.restarts != 0;
  pl.restart_base = o.restart_base ? o.restart_base : 1000 * std::uint64_t(p.rows) * std::uint64_t(p.cols);
  pl.subproblems = o.subproblems ? o.subproblems : std::max<std::size_t>(1024, 64 * std::size_t(o.run.shard.count));
}

Plan plan(const TilingProblem& p, const SearchOptions& o) {
  const TileSet& set = p.set;
  if (set.empty()) throw InputError("the tile set is empty");
  if (p.rows < 1 || p.cols < 1)
    throw InputError(fmt::format("the grid must be at least 1x1, got {}x{}", p.rows, p.cols));
  if (std::int64_t(p.rows) * p.cols > 1 << 22)
    throw InputError(fmt::format("the grid {}x{} is too large (at most 4194304 cells)", p.rows, p.cols));
  if (p.packing && std::size_t(p.rows) * std::size_t(p.cols) != set.size())
    throw InputError(
        fmt::format("a packing of {} tiles needs rows*cols == {}, got {}x{}", set.size(), set.size(), p.rows, p.cols));
  checked_thread_count(o.run.threads);
  const ShardSpec& shard = o.run.shard;
  if (shard.count < 1 || shard.count > kMaxShards || shard.index < 0 || shard.index >= shard.count)
    throw RequestError("shard", fmt::format("`shard` must be I/N with 0 <= I < N <= {}, got {}/{}", kMaxShards,
                                            shard.index, shard.count));
  if (!std::isfinite(o.run.time_limit) || !std::isfinite(o.run.checkpoint_every))
    throw RequestError("time_limit", "`time_limit` and `checkpoint_every` must be finite numbers of seconds");
  if (o.run.time_limit < 0) throw InputError(fmt::format("time limit must be >= 0 seconds, got {}", o.run.time_limit));
  if (o.run.checkpoint_every < 0)
    throw InputError(fmt::format("checkpoint interval must be >= 0 seconds, got {}", o.run.checkpoint_every));
  if (!o.run.checkpoint_path.empty() && !o.save_checkpoint)
    throw InputError("checkpoint_path needs checkpoint I/O: use solve_checkpointed() (checkpoints/checkpoint.hpp)");
  if (!o.run.resume_path.empty() && !o.resume_state)
    throw InputError("resume_path needs checkpoint I/O: use solve_checkpointed() (checkpoints/checkpoint.hpp)");
  Plan pl;
  pl.ordering = o.ordering;
  if (set.kind() == TileKind::Window) {
    plan_window(p, o, pl);
    return pl;
  }
  if (!o.impose.empty()) {
    pl.group = build_group(p, o.impose);
    pl.domain = FundamentalDomain::build(p, *pl.group);
    use_route(pl, pick_route(Subspace::Imposed, o.formulation, set.kind()));
    if (pl.ordering == "auto") pl.ordering = "mrv";  // most constrained tight site first
    if (o.impose_patterns >= 16) throw InputError("impose_patterns is a mask of bits 1..3");
    if (pl.route->formulation == Formulation::Sat) {
      if (o.mode != SearchMode::First)
        throw RequestError("mode", "the sat formulation finds one packing: use it with `mode` first");
      if (o.run.shard.count != 1 || o.save_checkpoint || o.resume_state)
        throw RequestError("shard",
                           "the sat formulation runs cadical once: it keeps no checkpoint and takes no `shard`");
    }
    if (!o.lift.empty()) throw RequestError("impose", "`impose` and `lift` are separate subspaces: give one of them");
  } else if (!o.lift.empty()) {
    const bool complete = set.size() == complete_size(set.horizontal_radix(), set.vertical_radix()) &&
                          set.horizontal_radix() == set.vertical_radix() && p.torus && p.packing &&
                          p.rows == int(set.colours() * set.colours()) && p.cols == p.rows;
    if (!complete) throw RequestError("lift", "`lift` searches packings of the complete sets (`kind` and `colours`)");
    pl.lift =
        std::make_shared<const LiftProblem>(make_lift_problem(set.kind(), set.colours(), parse_lift_spec(o.lift)));
    use_route(pl, pick_route(Subspace::Lift, o.formulation, set.kind()));
  } else {
    use_route(pl, pick_route(Subspace::Whole, o.formulation, set.kind()));
  }
  // Static scanline order is cheapest per node for packings; most constrained first is
  // essential for tilings of bounded regions (culik-13 on a 20x20 square: 5 ms vs > 60 s).
  if (pl.ordering == "auto") pl.ordering = p.packing || pl.formulation != "cell" ? "static" : "mrv";
  if (pl.ordering != "static" && pl.ordering != "mrv")
    throw InputError(fmt::format("unknown ordering '{}' (static, mrv or auto)", o.ordering));
  if (pl.ordering == "mrv" && pl.formulation != "cell" && !pl.group && !pl.lift)
    throw RequestError("ordering", "the mrv ordering needs the cell formulation (or `impose`)");
  if (pl.lift) pl.ordering = pl.formulation == "sat" ? "cadical" : pl.formulation == "lift-cell" ? "mrv" : "static";
  pl.restarts = o.mode == SearchMode::First && (o.restarts < 0 ? p.packing : o.restarts > 0);
  // Nodes per Luby unit: under a group, proportional to the fundamental domain (measured on
  // C=5 corner, BENCHMARKS.md); otherwise to the grid.
  const std::uint64_t auto_base = pl.domain ? kRestartPerSite * std::uint64_t(pl.domain->num_sites) + kRestartFloor
                                            : 1000 * std::uint64_t(p.rows) * std::uint64_t(p.cols);
  pl.restart_base = o.restart_base ? o.restart_base : auto_base;
  // About 64 subproblems per shard, at most kMaxSplitSubproblems: a split into more would take
  // longer (and gigabytes more) than many whole searches, while shards beyond it simply get
  // fewer subproblems each (or none: an empty shard counts 0).
  pl.subproblems = o.subproblems ? o.subproblems
                                 : std::min<std::size_t>(kMaxSplitSubproblems,
                                                         std::max<std::size_t>(1024, 64 * std::size_t(o.run.shard.count)));
  return pl;
}

std::string fingerprint(const TilingProblem& p, const SearchOptions& o, const Plan& pl) {
  StableHash tiles;  // over the tile indices
  for (std::size_t k = 0; k < p.set.size(); ++k) tiles.add(p.set.index_of(k), 4);
  nlohmann::json j = {{"solver", 1},
                      {"kind", std::string(kind_name(p.set.kind()))},
                      {"radix", {p.set.horizontal_radix(), p.set.vertical_radix()}},
                      {"tiles", p.set.size()},
                      {"tiles_hash", fmt::format("{:016x}", tiles.fnv())},
                      {"rows", p.rows},
                      {"cols", p.cols},
                      {"torus", p.torus},
                      {"packing", p.packing},
                      {"mode", mode_name(o.mode)},
                      {"formulation", pl.formulation},
                      {"ordering", pl.ordering},
                      {"seed", o.run.seed},
                      {"restarts", pl.restarts},
                      {"subproblems", pl.subproblems},
                      {"shard", {o.run.shard.index, o.run.shard.count}}};
  if (pl.restarts) j["restart_base"] = pl.restart_base;
  if (pl.lift) {
    StableHash base;
    for (TileIndex t : pl.lift->base.cells) base.add(t, 4);
    j["lift"] = {{"spec", pl.lift->spec.text()}, {"base_hash", fmt::format("{:016x}", base.fnv())}};
  }
  if (pl.window) j["window"] = {p.set.window_rows(), p.set.window_cols()};
  if (pl.window_lift) {
    StableHash base;
    for (TileIndex t : pl.window_lift->base.cells) base.add(t, 4);
    j["lift"] = {{"spec", pl.window_lift->row_difference ? std::string("rows") : pl.window_lift->spec.text()},
                 {"base", {pl.window_lift->base.rows, pl.window_lift->base.cols}},
                 {"base_hash", fmt::format("{:016x}", base.fnv())}};
  }
  if (pl.group) {
    j["impose"] = pl.group->spec_text();
    j["patterns"] = o.impose_patterns;
  }
  return j.dump();
}

// Every solution leaves through here: the independent validator and, under a group, the
// invariance check. A failure is a solver bug, never bad input.
// A window torus is invariant under an imposed group when P(x + t) = pi(P(x)) for every
// generator, read on its symbols (the group acts on them as on the pegs of a corner torus).
bool window_torus_invariant(const Tiling& t, const ImposedGroup& g) {
  const std::vector<Colour> p = pegs_of_window_torus(t);
  for (const GroupElement& e : g.elements())
    for (int r = 0; r < t.rows; ++r)
      for (int c = 0; c < t.cols; ++c) {
        const std::size_t to = std::size_t((r + e.dr) % t.rows) * std::size_t(t.cols) + std::size_t((c + e.dc) % t.cols);
        if (p[to] != e.ph[p[std::size_t(r) * std::size_t(t.cols) + std::size_t(c)]]) return false;
      }
  return true;
}

void check_solution(const Tiling& t, const TilingProblem& p, const Plan& pl) {
  ValidationReport rep = validate(t, &p.set);
  if (!rep.valid || (p.packing && p.torus && !rep.packing))
    throw std::logic_error("the solver produced a solution the validator rejects: " +
                           (rep.errors.empty() ? std::string("not a packing") : rep.errors.front()));
  if (pl.window && pl.group && !window_torus_invariant(t, *pl.group))
    throw std::logic_error("the solver produced a window torus that is not invariant under the imposed group");
  if (!pl.window && pl.group && !pl.group->is_invariant(t))
    throw std::logic_error("the solver produced a solution that is not invariant under the imposed group");
}

SearchResult new_result(const TilingProblem& p, const SearchOptions& o, const Plan& pl) {
  SearchResult res;
  res.formulation = pl.formulation;
  res.ordering = pl.ordering;
  res.threads = o.run.threads;
  res.fingerprint = fingerprint(p, o, pl);
  if (pl.group) {
    res.group = pl.group->spec_text();
    res.group_order = pl.group->order();
    res.sites = pl.domain ? pl.domain->num_sites : p.rows * p.cols / int(pl.group->order());
  }
  return res;
}

template <SearchModel M>
SearchResult run_model(const M& root, const TilingProblem& p, const SearchOptions& o, const Plan& pl) {
  SearchResult res = new_result(p, o, pl);
  if (o.resume_state && o.resume_state->fingerprint != res.fingerprint)
    throw InputError("checkpoint does not match this search (different problem, mode, seed, formulation or shard)");

  std::optional<PackingSymmetry> sym;
  const bool translations = root.multiplicity() > 1;
  // Orbits are counted for whole-torus translations only. (Plain ints, not a structured binding:
  // clang 14, the fuzz and sanitizer compiler, cannot capture bindings in the lambdas below.)
  const std::pair<int, int> steps = translation_steps(root);
  const int step_r = steps.first, step_c = steps.second;
  if (o.mode != SearchMode::First && o.count_orbits && translations && step_r == 1 && step_c == 1)
    sym = PackingSymmetry::for_problem(p);
  if (sym) res.symmetry_order = sym->full_order();

  std::mutex emit_mu;
  auto emit = [&](const Tiling& t) {
    check_solution(t, p, pl);
    if (o.on_solution) o.on_solution(t);
  };
  auto leaf = [&](const M& m, SearchCounters& c) {
    assert(m.multiplicity() >= 1);
    c.solutions += m.multiplicity();
    if (o.mode == SearchMode::Count && !sym) return;
    Tiling t = m.tiling();
    if (sym && sym->is_canonical(t.cells)) ++c.orbits;
    if (o.mode == SearchMode::Count) return;
    std::lock_guard lock(emit_mu);
    if (o.mode == SearchMode::First) {
      emit(t);
      res.found.push_back(t);
    } else if (translations) {
      for (int r = 0; r < t.rows; r += step_r)
        for (int col = 0; col < t.cols; col += step_c) emit(translate(t, r, col));
    } else {
      emit(t);
    }
  };

  ParallelConfig cfg;
  cfg.mode = o.mode;
  cfg.run = o.run;
  cfg.title = o.title.empty() ? std::string("search") : o.title;
  cfg.restarts = pl.restarts;
  cfg.restart_base = pl.restart_base;
  cfg.subproblem_target = pl.subproblems;
  cfg.estimate_probes = o.estimate_probes;
  cfg.fingerprint = res.fingerprint;
  cfg.save = o.save_checkpoint;
  cfg.resume = o.resume_state ? &*o.resume_state : nullptr;
  cfg.flush = [&] {
    std::lock_guard lock(emit_mu);
    if (o.flush) o.flush();
  };
  M start = root;
  if (o.run.seed && !pl.restarts) start.set_value_seed(o.run.seed);
  ParallelSearch<M> search(start, cfg, leaf);
  const double setup_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - pl.started).count();
  ParallelOutcome out = search.run();
  res.stats = out.stats;
  res.stats.setup_seconds = setup_seconds;

  res.complete = out.complete;
  res.interrupted = out.interrupted;
  res.timed_out = out.timed_out;
  res.signal = out.signal;
  res.solutions = o.mode == SearchMode::First ? res.found.size() : out.counts.solutions;
  if (sym) res.orbits = out.counts.orbits;
  res.nodes = out.counts.nodes;
  res.seconds = out.seconds;
  res.total_seconds = out.total_seconds;
  res.subproblems = out.subproblems;
  res.shard_subproblems = out.shard_subproblems;
  res.subproblems_done = out.subproblems_done;
  res.restarts = out.restarts;
  res.estimated_nodes = out.estimate.nodes;
  res.estimated_log10_nodes = out.estimate.log10_nodes;
  res.estimated_probes = out.estimate.probes;
  res.checkpoints = out.checkpoints_written;
  return res;
}

// The imposed group's subspace as CNF, solved by cadical (impose_sat.hpp); first mode only.
SearchResult run_sat(const TilingProblem& p, const SearchOptions& o, Plan& pl) {
  SearchResult res = new_result(p, o, pl);
  res.formulation = "sat-" + std::string(p.set.kind() == TileKind::Wang ? "edges" : "pegs");
  res.threads = 1;
  const double limit = o.run.time_limit > 0 ? o.run.time_limit : 1e6;
  const Deadline deadline(o.run.time_limit);
  StopToken token;
  // cadical's own -t counts whole seconds: the limit is also watched here
  auto stop = [&] { return o.run.cancelled() || poll_stop(token, deadline, o.run.catch_signals); };
  SatOutcome sat = solve_symmetric_sat(*pl.domain, limit, o.run.seed, stop);
  if (sat.status == SatOutcome::Status::Satisfiable) {
    Tiling t = pl.domain->to_tiling(sat.values);
    check_solution(t, p, pl);
    if (o.on_solution) o.on_solution(t);
    res.found.push_back(std::move(t));
    res.solutions = 1;
  }
  res.complete = sat.status != SatOutcome::Status::Unknown;
  res.signal = o.run.catch_signals ? SignalCatcher::caught() : 0;
  res.interrupted = res.signal != 0 && sat.status == SatOutcome::Status::Unknown;
  res.timed_out = !res.interrupted && sat.status == SatOutcome::Status::Unknown && o.run.time_limit > 0;
  res.seconds = res.total_seconds = sat.seconds;
  return res;
}

// ---- the routes' runners (kRoutes) ----
SearchResult run_cell(const TilingProblem& p, const SearchOptions& o, Plan& pl) {
  auto ord = pl.ordering == "mrv" ? CellModel::Ordering::MostConstrained : CellModel::Ordering::Static;
  return run_model(CellModel(p, true, ord), p, o, pl);
}

SearchResult run_lattice(const TilingProblem& p, const SearchOptions& o, Plan& pl) {
  return run_model(LatticeModel(p, true), p, o, pl);
}

SearchResult run_imposed(const TilingProblem& p, const SearchOptions& o, Plan& pl) {
  auto ord = pl.ordering == "mrv" ? ImposeModel::Ordering::MostConstrained : ImposeModel::Ordering::Static;
  return run_model(ImposeModel(std::move(*pl.domain), ord, o.impose_patterns), p, o, pl);
}

SearchResult run_lift(const TilingProblem& p, const SearchOptions& o, Plan& pl) {
  return run_model(lift_lattice_model(*pl.lift), p, o, pl);
}

SearchResult run_lift_cell(const TilingProblem& p, const SearchOptions& o, Plan& pl) {
  return run_model(lift_cell_model(*pl.lift), p, o, pl);
}

SearchResult run_lift_sat(const TilingProblem& p, const SearchOptions& o, Plan& pl) {
  return solve_lift_sat(*pl.lift, p, o, fingerprint(p, o, pl));
}

// A window torus's symbols tied by its imposed group or its lift (none: free).
SymbolTies window_ties(const TilingProblem& p, const Plan& pl) {
  return pl.group         ? group_ties(p, pl.group->elements())
         : pl.window_lift ? window_lift_ties(p, *pl.window_lift)
                          : SymbolTies{};
}

// The colour lift of a window torus (the row-difference lift only ties symbols).
const WindowLiftProblem* window_colour_lift(const Plan& pl) {
  return pl.window_lift && !pl.window_lift->row_difference ? &*pl.window_lift : nullptr;
}

SearchResult run_window(const TilingProblem& p, const SearchOptions& o, Plan& pl) {
  if (const WindowLiftProblem* colour_lift = window_colour_lift(pl))
    return run_model(WindowLiftModel(*colour_lift), p, o, pl);
  return run_model(WindowModel(p, 0, 0, window_ties(p, pl)), p, o, pl);
}

SearchResult run_window_sat(const TilingProblem& p, const SearchOptions& o, Plan& pl) {
  return solve_window_sat(p, window_colour_lift(pl), window_ties(p, pl), o, fingerprint(p, o, pl));
}

}  // namespace

std::string search_fingerprint(const TilingProblem& problem, const SearchOptions& options) {
  return fingerprint(problem, options, plan(problem, options));
}

namespace {

SearchResult solve_planned(const TilingProblem& problem, const SearchOptions& options, Plan& pl) {
  std::optional<SignalCatcher> signals;
  if (options.run.catch_signals) signals.emplace();
  return pl.route->run(problem, options, pl);
}

}  // namespace

SearchResult solve(const TilingProblem& problem, const SearchOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  Plan pl = plan(problem, options);
  pl.started = started;
  SearchResult res = solve_planned(problem, options, pl);
  res.stats.searches = 1;
  res.stats.solutions = res.solutions;
  if (res.stats.search_seconds == 0) res.stats.search_seconds = res.seconds;  // the cadical routes
  return res;
}

}  // namespace tilekit
