// tilekit pack: tile packings (every tile of a set exactly once on a torus) by search,
// construction or database lookup, with checkpoints, shards and signals for cluster runs.
#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <thread>

#include "base/atomic_file.hpp"
#include "checkpoints/checkpoint.hpp"
#include "checkpoints/results_db.hpp"
#include "cli/command.hpp"
#include "solver/impose_portfolio.hpp"
#include "solver/impose_solve.hpp"
#include "base/signals.hpp"
#include "solver/solve.hpp"
#include "solver/symmetry.hpp"
#include "tilesets/constructions.hpp"
#include "base/error.hpp"
#include "tilesets/tile_set_io.hpp"
#include "tilesets/validator.hpp"

namespace tilekit::cli {

namespace {

struct PackArgs {
  std::string kind, set, size, method = "auto", mode = "first", checkpoint, resume, db, shard = "0/1";
  std::string formulation = "auto", ordering = "auto", out;
  std::string impose, portfolio_stats;  // issue 7: imposed group; portfolio statistics file
  std::string lift;                     // issue 11: colour-quotient lift SPEC
  bool portfolio_report = false;
  std::int64_t colours = 0;
  int threads = 0;
  std::uint64_t seed = 0;
  double checkpoint_every = -1, time_limit = 0;
  bool quiet = false, plain = false;
};

SearchMode parse_mode(const std::string& m) {
  if (m == "first") return SearchMode::First;
  if (m == "count") return SearchMode::Count;
  if (m == "all") return SearchMode::All;
  throw InputError(fmt::format("unknown mode '{}' (first, count or all)", m));
}

void parse_shard(const std::string& s, SearchOptions& o) {
  int i = 0, n = 0;
  char slash = 0, extra = 0;
  if (std::sscanf(s.c_str(), "%d%c%d%c", &i, &slash, &n, &extra) != 3 || slash != '/' || n < 1 || i < 0 || i >= n)
    throw InputError(fmt::format("--shard must be I/N with 0 <= I < N, got '{}'", s));
  o.shard_index = i, o.shard_count = n;
}

TilingProblem make_problem(const PackArgs& a) {
  if (!a.set.empty()) {
    TilingProblem p;
    p.set = resolve_tile_set(a.set);
    p.torus = true;
    p.packing = true;
    if (!a.size.empty()) {
      char x = 0, extra = 0;
      if (std::sscanf(a.size.c_str(), "%d%c%d%c", &p.rows, &x, &p.cols, &extra) != 3 || (x != 'x' && x != 'X'))
        throw InputError(fmt::format("--size must be ROWSxCOLS, got '{}'", a.size));
    } else {
      int side = 1;
      while (std::size_t(side + 1) * std::size_t(side + 1) <= p.set.size()) ++side;
      if (std::size_t(side) * std::size_t(side) != p.set.size())
        throw InputError(fmt::format("the set has {} tiles, not a square number: give --size ROWSxCOLS", p.set.size()));
      p.rows = p.cols = side;
    }
    return p;
  }
  if (a.kind.empty()) throw InputError("pack needs --kind corner|wang and --colors C (or --set SET)");
  if (a.kind != "corner" && a.kind != "wang")
    throw InputError(fmt::format("unknown tile kind '{}' (corner or wang)", a.kind));
  check_colour_count(a.colours, "--colors");
  return complete_packing_problem(a.kind == "wang" ? TileKind::Wang : TileKind::Corner, std::uint32_t(a.colours));
}

std::string grid_text(const Tiling& t) {
  std::string s;
  for (int r = 0; r < t.rows; ++r) {
    for (int c = 0; c < t.cols; ++c) s += fmt::format("{:>4}", t.at(r, c));
    s += "\n";
  }
  return s;
}

// Stores solutions in the results database in batches; flush() is what the engine calls
// before each checkpoint, so a checkpoint never covers a solution the database lacks.
class SolutionSink {
 public:
  SolutionSink(ResultsDb& db, std::int64_t run_id, const TilingProblem& p)
      : db_(db), run_id_(run_id), sym_(PackingSymmetry::for_problem(p)) {}
  void add(const Tiling& t) {
    SolutionRecord s;
    s.run_id = run_id_;
    s.tiling = t;
    s.method = method;
    s.validated = true;  // solve() validates every solution before emitting it
    s.group = group;
    if (sym_) {
      // The translates of one leaf arrive one after another and share their canonical form.
      Tiling normal = sym_->normal_form(t);
      if (normal.cells != last_normal_) {
        last_normal_ = normal.cells;
        last_hash_ = solution_hash(sym_->canonical(normal, &last_orbit_));
      }
      s.canonical_hash = last_hash_;
      s.orbit_size = last_orbit_;
    }
    batch_.push_back(std::move(s));
    if (batch_.size() >= 50000) flush();
  }
  void flush() {
    added_ += db_.add_solutions(batch_);
    batch_.clear();
  }
  std::size_t added() const { return added_; }
  nlohmann::json group;          // the imposed group of the solutions added from now on (null: none)
  std::string method = "search";  // how the solutions added from now on were found

