// run_pack: the request/run logic of `tilekit pack` (pack.hpp).
#include "packing/pack.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "base/error.hpp"
#include "base/parallel.hpp"
#include "base/parse.hpp"
#include "base/signals.hpp"
#include "checkpoints/checkpoint.hpp"
#include "solver/search_state.hpp"
#include "packing/find_packing.hpp"
#include "packing/solution_sink.hpp"
#include "results/results_db.hpp"
#include "solver/colour_lift_model.hpp"
#include "solver/impose_domain.hpp"
#include "solver/portfolio.hpp"
#include "solver/solve.hpp"
#include "solver/symmetry.hpp"
#include "tilesets/constructions.hpp"
#include "tilesets/tile_grid.hpp"
#include "tilesets/tile_set_io.hpp"
#include "tilesets/validator.hpp"
#include "tilesets/window_torus.hpp"

namespace tilekit {
namespace {

SearchMode parse_mode(const std::string& m) {
  if (m == "first") return SearchMode::First;
  if (m == "count") return SearchMode::Count;
  if (m == "all") return SearchMode::All;
  throw InputError(fmt::format("unknown mode '{}' (first, count or all)", m));
}

// Kind window, window KxL, C colours, size RxS: every K x L window over C symbols once on the
// R x S torus (a de Bruijn torus); the size defaults to C^2 x C^2 for 2x2 windows (the corner case).
TilingProblem window_problem(const PackRequest& a) {
  if (a.window.empty())
    throw RequestError("kind", "`kind` window needs `window` KxL (e.g. `window` 3x3), `colours` C and `size` RxS");
  if (!a.set.empty()) throw RequestError("kind", "`kind` window packs every window over `colours` symbols, not `set`");
  const Dimensions w = parse_dimensions(a.window, kMaxTilingSide, kMaxTilingCells, "`window` KxL");
  check_colour_count(a.colours, "`colours`");
  Dimensions size{std::int64_t(a.colours) * a.colours, std::int64_t(a.colours) * a.colours};
  if (!a.size.empty())
    size = parse_dimensions(a.size, kMaxTilingSide, kMaxTilingCells, "`size` RxS");
  else if (w.first != 2 || w.second != 2)
    throw RequestError("kind",
                       fmt::format("`kind` window `window` {} needs `size` RxS, the torus (R*S = C^(K*L))", a.window));
  return window_torus_problem(a.colours, int(w.first), int(w.second), int(size.first), int(size.second));
}

TilingProblem make_problem(const PackRequest& a) {
  if (a.kind == "window") return window_problem(a);
  if (!a.window.empty()) throw RequestError("window", "`window` is for `kind` window (de Bruijn tori)");
  if (!a.set.empty()) {
    TilingProblem p;
    p.set = resolve_tile_set(a.set);
    p.torus = true;
    p.packing = true;
    if (!a.size.empty()) {
      // A packing holds every tile once: rows * cols must be the set's size.
      const Dimensions d = parse_dimensions(a.size, kMaxTilingSide, kMaxTilingCells, "`size` ROWSxCOLS");
      p.rows = int(d.first), p.cols = int(d.second);
      if (std::uint64_t(d.first * d.second) != p.set.size())
        throw RequestError(
            "size", fmt::format("`size` {}: a packing of the {} tiles of {} needs rows*cols = {}, not {}", a.size,
                                p.set.size(), p.set.name(), p.set.size(), d.first * d.second));
    } else {
      int side = 1;
      while (std::size_t(side + 1) * std::size_t(side + 1) <= p.set.size()) ++side;
      if (std::size_t(side) * std::size_t(side) != p.set.size())
        throw RequestError(
            "size", fmt::format("the set has {} tiles, not a square number: give `size` ROWSxCOLS", p.set.size()));
      p.rows = p.cols = side;
    }
    return p;
  }
  if (a.kind.empty())
    throw RequestError("kind", "pack needs `kind` corner|wang|window and `colours` C (or `set` SET, or `resume` FILE)");
  if (a.kind != "corner" && a.kind != "wang")
    throw InputError(fmt::format("unknown tile kind '{}' (corner, wang or window)", a.kind));
  return complete_packing_problem(a.kind == "wang" ? TileKind::Wang : TileKind::Corner, a.colours);
}

// The engine options of a request (checks every flag that solve() does not).
SearchOptions search_options(const PackRequest& a) {
  SearchOptions o;
  o.mode = parse_mode(a.mode);
  if (a.method != "auto" && a.method != "search" && a.method != "construct")
    throw InputError(fmt::format("unknown method '{}' (auto, search or construct)", a.method));
  if (a.method == "construct" && o.mode != SearchMode::First)
    throw RequestError("method", "`method` construct gives one packing: use it with `mode` first");
  if (a.method == "construct" && !a.set.empty())
    throw RequestError("method", "`method` construct is for the complete sets (`kind` and `colours`), not `set`");
  if (!a.impose.empty() && a.method == "construct")
    throw RequestError("impose", "`impose` searches: use `method` search or auto");
  if (!a.impose.empty() && a.plain) throw RequestError("impose", "`impose` and `plain` exclude each other");
  if (!a.lift.empty() && (!a.impose.empty() || a.method == "construct"))
    throw RequestError("lift", "`lift` searches its own subspace: drop `impose` and `method` construct");
  if (!a.candidates.empty() && (a.plain || !a.impose.empty() || !a.lift.empty()))
    throw RequestError("candidates", "`candidates` names a portfolio candidate: not with `plain`, `impose` or `lift`");
  if (a.subproblems < 0 || std::uint64_t(a.subproblems) > kMaxSplitSubproblems)
    throw RequestError("subproblems", fmt::format("`subproblems` must be 0 (auto) to {}, got {}",
                                                  kMaxSplitSubproblems, a.subproblems));
  o.subproblems = std::size_t(a.subproblems);
  o.formulation = a.formulation;
  o.ordering = a.ordering;
  o.impose = a.impose;
  o.lift = a.lift;
  o.run = a.run;
  if (o.run.checkpoint_path.empty()) o.run.checkpoint_path = a.run.resume_path;  // keep checkpointing to it
  if (a.checkpoint_every && !(*a.checkpoint_every >= 0))
    throw RequestError("checkpoint_every",
                       fmt::format("`checkpoint_every` must be >= 0 seconds, got {}", *a.checkpoint_every));
  o.run.checkpoint_every = a.checkpoint_every.value_or(o.run.checkpoint_path.empty() ? 0 : 300);
  o.estimate_probes = o.run.progress && o.mode != SearchMode::First ? 200 : 0;
  return o;
}

bool is_complete_set_problem(const TilingProblem& p) {
  if (p.set.kind() == TileKind::Window) return false;  // window tori have their own first-mode path
  const std::uint32_t c = p.set.colours();
  return p.set.size() == complete_size(p.set.horizontal_radix(), p.set.vertical_radix()) && p.rows == int(c * c) &&
         p.cols == p.rows;
}

nlohmann::json group_json(const TilingProblem& p, const std::string& spec) {
  return spec.empty() ? nlohmann::json(nullptr) : build_group(p, spec).to_json();
}

// The portfolio answers first-mode searches of complete sets unless the engine is pinned by a
// group, a lift, `plain`, a formulation or an ordering.
bool uses_portfolio(const PackRequest& a, SearchMode mode, bool complete_set) {
  return a.impose.empty() && a.lift.empty() && !a.plain && mode == SearchMode::First && a.method != "construct" &&
         complete_set && a.formulation == Formulation::Auto && a.ordering == "auto";
}

// Bad options, and searches that cannot fit in memory, are exit 2 before the database is touched.
void check_runnable(const PackRequest& a, const TilingProblem& problem, const SearchOptions& o,
                    const PortfolioOptions& po, bool use_portfolio) {
  if (!a.candidates.empty() && !use_portfolio)
    throw RequestError("candidates",
                       "`candidates` needs a portfolio run (first mode, complete set, auto formulation and ordering)");
  const std::uint32_t colours = problem.set.colours();
  const std::vector<std::uint32_t> constructible = a.set.empty() && problem.set.kind() != TileKind::Window
                                                       ? constructible_colours(problem.set.kind(), colours)
                                                       : std::vector<std::uint32_t>{};
  const bool may_construct = a.method != "search" && o.mode == SearchMode::First && a.impose.empty() &&
                             std::find(constructible.begin(), constructible.end(), colours) != constructible.end();
  if (a.method != "construct" && !may_construct) check_searchable(problem);
  SearchOptions check = o;
  check.run.checkpoint_path.clear(), check.run.resume_path.clear();
  if (use_portfolio) {
    portfolio_fingerprint(problem, check, po);
    for (const auto& c : po.candidates.empty() ? default_candidates(problem.set.kind(), colours) : po.candidates)
      make_candidate(problem, c);
  } else {
    search_fingerprint(problem, check);
  }
  // A checkpoint of another run is refused here, before the database or the file is touched.
  if (!o.run.resume_path.empty()) read_resume_file(problem, o, use_portfolio ? &po : nullptr);
  // So is a statistics file that cannot be read (a refused run creates no database).
  if (use_portfolio && !po.stats_path.empty() && po.stats_path != "-") PortfolioStats::load(po.stats_path);
}

// The run's row in the results database, "running" until finish_record().
RunRecord begin_record(ResultsDb& db, const PackRequest& a, const TilingProblem& problem, const SearchOptions& o,
                       const nlohmann::json& identity) {
  RunRecord record;
  record.command = "pack";
  record.params = identity;
  record.params["rows"] = problem.rows;
  record.params["cols"] = problem.cols;
  record.params["time_limit"] = a.run.time_limit;
  record.params["checkpoint"] = o.run.checkpoint_path;
  record.params["resume"] = o.run.resume_path;
  record.status = "running";
  record.threads = o.run.threads;
  record.id = db.begin_run(record);
  return record;
}

// The portfolio's answer as the outcome's SearchResult, with the winner and every candidate's
// runs; the packing found goes into `sink` under the winner's group.
void portfolio_search(PackOutcome& out, SearchOptions o, const PortfolioOptions& po, const nlohmann::json& identity,
                      SolutionSink& sink) {
  o.on_solution = nullptr;  // stored below with the winner's group
  o.flush = nullptr;
  PortfolioResult pr = run_portfolio_checkpointed(out.problem, o, po, identity);
  out.result = pr.as_search_result(o.run.threads);
  out.portfolio = {{"winner", pr.found ? nlohmann::json(pr.winner) : nlohmann::json(nullptr)}, {"runs", pr.runs}};
  sink.group = out.group = group_json(out.problem, out.result.group);
  if (pr.found) sink.add(pr.result.found.front());
}

// First mode on a complete set without a group or lift: the database, a construction, then
// `search` (find_packing.hpp), as --method allows.
void find_first(PackOutcome& out, ResultsDb& db, SolutionSink& sink, int threads, const std::function<void()>& search) {
  const PackRequest& a = out.request;
  SearchResult& r = out.result;
  const TileKind kind = out.problem.set.kind();
  const std::uint32_t colours = out.problem.set.colours();
  PackingSources src;
  src.db = a.method == "auto" ? &db : nullptr;
  src.construct = a.method != "search";
  if (a.method != "construct")
    src.search = [&]() -> std::optional<FoundPacking> {
      search();
      if (r.found.empty()) return std::nullopt;
      return FoundPacking{r.found.front(), "search", r.group, false, 0};
    };
  std::optional<FoundPacking> found = find_packing(kind, colours, src);
  out.method = found ? found->source : "search";
  if (found && found->source != "search") {
    r.found = {found->tiling};
    r.solutions = 1;
    r.threads = threads;
    r.complete = false;
    if (found->source == "construct") {
      out.construction = found->how;
      sink.method = "construct";
      sink.add(found->tiling);
      sink.flush();
    }
  }
  if (!found && a.method == "construct")
    throw NotFound(fmt::format("no construction is known for {} packings with {} colours (try `method` search)",
                               kind_name(kind), colours));
}

// First mode for window tori without a lift: the database, a construction (stored tori; 2x2
// windows: the corner packing), then `search`, as --method allows.
void find_first_window(PackOutcome& out, ResultsDb& db, SolutionSink& sink, int threads,
                       const std::function<void()>& search) {
  const PackRequest& a = out.request;
  const TilingProblem& p = out.problem;
  const TileSet& set = p.set;
  SearchResult& r = out.result;
  auto answer = [&](Tiling t, const std::string& method) {
    if (!validate(t, &set).packing)
      throw std::logic_error("a stored or constructed window torus failed the validator");  // data or library bug
    r.found = {std::move(t)};
    r.solutions = 1;
    r.threads = threads;
    out.method = method;
  };
  if (a.method == "auto")
    if (auto s = db.find_solution(TileKind::Window, set.horizontal_radix(), p.rows, p.cols, set.window_rows(),
                                  set.window_cols());
        s && validate(s->tiling, &set).packing)
      return answer(std::move(s->tiling), "db");
  if (a.method != "search")
    if (auto c = construct_window_torus(set.horizontal_radix(), set.window_rows(), set.window_cols(), p.rows, p.cols)) {
      answer(std::move(c->tiling), "construct");
      out.construction = c->how;
      sink.method = "construct";
      sink.add(r.found.front());
      sink.flush();
      return;
    }
  if (a.method == "construct")
    throw NotFound(
        fmt::format("no construction is known for {}x{} windows over {} symbols on {}x{} (try `method` search)",
                    set.window_rows(), set.window_cols(), set.horizontal_radix(), p.rows, p.cols));
  out.method = "search";
  search();
}

// Why first mode found no packing (exit 1).
std::string not_found_reason(const PackOutcome& out) {
  const PackRequest& a = out.request;
  const SearchResult& r = out.result;
  if (r.complete)
    return !a.impose.empty() ? "no packing is invariant under the imposed group (its subspace was exhausted)"
           : !a.lift.empty() ? "no packing is a lift of the base packing (its subspace was exhausted)"
                             : "no packing exists (the search space was exhausted)";
  return out.portfolio.is_object() && !out.interrupted && !r.timed_out
             ? "no packing in the portfolio's subspaces (each candidate was exhausted)"
             : "no packing found within the time limit";
}

// The outcome's closing fields from the search result, and the run's row closed.
void finish(PackOutcome& out, ResultsDb& db, RunRecord& record, const SolutionSink& sink, const SearchOptions& o) {
  const SearchResult& r = out.result;
  out.signal = r.signal ? r.signal : SignalCatcher::caught();
  out.interrupted = r.interrupted || SignalCatcher::caught() != 0;
  record.status = out.interrupted ? "interrupted" : r.complete ? "complete" : "incomplete";
  record.solutions = r.solutions;
  record.orbits = r.orbits;
  record.nodes = r.nodes;
  record.seconds = r.seconds;
  db.finish_run(record);
  out.stored = sink.added();
  // Named only when this run wrote it: a signal before the search (a database lookup, a
  // construction) keeps nothing, and the CLI's message must say so.
  if (out.method == "search" && !o.run.checkpoint_path.empty() && r.checkpoints > 0)
    out.checkpoint = o.run.checkpoint_path;
  if (!r.found.empty())
    if (auto sym = PackingSymmetry::for_problem(out.problem)) {
      std::uint64_t orbit = 0;
      sym->canonical(r.found.front(), &orbit);
      out.orbit_size = orbit;
    }
  if (o.mode == SearchMode::First && r.found.empty()) out.not_found = not_found_reason(out);
}

}  // namespace

PackOutcome run_pack(PackRequest request, const PackFields& given) {
  std::optional<SignalCatcher> signals;  // from here to the outcome: a signal always ends in `interrupted`
  if (request.run.catch_signals) signals.emplace();
  // A lift's base file is stored absolute, so that `pack --resume F` works from any directory.
  if (request.set.empty() && request.kind != "window") request.lift = lift_with_absolute_base(request.lift);
  if (!request.run.resume_path.empty()) {  // `--resume FILE` alone: the checkpoint says what the run is
    CheckpointFile f = read_checkpoint_file(request.run.resume_path);
    request = resume_request(request, given, f.request, request.run.resume_path);
  }
  PackOutcome out;
  out.request = request;
  const PackRequest& a = out.request;
  out.problem = make_problem(a);
  const TilingProblem& problem = out.problem;
  SearchOptions o = search_options(a);
  const bool complete_set = is_complete_set_problem(problem);
  const bool use_portfolio = uses_portfolio(a, o.mode, complete_set);
  o.title = problem.set.kind() == TileKind::Window
                ? fmt::format("pack window {}x{} C={} {}x{} {}", problem.set.window_rows(), problem.set.window_cols(),
                              problem.set.horizontal_radix(), problem.rows, problem.cols, a.mode)
                : fmt::format("pack {} C={} {}", kind_name(problem.set.kind()), problem.set.colours(), a.mode);
  PortfolioOptions po;
  po.stats_path = a.portfolio_stats;
  po.candidates = a.candidates;
  check_runnable(a, problem, o, po, use_portfolio);
  const nlohmann::json identity = request_identity(a);
  // What every checkpoint stores: the identity, and the time limit that `pack --resume F`
  // alone applies again (a run setting, so a flag given on resume replaces it).
  nlohmann::json stored = identity;
  stored["time_limit"] = a.run.time_limit;
  // An MPI job (cluster/mpi_work.hpp) of several ranks: one count shared by its ranks (one
  // process with a work source, a part of a split shard, cluster/part_work.hpp, runs as any).
  if (a.run.work && a.run.work->ranks() > 1) {
    if (o.mode != SearchMode::Count) throw RequestError("mode", "an MPI run counts: `mode` must be count");
    if (a.run.shard.count != 1)
      throw RequestError("shard", "an MPI run shares its work among its ranks dynamically: no `shard`");
    if (a.run.work->rank() != 0) {  // the root alone writes the database
      out.method = "search";
      out.result = solve_checkpointed(problem, o, stored);
      out.signal = out.result.signal ? out.result.signal : SignalCatcher::caught();
      out.interrupted = out.result.interrupted || SignalCatcher::caught() != 0;
      return out;
    }
  }

  ResultsDb db(a.db.empty() ? ResultsDb::default_path() : a.db);
  out.db_path = db.path();
  RunRecord record = begin_record(db, a, problem, o, identity);
  out.run_id = record.id;
  SolutionSink sink(db, record.id, problem);
  if (o.mode == SearchMode::First) sink.before_first_store = a.write_found;  // its file, then the database
  if (o.mode != SearchMode::Count) {
    o.on_solution = [&sink](const Tiling& t) { sink.add(t); };
    o.flush = [&sink] { sink.flush(); };
  }
  sink.group = out.group = group_json(problem, a.impose);
  // One search: the portfolio, or solve() (under the group with --impose).
  auto search = [&] {
    if (use_portfolio)
      portfolio_search(out, o, po, stored, sink);
    else
      out.result = solve_checkpointed(problem, o, stored);
    sink.flush();
  };
  try {
    if (o.mode == SearchMode::First && complete_set && a.impose.empty() && a.lift.empty() && a.set.empty()) {
      find_first(out, db, sink, o.run.threads, search);
    } else if (o.mode == SearchMode::First && problem.set.kind() == TileKind::Window && a.lift.empty()) {
      find_first_window(out, db, sink, o.run.threads, search);
    } else {
      out.method = "search";
      search();
    }
  } catch (const InputError&) {
    // Bad input the engine found before it stored anything (a checkpoint inconsistent with this
    // search): a refused command leaves no trace, so its run row goes again.
    if (sink.added() == 0 && db.forget_run(record.id)) throw;
    record.status = "failed";
    db.finish_run(record);
    throw;
  } catch (...) {
    record.status = "failed";
    db.finish_run(record);
    throw;
  }
  finish(out, db, record, sink, o);
  return out;
}

nlohmann::json portfolio_report(const std::vector<std::string>& stats_files, const std::string& kind,
                                std::int64_t colours, const std::string& out) {
  std::vector<std::string> paths = stats_files;
  if (paths.empty()) paths.push_back(PortfolioStats::default_path());
  PortfolioStats sum;
  for (const auto& p : paths) sum.merge(PortfolioStats::load(p));
  if (!out.empty()) sum.save(out);
  nlohmann::json rows = nlohmann::json::array();
  const nlohmann::json report = sum.report();
  for (const auto& row : report["groups"]) {
    if (!kind.empty() && row["kind"] != kind) continue;
    if (colours && row["colors"] != colours) continue;
    rows.push_back(row);
  }
  nlohmann::json j = {{"stats", paths.size() == 1 ? nlohmann::json(paths[0]) : nlohmann::json(paths)},
                      {"groups", rows}};
  if (!out.empty()) j["out"] = out;
  return j;
}

nlohmann::json estimate_pack(const PackRequest& a, std::uint64_t probes, double slice_seconds) {
  const TilingProblem problem = make_problem(a);
  SearchOptions o = search_options(a);
  if (o.mode != SearchMode::First || !is_complete_set_problem(problem) || !uses_portfolio(a, o.mode, true))
    throw RequestError(
        "probes",
        "`probes` measures the portfolio's candidates: a complete set (`kind`, `colours`), `mode` first, "
        "no `impose`, `lift`, `plain`, `formulation` or `ordering`");
  if (!a.run.resume_path.empty())
    throw RequestError("probes", "`probes` measures the candidates afresh: it does not continue a checkpoint (`resume`)");
  o.run.threads = resolve_threads(o.run.threads);
  PortfolioOptions po;
  po.candidates = a.candidates;
  nlohmann::json rows = nlohmann::json::array();
  for (const CandidateEstimate& e : estimate_candidates(problem, o, po, probes, slice_seconds)) {
    nlohmann::json r = {{"candidate", e.name}, {"family", e.family}, {"estimable", e.estimable}};
    if (e.estimable) {
      const double cpu = e.seconds * o.run.threads, rate = cpu > 0 ? double(e.nodes) / cpu : 0;
      r["log10_tree_nodes"] = e.log10_tree_nodes;
      r["probes"] = e.probes;
      r["nodes"] = e.nodes;
      r["seconds"] = e.seconds;
      r["nodes_per_cpu_second"] = rate;
      r["log10_exhaust_cpu_hours"] =
          rate > 0 ? nlohmann::json(e.log10_tree_nodes - std::log10(rate * 3600)) : nlohmann::json(nullptr);
      r["found"] = e.found;
    }
    rows.push_back(r);
  }
  // A signal ends the estimate with the candidates measured so far (the CLI exits 3).
  const int signal = o.run.catch_signals ? SignalCatcher::caught() : 0;
  return {{"kind", std::string(kind_name(problem.set.kind()))},
          {"colors", problem.set.colours()},
          {"threads", o.run.threads},
          {"interrupted", signal != 0},
          {"signal", signal},
          {"probes", probes},
          {"slice_seconds", slice_seconds},
          {"candidates", rows}};
}

}  // namespace tilekit
