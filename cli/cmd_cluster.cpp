// tilekit cluster submit|status: flags in, printing out. Planning the Slurm job array, its
// scripts, the run directory, the submission and a run's status are cluster/.
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <regex>
#include <string_view>

#include "base/error.hpp"
#include "base/parse.hpp"
#include "cli/command.hpp"
#include "cluster/job_scripts.hpp"
#include "cluster/plan.hpp"
#include "cluster/schedule_sim.hpp"
#include "cli/shard_words.hpp"
#include "cluster/status.hpp"
#include "cluster/split.hpp"
#include "cluster/submit.hpp"
#include "cluster/run_directory.hpp"

namespace tilekit::cli {
namespace fs = std::filesystem;
namespace {

struct SubmitArgs {
  cluster::SubmitRequest request;
  bool dry_run = false;
  std::string sbatch = "sbatch";
};

struct StatusArgs {
  std::string run_dir;
};

struct SimulateArgs {
  std::vector<std::string> traces;
  std::string workers = "16,128,1024,10000";
  std::string policies = "static,pool,split,steal";
  std::string cost = "nodes";
  std::int64_t rounds = 4;
};

// "16,128,1024": each a whole number of workers in 1..10^9.
std::vector<std::int64_t> worker_counts(const std::string& text) {
  std::vector<std::int64_t> out;
  std::size_t from = 0;
  for (;;) {
    const std::size_t comma = text.find(',', from);
    out.push_back(parse_integer(std::string_view(text).substr(from, comma - from), 1, 1'000'000'000, "--workers"));
    if (comma == std::string::npos) return out;
    from = comma + 1;
  }
}

void run_simulate(const SimulateArgs& a, const Context& ctx) {
  const std::vector<std::int64_t> workers = worker_counts(a.workers);
  std::vector<cluster::SchedulePolicy> policies;
  std::size_t from = 0;
  for (;;) {
    const std::size_t comma = a.policies.find(',', from);
    policies.push_back(cluster::policy_from_name(a.policies.substr(from, comma - from)));
    if (comma == std::string::npos) break;
    from = comma + 1;
  }
  if (a.rounds < 1 || a.rounds > 1000) throw InputError(fmt::format("--rounds must be 1..1000, got {}", a.rounds));
  const cluster::Trace trace = cluster::read_trace(a.traces, a.cost);
  nlohmann::json rows = nlohmann::json::array();
  std::vector<cluster::SimResult> results;
  for (std::int64_t p : workers)
    for (cluster::SchedulePolicy pol : policies) {
      results.push_back(cluster::simulate(trace, pol, p, int(a.rounds)));
      rows.push_back(cluster::to_json(results.back()));
    }
  std::size_t pieces = 0;
  for (const auto& u : trace.units) pieces += std::max<std::size_t>(1, u.pieces.size());
  nlohmann::json j = {{"traces", a.traces},          {"cost", a.cost},        {"mode", trace.first ? "first" : "exhaustive"},
                      {"units", trace.units.size()}, {"pieces", pieces},      {"work", trace.work()},
                      {"largest_piece", trace.largest_piece()}, {"results", rows}};
  emit(ctx, j, [&] {
    fmt::print("{}: {} run, {} units, {} pieces, work {:.6g} {}, largest piece {:.3g}\n", trace.files,
               trace.first ? "first-mode" : "exhaustive", trace.units.size(), pieces, trace.work(), a.cost,
               trace.largest_piece());
    fmt::print("{:>8} {:<7} {:>12} {:>12} {:>12} {:>10} {:>6} {:>8}\n", "workers", "policy", "makespan", "ideal",
               "bound", "efficiency", "rounds", "steals");
    for (const auto& r : results)
      fmt::print("{:>8} {:<7} {:>12.4g} {:>12.4g} {:>12.4g} {:>9.1f}% {:>6} {:>8}\n", r.workers,
                 cluster::policy_name(r.policy), r.makespan, r.ideal, r.bound, 100 * r.efficiency, r.rounds, r.steals);
  });
}

// A field name with '-' for '_'.
std::string dashed(std::string name) {
  std::replace(name.begin(), name.end(), '_', '-');
  return name;
}

// A cluster/ message in flag terms: the library names the fields of its request between
// backquotes ("`checkpoint_every` must be ..."), the user reads the flags that set them
// ("--checkpoint-every must be ...").
std::string cluster_message_in_flags(std::string_view message) {
  static const std::regex field("`([a-z][a-z0-9_]*)`");
  const char* from = message.data();
  const char* const last = message.data() + message.size();
  std::string out;
  for (std::cregex_iterator m(from, last, field), end; m != end; ++m) {
    out.append(from, (*m)[0].first);
    const std::string name = (*m)[1].str();
    out += name == "shard_args"    ? std::string("--pack-arg")
           : name == "sbatch_args" ? std::string("--sbatch-arg")
                                   : "--" + dashed(name);
    from = (*m)[0].second;
  }
  return out.append(from, last);
}

// Runs one cluster/ call, its errors worded in flag terms (the exit codes unchanged).
template <class F>
void with_cluster_errors_in_flags(F call) {
  try {
    call();
  } catch (const NotFound& e) {
    throw NotFound(cluster_message_in_flags(e.what()));
  } catch (const InputError& e) {
    throw InputError(cluster_message_in_flags(e.what()));
  }
}

void print_dry_run(const cluster::ClusterPlan& p, const Context& ctx) {
  const fs::path dir(p.run_dir);
  const auto scripts = cluster::job_scripts(p);
  nlohmann::json js = nlohmann::json::object();
  for (const auto& s : scripts) js[(dir / s.name).string()] = s.text;
  emit(ctx,
       {{"dry_run", true},
        {"run_dir", p.run_dir},
        {"shards", p.shards},
        {"mpi", p.mpi},
        {"tilekit", p.tilekit},
        {"scripts", js}},
       [&] {
         for (const auto& s : scripts) fmt::print("==> {} <==\n{}\n", (dir / s.name).string(), s.text);
         fmt::print("(dry run: nothing written or queued; without --dry-run, submit.sh's sbatch {} run)\n",
                    p.mpi ? "call" : "calls");
       });
}

void run_submit(const SubmitArgs& a, const Context& ctx) {
  const cluster::ClusterPlan p = cluster::make_plan(a.request);
  if (a.dry_run) return print_dry_run(p, ctx);
  const cluster::Submission s = cluster::submit_run(p, a.sbatch);
  if (p.mpi)
    return emit(ctx,
                {{"run_dir", p.run_dir},
                 {"mpi_job", s.array_job},
                 {"nodes", p.nodes},
                 {"ntasks", p.ntasks},
                 {"launcher", p.launcher},
                 {"tilekit", p.tilekit},
                 {"submissions", s.submissions}},
                [&] {
                  fmt::print("submitted one MPI job to Slurm: job {}, {} ranks on {} nodes ({})\n", s.array_job,
                             p.ntasks, p.nodes, p.launcher == "srun" ? "srun --mpi=" + p.srun_mpi : p.launcher);
                  fmt::print("the ranks run {} pack --mpi\nrun directory: {}\n", p.tilekit, p.run_dir);
                  fmt::print("progress: tilekit cluster status --run-dir {}\n", cluster::shell_quote(p.run_dir));
                });
  emit(ctx,
       {{"run_dir", p.run_dir},
        {"shards", p.shards},
        {"tilekit", p.tilekit},
        {"array_job", s.array_job},
        {"merge_job", s.merge_job},
        {"submissions", s.submissions}},
       [&] {
         fmt::print("submitted {} shards to Slurm: array job {}, merge job {} (afterok:{})\n", p.shards, s.array_job,
                    s.merge_job, s.array_job);
         fmt::print("the jobs run {}\nrun directory: {}\nprogress: tilekit cluster status --run-dir {}\n", p.tilekit,
                    p.run_dir, cluster::shell_quote(p.run_dir));
       });
}

// A shard's checkpoint column: its progress so far, or why it cannot be read.
std::string checkpoint_text(const cluster::ShardStatus& s) {
  if (!s.checkpoint_age_seconds || !s.progress) return "-";
  const cluster::ShardProgress& p = *s.progress;
  if (!p.error.empty()) return fmt::format("unreadable: {}", p.error);
  return fmt::format("{}/{} subproblems ({:.1f}%), {} solutions, {} nodes; written {} s ago{}", p.subproblems_done,
                     p.subproblems, 100 * p.fraction, p.solutions, p.nodes, *s.checkpoint_age_seconds,
                     p.eta_seconds ? fmt::format("; ETA ~{:.0f} s", *p.eta_seconds) : std::string());
}

template <class T>
std::string value_or_dash(const std::optional<T>& v) {
  return v ? fmt::format("{}", *v) : std::string("-");
}

void print_status(const cluster::RunStatus& r) {
  std::string args;
  for (const auto& a : r.pack_args) args += " " + a;
  if (r.mpi_ranks)
    fmt::print("run {} (tilekit pack --mpi{}), one MPI job of {} ranks (shard 0 below: the ranks' checkpoints "
               "merged)\n",
               r.run_dir, args, r.mpi_ranks);
  else
    fmt::print("run {} (tilekit pack{}), {} shards: {} done, {} checkpointed, {} started, {} pending\n", r.run_dir,
               args, r.shards, r.done, r.checkpointed, r.started, r.pending);
  fmt::print("{:>5}  {:<12} {:>8} {:>9} {:>9} {:>12}  {}\n", "shard", "state", "attempts", "exit 3s", "last exit",
             "solutions", "checkpoint (progress so far)");
  for (const auto& s : r.per_shard) {
    fmt::print("{:>5}  {:<12} {:>8} {:>9} {:>9} {:>12}  {}\n", s.shard, s.state, s.attempts, s.checkpointed_exits,
               value_or_dash(s.last_exit), value_or_dash(s.solutions), checkpoint_text(s));
    if (!s.attempts_error.empty()) fmt::print("       attempts unreadable: {}\n", s.attempts_error);
  }
  fmt::print("solutions in done shards: {}\n", r.solutions_in_done_shards);
  fmt::print("work done: {} nodes; outstanding: {}; ETA: {}\n", r.work_done_nodes,
             r.work_outstanding_nodes ? fmt::format("~{:.3g} nodes (open subproblems at the mean finished size)",
                                                    *r.work_outstanding_nodes)
                                      : std::string("not yet known (a shard has no finished subproblem)"),
             r.eta_seconds ? fmt::format("~{:.0f} s (the slowest shard at its node rate so far)", *r.eta_seconds)
                           : std::string("-"));
  if (r.mpi_ranks) return;  // no merge: rank 0 writes the one database
  if (!r.merged_solutions)
    fmt::print("merged: not yet (the merge job runs when every shard ended with exit 0)\n");
  else
    fmt::print("merged: {} distinct solutions ({} up to symmetry) in {}\n", *r.merged_solutions,
               r.merged_orbits ? fmt::format("{}", *r.merged_orbits) : std::string("null"),
               (fs::path(r.run_dir) / "merged.sqlite").string());
}

void run_status(const StatusArgs& a, const Context& ctx) {
  const cluster::RunStatus r = cluster::read_run_status(a.run_dir);
  emit(ctx, cluster::to_json(r), [&] { print_status(r); });
}

void add_submit(CLI::App& cluster, Context& ctx) {
  auto* cmd = cluster.add_subcommand(
      "submit",
      "Write the job-array, merge and submit scripts for a sharded `tilekit pack` (or, with --mpi, one MPI job's "
      "script) and queue them with sbatch");
  auto a = std::make_shared<SubmitArgs>();
  cluster::SubmitRequest& r = a->request;
  r.words = pack_shard_words();
  cluster::ClusterPlan& plan = r.settings;
  cmd->add_option("--command", r.command, "The shard command: pack (default) or enumerate (aperiodic enumerate)");
  cmd->add_option("--kind", r.kind,
                  "pack: tile kind, wang, corner or window (de Bruijn tori: --pack-arg=--window=KxL "
                  "--pack-arg=--size=RxS; required)");
  cmd->add_option("--colors", r.colors, "pack: number of colours C (required)");
  cmd->add_option("--method", r.method, "Passed to pack: auto, search or construct");
  cmd->add_option("--mode", r.mode, "Passed to pack: first, count or all (default: all; count with --mpi)");
  cmd->add_option("--seed", r.seed, "Passed to pack");
  cmd->add_option("--pack-arg", r.shard_args,
                  "Another argument of the shard command for every shard, e.g. --pack-arg=--max-depth=3 (repeatable)");
  cmd->add_option("--shards", plan.shards, "Number of shards = array tasks (required without --mpi)");
  cmd->add_option("--split-after", plan.split_after,
                  "Adaptive splitting: each shard (and each later work unit) stops after this many seconds; the merge "
                  "job splits what it left into --split-ways units, queued as a follow-up array (0 = never). A unit's "
                  "start-up (its first checkpoint) counts against it: give minutes, not milliseconds")
      ->capture_default_str();
  cmd->add_option("--split-ways", plan.split_ways, "Units an unfinished shard or unit becomes in the next round")
      ->capture_default_str();
  cmd->add_flag("--mpi", plan.mpi,
                "One MPI job instead of an array: `srun tilekit pack --mpi` with --ntasks ranks on --nodes nodes of "
                "one allocation (count mode; Open MPI with PMIx)");
  cmd->add_option("--nodes", plan.nodes, "--mpi: nodes of the allocation")->capture_default_str();
  cmd->add_option("--ntasks", plan.ntasks, "--mpi: MPI ranks (default: --nodes)");
  cmd->add_option("--launcher", plan.launcher,
                  "--mpi: how the ranks start: srun (srun --mpi=SRUN_MPI) or mpirun (Open MPI's, inside the "
                  "allocation)")
      ->capture_default_str();
  cmd->add_option("--srun-mpi", plan.srun_mpi, "--mpi with srun: Slurm's MPI plugin (srun --mpi=list)")
      ->capture_default_str();
  cmd->add_option("--cpus-per-task", plan.cpus_per_task, "Cores per shard (OMP_NUM_THREADS)")->capture_default_str();
  cmd->add_option("--time", plan.time, "Wall time of one attempt (Slurm format: M, H:M:S, D-H:M:S)")
      ->capture_default_str();
  cmd->add_option("--partition", plan.partition, "Slurm partition (default: the cluster's)");
  cmd->add_option("--checkpoint-every", plan.checkpoint_every, "Seconds between checkpoints")->capture_default_str();
  cmd->add_option("--signal-seconds", r.signal_seconds,
                  "USR1 this many seconds before the wall-time limit (default: 120, at most half the limit)");
  cmd->add_option("--max-requeues", plan.max_requeues, "Most requeues of one shard task")->capture_default_str();
  cmd->add_option("--merge-time", r.merge_time, "Wall time of the merge job (default: --time)");
  cmd->add_option("--run-dir", r.run_dir, "Run directory on the shared filesystem (default: ./tilekit-run-KINDC-MODE)");
  cmd->add_option("--job-name", r.job_name, "Slurm job name (default: tk-KINDC)");
  cmd->add_option("--tilekit", r.tilekit,
                  "The tilekit binary the jobs run (default: `tilekit` on PATH, else this one)");
  cmd->add_option("--sbatch-arg", plan.sbatch_args, "Another #SBATCH directive, e.g. --account=NAME (repeatable)");
  cmd->add_option("--sbatch", a->sbatch, "The sbatch command")->capture_default_str();
  cmd->add_flag("--dry-run", a->dry_run, "Print the scripts; write and queue nothing");
  add_json_flag(cmd, ctx);
  cmd->callback([a, cmd, &ctx] {
    // pack --mpi counts: the default mode of an MPI run
    if (a->request.settings.mpi && cmd->count("--mode") == 0) a->request.mode = "count";
    if (!a->request.settings.mpi && cmd->count("--shards") == 0)
      throw InputError("cluster submit: --shards is required (or --mpi for one MPI job)");
    with_cluster_errors_in_flags([&] { run_submit(*a, ctx); });
  });
}

void add_status(CLI::App& cluster, Context& ctx) {
  auto* cmd = cluster.add_subcommand("status", "Per-shard progress of a run, read from its run directory");
  auto a = std::make_shared<StatusArgs>();
  cmd->add_option("--run-dir", a->run_dir, "The run directory given to submit")->required();
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { with_cluster_errors_in_flags([&] { run_status(*a, ctx); }); });
}

struct SplitArgs {
  std::string run_dir;
  std::int64_t after_round = 0;
};

void add_split(CLI::App& cluster, Context& ctx) {
  auto* cmd = cluster.add_subcommand(
      "split",
      "A split run's next round (the merge job runs it): the shards now complete get their result, what is "
      "unfinished becomes the work units of the next array (units/round-R.tsv)");
  auto a = std::make_shared<SplitArgs>();
  cmd->add_option("--run-dir", a->run_dir, "The run directory given to submit")->required();
  cmd->add_option("--after-round", a->after_round, "The round that just ended (0 = the first array)")
      ->capture_default_str();
  add_json_flag(cmd, ctx);
  cmd->footer("Exit codes: 0 ok (units: 0 when nothing is left), 1 no run directory, 2 bad input.");
  cmd->callback([a, &ctx] {
    const auto run = cluster::read_run_file(fs::path(a->run_dir) / "run.json");
    if (!run) throw NotFound(fmt::format("{}: no run.json (not a `tilekit cluster submit` run directory)", a->run_dir));
    if (!run->split_ways) throw InputError(fmt::format("{}: not a split run (submit it with --split-after)", a->run_dir));
    if (a->after_round < 0 || a->after_round >= 1000)
      throw InputError(fmt::format("--after-round must be 0..999, got {}", a->after_round));
    const cluster::RoundPlan plan = cluster::next_round(a->run_dir, int(a->after_round), run->split_ways);
    emit(ctx, cluster::to_json(plan), [&] {
      std::string done;
      for (int s : plan.completed) done += fmt::format(" {}", s);
      fmt::print("after round {}: {} unfinished subproblems; shards complete now:{}\n", a->after_round,
                 plan.unfinished, done.empty() ? " none" : done);
      fmt::print("round {}: {} work units{}\n", plan.round, plan.units.size(),
                 plan.units.empty() ? "" : fmt::format(" in {}/units/round-{}.tsv", a->run_dir, plan.round));
    });
  });
}

void add_simulate(CLI::App& cluster, Context& ctx) {
  auto* cmd = cluster.add_subcommand(
      "simulate",
      "Replay a run's trace (pack --trace FILE) under scheduling policies on P workers: makespan against the ideal "
      "(work / P)");
  auto a = std::make_shared<SimulateArgs>();
  cmd->add_option("trace", a->traces, "Trace files (JSON lines of pack --trace; several: the ranks or shards of one run)")
      ->required();
  cmd->add_option("--workers", a->workers, "Worker counts P, comma-separated")->capture_default_str();
  cmd->add_option("--policy", a->policies,
                  "Policies, comma-separated: static (i mod P), pool (whole subproblems on demand), split (rounds of "
                  "arrays, a shard past its share leaves its open subtrees to the next), steal (pool, then the later "
                  "half of a busy worker's open pieces)")
      ->capture_default_str();
  cmd->add_option("--cost", a->cost, "The work of a unit: nodes (deterministic) or seconds (as measured)")
      ->capture_default_str();
  cmd->add_option("--rounds", a->rounds, "split: the most arrays (the last runs to the end)")->capture_default_str();
  add_json_flag(cmd, ctx);
  cmd->footer(
      "What a trace can model: pieces are not split further and latencies are 0, so each figure is an upper bound "
      "for its policy (cluster/schedule_sim.hpp).\nExit codes: 0 ok, 2 bad input (a trace that cannot be read).");
  cmd->callback([a, &ctx] { run_simulate(*a, ctx); });
}

}  // namespace

cluster::ShardCommandWords pack_shard_words() {
  return {.kind = "--kind",
          .colours = "--colors",
          .method = "--method",
          .mode = "--mode",
          .seed = "--seed",
          .window = "--window",
          .mpi = "--mpi",
          .per_shard = {"--shard", "--checkpoint", "--checkpoint-every", "--resume", "--db", "--threads", "--json",
                        "--portfolio-stats", "--mpi", "--part", "--time-limit"}};
}

void add_cluster_commands(CLI::App& app, Context& ctx) {
  auto* cluster = app.add_subcommand("cluster", "Run a sharded `tilekit pack` as a Slurm job array (or one MPI job)");
  cluster->require_subcommand(1);
  add_submit(*cluster, ctx);
  add_status(*cluster, ctx);
  add_simulate(*cluster, ctx);
  add_split(*cluster, ctx);
}

}  // namespace tilekit::cli
