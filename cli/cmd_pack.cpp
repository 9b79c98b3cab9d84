// tilekit pack: flags in, printing out. What a pack run does (database hit, construction,
// portfolio, search, checkpoints, signals, storage) is packing/pack.hpp.
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <optional>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/parse.hpp"
#include "base/signals.hpp"
#include "cli/command.hpp"
#include "cli/flag_terms.hpp"
#include "cli/run_options.hpp"
#include "checkpoints/checkpoint.hpp"
#include "cluster/mpi_work.hpp"
#include "cluster/part_work.hpp"
#include "packing/pack.hpp"
#include "tilesets/tile_set_io.hpp"
#include "tilesets/validator.hpp"

namespace tilekit::cli {

namespace {

struct PackArgs {
  PackRequest request;
  std::string out;
  std::vector<std::string> portfolio_stats;
  bool portfolio_report = false;
  std::int64_t estimate = 0;      // --estimate PROBES: the candidates' distances instead of a search
  double estimate_seconds = 5;    // the slice that measures each candidate's node rate
  bool quiet = false;
  bool stats = false;         // --stats: the engine's counters (solver/search_stats.hpp)
  bool mpi = false;           // --mpi: one MPI job, ranks share the subproblems (cluster/mpi_work.hpp)
  std::string part;           // --part J/K: a work unit of a split shard (cluster/part_work.hpp)
  std::string trace;          // --trace FILE: every subproblem's nodes and seconds (solver/run_trace.hpp)
  std::string formulation = "auto";  // --formulation WORD, parsed into request.formulation
  RunOptions run = [] {  // into request.run
    RunOptions r;
    r.checkpoint_every = 300;  // shown in --help; packing/ applies it when --checkpoint-every is not given
    return r;
  }();
};

// The formulation --formulation names (solver/problem.hpp).
Formulation parse_formulation(const std::string& word, bool lift) {
  if (const std::optional<Formulation> f = formulation_from_name(word)) return *f;
  if (lift)
    throw InputError(fmt::format(
        "--lift searches with the engine (--formulation auto: pegs/edges, or cell) or cadical (sat), not '{}'", word));
  throw InputError(fmt::format("unknown formulation '{}' (cell, pegs, edges, sat or auto)", word));
}

// A window torus as its symbols (one digit each, tile_grid.hpp's peg form); other tilings as
// their tile indices.
std::string grid_text(const Tiling& t) {
  std::string s;
  if (t.kind == TileKind::Window && t.colours <= 62) {
    for (const auto& row : tiling_to_peg_json(t)["pegs"]) s += row.get<std::string>() + "\n";
    return s;
  }
  for (int r = 0; r < t.rows; ++r) {
    for (int c = 0; c < t.cols; ++c) s += fmt::format("{:>4}", t.at(r, c));
    s += "\n";
  }
  return s;
}

// --portfolio-report: the per-candidate statistics that order the portfolio (several files:
// their sum, e.g. the shards of a cluster run; --out writes the sum).
void print_portfolio_report(const PackArgs& a, const Context& ctx) {
  nlohmann::json j = portfolio_report(a.portfolio_stats, a.request.kind, a.request.colours, a.out);
  emit(ctx, j, [&] {
    fmt::print("portfolio statistics: {}\n",
               j["stats"].is_string() ? j["stats"].get<std::string>() : j["stats"].dump());
    fmt::print("{:<7} {:>3} {:>6} {:>9} {:>10}  {}\n", "kind", "C", "tries", "successes", "median_s", "group");
    for (const auto& r : j["groups"])
      fmt::print("{:<7} {:>3} {:>6} {:>9} {:>10.3f}  {}\n", r["kind"].get<std::string>(), r["colors"].get<int>(),
                 r["tries"].get<std::uint64_t>(), r["successes"].get<std::uint64_t>(),
                 r["median_seconds"].get<double>(), r["group"].get<std::string>());
    if (j.contains("out")) fmt::print("sum written to {}\n", j["out"].get<std::string>());
  });
}

// 10^x as "8.68e+164" (x may be far beyond double's range).
std::string power_of_ten(double x) {
  const double e = std::floor(x);
  return fmt::format("{:.2f}e{:+}", std::pow(10.0, x - e), std::int64_t(e));
}

// --estimate PROBES: per portfolio candidate, Knuth's estimate of its search tree and the node
// rate of one slice, so the projected CPU time to exhaust it.
void print_estimate(const PackRequest& req, const PackArgs& a, const Context& ctx) {
  if (a.estimate < 1) throw InputError(fmt::format("--estimate needs at least 1 probe, got {}", a.estimate));
  const nlohmann::json j = estimate_pack(req, std::uint64_t(a.estimate), a.estimate_seconds);
  emit(ctx, j, [&] {
    fmt::print("{} C={}: each candidate's search tree by Knuth's estimate ({} probes), node rate of a {:g} s slice on "
               "{} threads\n",
               j["kind"].get<std::string>(), j["colors"].get<int>(), j["probes"].get<std::uint64_t>(),
               j["slice_seconds"].get<double>(), j["threads"].get<int>());
    fmt::print("{:<36} {:>12} {:>14} {:>21}  {}\n", "candidate", "tree nodes", "nodes/CPU-s", "CPU-hours to exhaust",
               "found in the slice");
    for (const auto& r : j["candidates"]) {
      if (!r["estimable"].get<bool>()) {
        fmt::print("{:<36} {:>12} {:>14} {:>21}  -\n", r["candidate"].get<std::string>(), "(cadical)", "-", "-");
        continue;
      }
      fmt::print("{:<36} {:>12} {:>14.3g} {:>21}  {}\n", r["candidate"].get<std::string>(),
                 power_of_ten(r["log10_tree_nodes"].get<double>()), r["nodes_per_cpu_second"].get<double>(),
                 r["log10_exhaust_cpu_hours"].is_null() ? std::string("-")
                                                        : power_of_ten(r["log10_exhaust_cpu_hours"].get<double>()),
                 r["found"].get<bool>() ? "yes" : "no");
    }
  });
  if (j["interrupted"].get<bool>()) throw Interrupted(interrupted_message(j["signal"].get<int>(), "nothing kept"));
}

nlohmann::json outcome_json(const PackOutcome& o, const std::string& out_file) {
  const SearchResult& r = o.result;
  const PackRequest& a = o.request;
  const TilingProblem& p = o.problem;
  nlohmann::json j = {{"kind", std::string(kind_name(p.set.kind()))},
                      {"colors", p.set.colours()},
                      {"set", p.set.name()},
                      {"rows", p.rows},
                      {"cols", p.cols},
                      {"method", o.method},
                      {"mode", a.mode},
                      {"complete", r.complete},
                      {"solutions", r.solutions},
                      {"nodes", r.nodes},
                      {"seconds", r.seconds},
                      {"total_seconds", r.total_seconds},
                      {"threads", r.threads},
                      {"formulation", r.formulation},
                      {"ordering", r.ordering},
                      {"shard", shard_text(a.run.shard)},
                      {"subproblems", r.shard_subproblems},
                      {"subproblems_done", r.subproblems_done},
                      {"interrupted", o.interrupted},
                      {"timed_out", r.timed_out},
                      {"db", o.db_path},
                      {"run_id", o.run_id},
                      {"stored", o.stored}};
  j["orbits"] = r.orbits ? nlohmann::json(*r.orbits) : nlohmann::json(nullptr);
  j["nodes_per_second"] = r.seconds > 0 ? double(r.nodes) / r.seconds : 0.0;
  j["group"] = o.group;
  if (!o.construction.empty()) j["construction"] = o.construction;
  if (!o.portfolio.is_null()) j["portfolio"] = o.portfolio;
  if (!o.checkpoint.empty()) j["checkpoint"] = o.checkpoint;
  if (p.set.kind() == TileKind::Window) j["window"] = {p.set.window_rows(), p.set.window_cols()};
  if (!r.found.empty()) {
    const Tiling& t = r.found.front();
    ValidationReport rep = validate(t, &p.set);
    j["valid"] = rep.valid && rep.packing;
    j["cells"] = tiling_to_json(t)["cells"];
    if (t.kind == TileKind::Window && t.colours <= 62) j["pegs"] = tiling_to_peg_json(t)["pegs"];
    if (o.orbit_size) j["orbit_size"] = *o.orbit_size;
    if (!out_file.empty()) j["out"] = out_file;
  }
  return j;
}

void print_outcome(const PackOutcome& o) {
  const SearchResult& r = o.result;
  const TilingProblem& p = o.problem;
  const std::string kind = p.set.kind() == TileKind::Window
                               ? fmt::format("window {}x{}", p.set.window_rows(), p.set.window_cols())
                               : std::string(kind_name(p.set.kind()));
  const std::uint32_t colours = p.set.colours();
  if (o.method == "search")
    fmt::print("{} C={} {}x{} packing by search, mode {}, {} ({} formulation, {} threads, shard {})\n", kind, colours,
               p.rows, p.cols, o.request.mode, r.complete ? "complete" : "incomplete", r.formulation, r.threads,
               shard_text(o.request.run.shard));
  else
    fmt::print("{} C={} {}x{} packing from {}{}\n", kind, colours, p.rows, p.cols,
               o.method == "db" ? "the database" : "a construction",
               o.construction.empty() ? "" : " (" + o.construction + ")");
  if (o.request.mode != "first")
    fmt::print("solutions: {}{}\n", r.solutions, r.orbits ? fmt::format(" ({} up to symmetry)", *r.orbits) : "");
  fmt::print("nodes: {}  seconds: {:.3f}  database: {} (run {}, {} new solutions)\n", r.nodes, r.seconds, o.db_path,
             o.run_id, o.stored);
  if (!o.group.is_null())
    fmt::print("imposed group: {} (order {})\n", o.group["spec"].get<std::string>(), o.group["order"].get<int>());
  if (o.portfolio.is_object() && !o.portfolio["winner"].is_null())
    fmt::print("portfolio winner: {}\n", o.portfolio["winner"].get<std::string>());
  if (!r.found.empty()) fmt::print("{}", grid_text(r.found.front()));
}

void run_pack_command(const PackArgs& a, const CLI::App& cmd, const Context& ctx) {
  if (a.portfolio_report) return print_portfolio_report(a, ctx);
  PackRequest req = a.request;
  a.run.apply(req.run, cmd);
  if (cmd.count("--checkpoint-every")) req.checkpoint_every = a.run.checkpoint_every;
  req.formulation = parse_formulation(a.formulation, !req.lift.empty());
  req.run.progress = !a.quiet;
  int rank = 0;
  if (a.mpi) {
    req.run.work = cluster::start_mpi_work();
    rank = req.run.work->rank();
    if (rank != 0) req.run.progress = false;  // the root reports for the job
  }
  if (!a.part.empty()) {
    if (a.mpi) throw InputError("--part: a work unit of a split job array runs without --mpi");
    // (first mode's restarts do not take their work from a source; a resume without --mode
    // takes the checkpoint's, which a split run's units always give)
    if (cmd.count("--mode") && req.mode == "first")
      throw InputError("--part: a split shard counts or lists all (--mode count or all)");
    const ShardSpec p = parse_shard(a.part, "--part");
    req.run.work = cluster::part_work(req.run.shard, ShardPart{p.index, p.count});
  }
  if (!a.trace.empty())  // an MPI rank R > 0 traces to TRACE.rank-R, like its checkpoint
    req.run.trace = std::make_shared<RunTrace>(rank == 0 ? a.trace : rank_checkpoint_path(a.trace, rank));
  if (a.portfolio_stats.size() > 1) throw InputError("--portfolio-stats: a run writes one statistics file");
  if (!a.portfolio_stats.empty()) req.portfolio_stats = a.portfolio_stats.front();
  if (cmd.count("--estimate")) return print_estimate(req, a, ctx);
  PackFields given;
  for (PackField f : pack_fields())
    if (cmd.count(flag_of_field(pack_field_name(f)))) given.insert(f);
  // --out is written before the packing is stored (the database last), or after the run where
  // nothing new is stored (a packing from the database).
  const auto write_out = [&a](const Tiling& t) {  // window tori in the compact peg form
    write_file_atomic(a.out, (t.kind == TileKind::Window && t.colours <= 62 ? tiling_to_peg_json(t) : tiling_to_json(t))
                                     .dump(1) +
                                 "\n");
  };
  bool out_written = false;
  if (!a.out.empty() && rank == 0) req.write_found = [&](const Tiling& t) { write_out(t), out_written = true; };
  PackOutcome o = run_pack(req, given);
  if (rank != 0) {  // another rank of an MPI job: the root prints the job's result
    if (o.interrupted) throw Interrupted(interrupted_message(o.signal, "rank checkpoint written"));
    return;
  }
  std::string out_file;
  if (!a.out.empty() && !o.result.found.empty()) {
    if (!out_written) write_out(o.result.found.front());
    out_file = a.out;
  }
  nlohmann::json j = outcome_json(o, out_file);
  if (a.stats) j["stats"] = o.result.stats;
  std::optional<WorkStats> mpi;
  if (a.mpi) {
    mpi = req.run.work->stats();
    j["mpi"] = {{"ranks", mpi->ranks},     {"jobs", mpi->jobs},         {"steals", mpi->steals},
                {"pieces", mpi->pieces},   {"declined", mpi->declined}, {"splits_completed", mpi->splits_completed}};
  }
  emit(ctx, j, [&] {
    print_outcome(o);
    if (mpi)
      fmt::print("mpi: {} ranks, {} jobs, {} steals ({} pieces, {} split subproblems completed), {} split requests declined\n",
                 mpi->ranks, mpi->jobs, mpi->steals, mpi->pieces, mpi->splits_completed, mpi->declined);
  });
  if (a.stats && !ctx.json) fmt::print(stderr, "{}", stats_table(o.result.stats));
  if (o.interrupted)
    throw Interrupted(interrupted_message(
        o.signal, o.checkpoint.empty()
                      ? std::string("nothing kept (use --checkpoint F to resume later)")
                      : "checkpoint written to " + o.checkpoint + " (continue with --resume " + o.checkpoint + ")"));
  if (!o.not_found.empty()) throw NotFound(o.not_found);
}

}  // namespace

void add_pack_command(CLI::App& app, Context& ctx) {
  auto a = std::make_shared<PackArgs>();
  PackRequest& r = a->request;
  auto* cmd = app.add_subcommand("pack", "Tile packing: every tile of a set exactly once on a torus (thesis sec. 5.5)");
  cmd->add_option("--kind", r.kind,
                  "Tile kind of the complete set: corner, wang, or window (every KxL window over C symbols once: a "
                  "de Bruijn torus)");
  cmd->add_option("--colors", r.colours, "Number of colours C (the complete set on the C^2 x C^2 torus)");
  cmd->add_option("--window", r.window, "--kind window: the window KxL (rows x columns)");
  cmd->add_option("--set", r.set, "Pack this tile set instead (built-in name or file)");
  cmd->add_option("--size", r.size,
                  "Torus size ROWSxCOLS for --set (default: square) and for --kind window (R*S = C^(K*L); default "
                  "C^2 x C^2 for 2x2 windows)");
  cmd->add_option("--method", r.method, "auto (database, construction, search), search or construct")
      ->capture_default_str();
  cmd->add_option("--mode", r.mode, "first, count or all (all stores every packing)")->capture_default_str();
  cmd->add_option("--formulation", a->formulation,
                  "auto, cell, pegs (corner, window), edges (Wang) or sat (with --impose or --lift; window tori)")
      ->capture_default_str();
  cmd->add_option("--ordering", r.ordering, "auto, static or mrv (most constrained first)")->capture_default_str();
  add_run_options(cmd,
                  RunOptionFlags::Threads | RunOptionFlags::Seed | RunOptionFlags::TimeLimit |
                      RunOptionFlags::Checkpoint | RunOptionFlags::Shard,
                  a->run);
  cmd->add_option("--db", r.db, "Results database");
  cmd->add_option("--out", a->out,
                  "Write the packing found to this JSON file (with --portfolio-report: the summed statistics)");
  cmd->add_option("--impose", r.impose,
                  "Search only packings invariant under this group: generators 't=DR,DC:pi=P0,P1,...' separated "
                  "by ';' (Wang: pih=/piv= per edge direction; cycles like pi=(0 1)(2 3) also work)");
  cmd->add_option("--lift", r.lift,
                  "Search packings A = B + M*E over a known packing B of M colours (colour-quotient lift; --kind "
                  "window: over a known de Bruijn torus B): 'M' or 'm=M,base=FILE'; --formulation sat solves it "
                  "with cadical");
  cmd->add_flag("--plain", r.plain, "First mode: plain search only (no portfolio)");
  cmd->add_option("--subproblems", r.subproblems,
                  "Split the search into about this many subproblems (0 = auto: 1024, at least 64 per shard; part "
                  "of the run's identity)")
      ->capture_default_str();
  cmd->add_option("--candidate", r.candidates,
                  "A portfolio candidate (repeatable): plain, a group SPEC, impose:SPEC or sat:SPEC (default: the "
                  "candidate groups and plain)");
  cmd->add_flag("--portfolio-report", a->portfolio_report,
                "Print the per-candidate statistics (tries, successes, median time) that order the portfolio");
  cmd->add_option("--estimate", a->estimate,
                  "Instead of searching: each portfolio candidate's search tree by Knuth's estimate (this many "
                  "random dives) and its node rate, so the CPU time to exhaust it");
  cmd->add_option("--estimate-seconds", a->estimate_seconds,
                  "With --estimate: the slice per candidate that measures its node rate")
      ->capture_default_str();
  cmd->add_option("--portfolio-stats", a->portfolio_stats,
                  "Portfolio statistics file (default $TILEKIT_PORTFOLIO_STATS or ~/.local/share/tilekit/"
                  "portfolio-stats.json); with --portfolio-report repeatable: the files are added up");
  cmd->add_flag("--mpi", a->mpi,
                "Run as one MPI job (mpirun/srun -n RANKS tilekit pack --mpi ...; count mode): the ranks take "
                "subproblems from a pool on rank 0 and, once it is empty, pieces a busy rank splits off its oldest open "
                "subtree (work stealing), each rank checkpoints to F.rank-R beside --checkpoint F (rank 0: F), "
                "--resume F continues with any number of ranks, rank 0 alone prints and writes the database");
  cmd->add_option("--part", a->part,
                  "J/K: of --shard I/N, run only the subproblems i with (i / N) % K == J (a work unit of a split job "
                  "array, tilekit cluster submit --split-after); --resume F merges every F.rank-* beside F first");
  cmd->add_option("--trace", a->trace,
                  "Write a trace of the run to this file (JSON lines, rewritten whole at every checkpoint and at the "
                  "end): every subproblem or restart dive with its owner, nodes, seconds and the cost of its pieces, "
                  "for `tilekit cluster simulate`");
  cmd->add_flag("--quiet", a->quiet, "No progress output on stderr");
  cmd->add_flag("--stats", a->stats,
                "Print the engine's statistics (nodes, decisions, propagations, prunes per rule, backtracks, "
                "restarts, time per phase): a table on stderr, or a \"stats\" object with --json");
  add_json_flag(cmd, ctx);
  cmd->footer(
      "`tilekit pack --resume FILE [--db DB]` alone continues the run FILE describes.\n"
      "Exit codes: 0 ok, 1 no packing found, 2 bad input or checkpoint, 3 interrupted by a signal (its one line "
      "says whether a checkpoint was written: \"checkpoint written to F\" or \"nothing kept\").");
  cmd->callback([a, cmd, &ctx] { run_pack_command(*a, *cmd, ctx); });
}

}  // namespace tilekit::cli