 private:
  ResultsDb& db_;
  std::int64_t run_id_;
  std::optional<PackingSymmetry> sym_;
  std::vector<SolutionRecord> batch_;
  std::vector<TileIndex> last_normal_;
  std::string last_hash_;
  std::uint64_t last_orbit_ = 0;
  std::size_t added_ = 0;
};

// --portfolio-report: the per-group statistics that order the --method auto portfolio.
void print_portfolio_report(const PackArgs& a, const Context& ctx) {
  std::string path = a.portfolio_stats.empty() ? PortfolioStats::default_path() : a.portfolio_stats;
  nlohmann::json rows = nlohmann::json::array();
  const nlohmann::json report = PortfolioStats::load(path).report();
  for (const auto& row : report["groups"]) {
    if (!a.kind.empty() && row["kind"] != a.kind) continue;
    if (a.colours && row["colors"] != a.colours) continue;
    rows.push_back(row);
  }
  emit(ctx, {{"stats", path}, {"groups", rows}}, [&] {
    fmt::print("portfolio statistics: {}\n", path);
    fmt::print("{:<7} {:>3} {:>6} {:>9} {:>10}  {}\n", "kind", "C", "tries", "successes", "median_s", "group");
    for (const auto& r : rows)
      fmt::print("{:<7} {:>3} {:>6} {:>9} {:>10.3f}  {}\n", r["kind"].get<std::string>(), r["colors"].get<int>(),
                 r["tries"].get<std::uint64_t>(), r["successes"].get<std::uint64_t>(), r["median_seconds"].get<double>(),
                 r["group"].get<std::string>());
  });
}

void run_pack(const PackArgs& a, const Context& ctx) {
  if (a.portfolio_report) return print_portfolio_report(a, ctx);
  SignalCatcher signals;  // from here to the exit code: a signal always ends in exit 3
  TilingProblem problem = make_problem(a);
  SearchOptions o;
  o.mode = parse_mode(a.mode);
  if (a.method != "auto" && a.method != "search" && a.method != "construct")
    throw InputError(fmt::format("unknown method '{}' (auto, search or construct)", a.method));
  if (a.method == "construct" && o.mode != SearchMode::First)
    throw InputError("--method construct gives one packing: use it with --mode first");
  if (a.method == "construct" && !a.set.empty())
    throw InputError("--method construct is for the complete sets (--kind and --colors), not --set");
  if (!a.impose.empty() && a.method == "construct") throw InputError("--impose searches: use --method search or auto");
  if (!a.impose.empty() && a.plain) throw InputError("--impose and --plain exclude each other");
  if (!a.lift.empty() && (!a.impose.empty() || a.method == "construct"))
    throw InputError("--lift searches its own subspace: drop --impose and --method construct");
  o.lift = a.lift;
  o.threads = a.threads;
  o.seed = a.seed;
  o.time_limit = a.time_limit;
  o.formulation = a.formulation;
  o.ordering = a.ordering;
  parse_shard(a.shard, o);
  o.resume_path = a.resume;
  o.checkpoint_path = !a.checkpoint.empty() ? a.checkpoint : a.resume;
  if (a.checkpoint_every < 0 && a.checkpoint_every != -1)
    throw InputError(fmt::format("--checkpoint-every must be >= 0 seconds, got {}", a.checkpoint_every));
  o.checkpoint_every = a.checkpoint_every >= 0 ? a.checkpoint_every : (o.checkpoint_path.empty() ? 0 : 300);
  o.progress = !a.quiet;
  o.catch_signals = true;
  o.estimate_probes = o.progress && o.mode != SearchMode::First ? 200 : 0;
  const std::string kind(kind_name(problem.set.kind()));
  const std::uint32_t colours = problem.set.colours();
  // --impose: search only the packings invariant under the group (bad groups are exit 2 here).
  std::optional<ImposedGroup> imposed;
  if (!a.impose.empty()) {
    if (!o.checkpoint_path.empty() || !o.resume_path.empty() || o.shard_count != 1)
      throw InputError("--impose runs are not checkpointed or sharded: drop --checkpoint, --resume and --shard");
    imposed = build_group(problem, a.impose);
  }
  const bool complete_set_problem =
      problem.set.size() == complete_size(problem.set.horizontal_radix(), problem.set.vertical_radix()) &&
      problem.rows == int(colours * colours) && problem.cols == problem.rows;
  // The portfolio (plain search + imposed groups, first found wins) answers first-mode searches
  // of complete sets unless the engine is pinned by a formulation, ordering, checkpoint or shard.
  const bool use_portfolio = !imposed && a.lift.empty() && !a.plain && o.mode == SearchMode::First && a.method != "construct" &&
                             complete_set_problem && a.formulation == "auto" && a.ordering == "auto" &&
                             o.checkpoint_path.empty() && o.resume_path.empty() && o.shard_count == 1;
  o.title = fmt::format("pack {} C={} {}", kind, colours, a.mode);
  {  // bad options are exit 2 before the database is touched
    SearchOptions check = o;
    check.checkpoint_path.clear(), check.resume_path.clear();
    search_fingerprint(problem, check);
  }

  ResultsDb db(a.db.empty() ? ResultsDb::default_path() : a.db);
  RunRecord run;
  run.command = "pack";
  run.params = {{"kind", kind},
                {"colors", colours},
                {"set", problem.set.name()},
                {"rows", problem.rows},
                {"cols", problem.cols},
                {"mode", a.mode},
                {"method", a.method},
                {"seed", a.seed},
                {"shard", a.shard},
                {"formulation", a.formulation},
                {"ordering", a.ordering},
                {"time_limit", a.time_limit},
                {"checkpoint", o.checkpoint_path},
                {"resume", o.resume_path},
                {"impose", a.impose},
                {"lift", a.lift}};
  run.status = "running";
  run.threads = o.threads;
  run.id = db.begin_run(run);
  SolutionSink sink(db, run.id, problem);
  if (o.mode != SearchMode::Count) {
    o.on_solution = [&sink](const Tiling& t) { sink.add(t); };
    o.flush = [&sink] { sink.flush(); };
  }

  SearchResult r;
  std::string method = "search";
  nlohmann::json group_json = nullptr, portfolio_json = nullptr;
  std::optional<SolutionRecord> hit;
  if (a.method == "auto" && o.mode == SearchMode::First && complete_set_problem && !imposed && a.lift.empty())
    hit = db.find_solution(problem.set.kind(), colours, problem.rows, problem.cols);
  if (!(hit && validate(hit->tiling, &problem.set).packing)) hit.reset();
  std::optional<ConstructedPacking> built;
  if (!hit && a.set.empty() && !imposed && a.lift.empty() && o.mode == SearchMode::First &&
      (a.method == "construct" || a.method == "auto")) {
    built = construct_packing(problem.set.kind(), colours);
    if (built && !validate(built->tiling, &problem.set).packing)
      throw std::logic_error("construct_packing() returned a tiling the validator rejects");
    if (!built && a.method == "construct") {
      run.status = "failed";
      db.finish_run(run);
      throw NotFound(
          fmt::format("no construction is known for {} packings with {} colours (try --method search)", kind, colours));
    }
  }
  if (hit || built) {
    method = hit ? "db" : "construct";
    r.found.push_back(hit ? hit->tiling : built->tiling);
    r.solutions = 1;
    r.threads = o.threads;
    if (built) {
      sink.method = "construct";
      sink.add(built->tiling);
      sink.flush();
    }
  } else {
    try {
      // Signals stop the imposed searches and the portfolio through this flag.
      std::atomic<bool> stop{false}, done{false};
      std::thread watcher;
      if (imposed || use_portfolio)
        watcher = std::thread([&] {
          while (!done.load()) {
            if (SignalCatcher::caught()) stop = true;
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
          }
        });
      struct Join {
        std::atomic<bool>& done;
        std::thread& t;
        ~Join() {
          done = true;
          if (t.joinable()) t.join();
        }
      } join{done, watcher};
      if (imposed) {
        sink.group = imposed->to_json();
        group_json = sink.group;
        SymmetricControl ctl;
        ctl.stop = &stop;
        r = solve_symmetric(problem, *imposed, o, ctl).result;
        r.interrupted = stop.load();
      } else if (use_portfolio) {
        PortfolioOptions po;
        po.stats_path = a.portfolio_stats;
        po.stop = &stop;
        SearchOptions po_opts = o;
        po_opts.on_solution = nullptr;
        PortfolioResult pr = run_portfolio(problem.set.kind(), colours, po_opts, po);
        r = pr.result;
        r.nodes = pr.nodes;
        r.seconds = pr.seconds;
        r.threads = o.threads;
        r.interrupted = stop.load();
        portfolio_json = {{"winner", pr.found ? nlohmann::json(pr.spec) : nlohmann::json(nullptr)},
                          {"runs", pr.runs}};
        group_json = pr.group;
        sink.group = pr.group;
        if (pr.found) sink.add(pr.result.found.front());
      } else {
        r = solve_checkpointed(problem, o);
      }
      sink.flush();
    } catch (...) {
      run.status = "failed";
      db.finish_run(run);
      throw;
    }
  }
  run.status = r.interrupted || SignalCatcher::caught() ? "interrupted" : r.complete ? "complete" : "incomplete";
  run.solutions = r.solutions;
  run.orbits = r.orbits;
  run.nodes = r.nodes;
  run.seconds = r.seconds;
  db.finish_run(run);

  nlohmann::json j = {{"kind", kind},
                      {"colors", colours},
                      {"set", problem.set.name()},
                      {"rows", problem.rows},
                      {"cols", problem.cols},
                      {"method", method},
                      {"mode", a.mode},
                      {"complete", r.complete},
                      {"solutions", r.solutions},
                      {"nodes", r.nodes},
                      {"seconds", r.seconds},
                      {"total_seconds", r.total_seconds},
                      {"threads", r.threads},
                      {"formulation", r.formulation},
                      {"ordering", r.ordering},
                      {"shard", fmt::format("{}/{}", o.shard_index, o.shard_count)},
                      {"subproblems", r.shard_subproblems},
                      {"subproblems_done", r.subproblems_done},
                      {"interrupted", r.interrupted || SignalCatcher::caught() != 0},
                      {"timed_out", r.timed_out},
                      {"db", db.path()},
                      {"run_id", run.id},
                      {"stored", sink.added()}};
  j["orbits"] = r.orbits ? nlohmann::json(*r.orbits) : nlohmann::json(nullptr);
  j["nodes_per_second"] = r.seconds > 0 ? double(r.nodes) / r.seconds : 0.0;
  j["group"] = group_json;
  if (built) j["construction"] = built->how;
  if (!portfolio_json.is_null()) j["portfolio"] = portfolio_json;
  if (!o.checkpoint_path.empty()) j["checkpoint"] = o.checkpoint_path;
  if (!r.found.empty()) {
    const Tiling& t = r.found.front();
    ValidationReport rep = validate(t, &problem.set);
    j["valid"] = rep.valid && rep.packing;
    j["cells"] = tiling_to_json(t)["cells"];
    if (auto sym = PackingSymmetry::for_problem(problem)) {
      std::uint64_t orbit = 0;
      sym->canonical(t, &orbit);
      j["orbit_size"] = orbit;
    }
    if (!a.out.empty()) {
      write_file_atomic(a.out, tiling_to_json(t).dump(1) + "\n");
      j["out"] = a.out;
    }
  }
  emit(ctx, j, [&] {
    if (method == "search")
      fmt::print("{} C={} {}x{} packing by search, mode {}, {} ({} formulation, {} threads, shard {}/{})\n", kind,
                 colours, problem.rows, problem.cols, a.mode, r.complete ? "complete" : "incomplete",
                 r.formulation.empty() ? "portfolio" : r.formulation, r.threads, o.shard_index, o.shard_count);
    else
      fmt::print("{} C={} {}x{} packing from {}{}\n", kind, colours, problem.rows, problem.cols,
                 method == "db" ? "the database" : "a construction", built ? " (" + built->how + ")" : "");
    if (o.mode != SearchMode::First)
      fmt::print("solutions: {}{}\n", r.solutions, r.orbits ? fmt::format(" ({} up to symmetry)", *r.orbits) : "");
    fmt::print("nodes: {}  seconds: {:.3f}  database: {} (run {}, {} new solutions)\n", r.nodes, r.seconds, db.path(),
               run.id, sink.added());
    if (!group_json.is_null()) fmt::print("imposed group: {} (order {})\n", group_json["spec"].get<std::string>(),
                                          group_json["order"].get<int>());
    if (!r.found.empty()) fmt::print("{}", grid_text(r.found.front()));
  });
  if (r.interrupted || SignalCatcher::caught())
    throw Interrupted(fmt::format(
        "interrupted by signal {}; {}", SignalCatcher::caught(),
        imposed || use_portfolio ? std::string("imposed-group searches keep no checkpoint (run again to restart)")
        : o.checkpoint_path.empty()
            ? std::string("no checkpoint (use --checkpoint F to resume later)")
            : "checkpoint written to " + o.checkpoint_path + " (continue with --resume " + o.checkpoint_path + ")"));
  if (o.mode == SearchMode::First && r.found.empty())
    throw NotFound(r.complete ? (imposed ? "no packing is invariant under the imposed group (its subspace was exhausted)"
                                         : "no packing exists (the search space was exhausted)")
                              : "no packing found within the time limit");
}

}  // namespace

void add_pack_command(CLI::App& app, Context& ctx) {
  auto a = std::make_shared<PackArgs>();
  a->threads = int(std::max(1u, std::thread::hardware_concurrency()));
  auto* cmd = app.add_subcommand("pack", "Tile packing: every tile of a set exactly once on a torus (thesis sec. 5.5)");
  cmd->add_option("--kind", a->kind, "Tile kind of the complete set: corner or wang");
  cmd->add_option("--colors", a->colours, "Number of colours C (the complete set on the C^2 x C^2 torus)");
  cmd->add_option("--set", a->set, "Pack this tile set instead (built-in name or file)");
  cmd->add_option("--size", a->size, "Torus size ROWSxCOLS for --set (default: square)");
  cmd->add_option("--method", a->method, "auto (database, construction, search), search or construct")->capture_default_str();
  cmd->add_option("--mode", a->mode, "first, count or all (all stores every packing)")->capture_default_str();
  cmd->add_option("--threads", a->threads, "Worker threads (default: all cores)");
  cmd->add_option("--seed", a->seed, "Seed of the value order and restarts")->capture_default_str();
  cmd->add_option("--formulation", a->formulation, "auto, cell, pegs (corner) or edges (Wang)")->capture_default_str();
  cmd->add_option("--ordering", a->ordering, "auto, static or mrv (most constrained first)")->capture_default_str();
  cmd->add_option("--checkpoint", a->checkpoint, "Write checkpoints to this file");
  cmd->add_option("--checkpoint-every", a->checkpoint_every, "Seconds between checkpoints (default 300 with --checkpoint)");
  cmd->add_option("--resume", a->resume, "Resume from this checkpoint (and keep checkpointing to it)");
  cmd->add_option("--db", a->db, "Results database");
  cmd->add_option("--shard", a->shard, "Run shard I of N (I/N, 0-based)")->capture_default_str();
  cmd->add_option("--time-limit", a->time_limit, "Stop after this many seconds (0 = none)")->capture_default_str();
  cmd->add_option("--out", a->out, "Write the packing found to this JSON file");
  cmd->add_option("--impose", a->impose,
                  "Search only packings invariant under this group: generators 't=DR,DC:pi=P0,P1,...' separated "
                  "by ';' (Wang: pih=/piv= per edge direction; cycles like pi=(0 1)(2 3) also work)");
  cmd->add_option("--lift", a->lift,
                  "Search packings A = B + M*E over a known packing B of M colours (colour-quotient lift): "
                  "'M' or 'm=M,base=FILE'; --formulation sat solves it with cadical");
  cmd->add_flag("--plain", a->plain, "First mode: plain search only (no imposed-group portfolio)");
  cmd->add_flag("--portfolio-report", a->portfolio_report,
                "Print the per-group statistics (tries, successes, median time) that order the auto portfolio");
  cmd->add_option("--portfolio-stats", a->portfolio_stats,
                  "Portfolio statistics file (default $TILEKIT_PORTFOLIO_STATS or ~/.local/share/tilekit/portfolio-stats.json)");
  cmd->add_flag("--quiet", a->quiet, "No progress output on stderr");
  add_json_flag(cmd, ctx);
  cmd->footer("Exit codes: 0 ok, 1 no packing found, 2 bad input or checkpoint, 3 interrupted (checkpoint written).");
  cmd->callback([a, &ctx] { run_pack(*a, ctx); });
}

}  // namespace tilekit::cli
