// tilekit aperiodic enumerate: the search over conversion chains (aperiodic/enumerate.hpp);
// tilekit aperiodic link: re-derives one chain from its source, step by step, to check each link.
#include <fmt/format.h>
#include <sys/resource.h>

#include <memory>

#include "aperiodic/canonical.hpp"
#include "aperiodic/conversion_graph.hpp"
#include "aperiodic/enumerate.hpp"
#include "aperiodic/enumerate_report.hpp"
#include "aperiodic/json.hpp"
#include "aperiodic/smallest.hpp"
#include "aperiodic/steps.hpp"
#include "aperiodic/table_checks.hpp"
#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/parse.hpp"
#include "base/signals.hpp"
#include "cli/cmd_aperiodic.hpp"
#include "cli/numeric_flags.hpp"
#include "cli/run_options.hpp"
#include "solver/run_trace.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit::cli {

namespace {

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct EnumerateArgs {
  EnumerateOptions o;
  RunOptions run = [] {  // threads, shard, time limit and checkpoints, into `o`
    RunOptions r;
    r.checkpoint_every = 60;
    return r;
  }();
  std::int64_t max_tiles = 60, batch = 8;  // checked here: CLI11 would wrap a negative size_t
  bool quiet = false;
  SmallestCheckOptions smallest;
  std::string record;  // --record FILE
  std::string trace;   // --trace FILE (solver/run_trace.hpp)
};

nlohmann::json link_json(const ChainLink& l) {
  return {{"set", l.hash},          {"step", l.step},
          {"label", l.label},       {"tiles", l.tiles},
          {"colors", l.colours},    {"kind", std::string(kind_name(l.kind))},
          {"argument", l.argument}, {"check", check_command(l.derivation)}};
}

nlohmann::json stored_chain_json(const StoredChain& c, const ConversionGraph& g) {
  nlohmann::json links = nlohmann::json::array();
  std::vector<std::string> steps;
  for (const GraphEdge& e : c.links) {
    steps.push_back(e.step);
    const GraphSet& s = g.sets.at(e.to);
    links.push_back({{"set", e.to},
                     {"step", e.step},
                     {"label", e.label},
                     {"tiles", s.tiles},
                     {"colors", s.colours},
                     {"kind", s.kind},
                     {"argument", e.argument},
                     {"check", check_command({c.source, steps})}});
  }
  return {{"source", c.source}, {"links", links}};
}

// The run's options from the flags (the sizes checked here: CLI11 would wrap a negative size_t).
EnumerateOptions enumerate_options(const EnumerateArgs& a) {
  if (a.max_tiles < 1) throw InputError(fmt::format("--max-tiles must be >= 1, got {}", a.max_tiles));
  if (a.batch < 1 || a.batch > 1000000) throw InputError(fmt::format("--batch must be between 1 and 1000000, got {}", a.batch));
  a.run.check_seconds();
  EnumerateOptions o = a.o;
  o.max_tiles = std::size_t(a.max_tiles);
  o.batch = std::size_t(a.batch);
  o.threads = int(a.run.resolved_threads());
  o.shard = a.run.shard_spec();
  o.time_limit = a.run.time_limit;
  o.checkpoint_path = a.run.checkpoint;
  o.checkpoint_every = a.run.checkpoint_every;
  o.resume_path = a.run.resume;
  o.progress = !a.quiet;
  o.catch_signals = true;
  return o;
}

nlohmann::json smallest_json(const SmallestFound& s) {
  nlohmann::json links = nlohmann::json::array();
  for (const ChainLink& l : s.chain) links.push_back(link_json(l));
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t k = 0; k < s.set.size(); ++k) list.push_back(s.set.file_colours(k));
  return {{"set", s.node.hash},
          {"tiles", s.node.tiles},
          {"colors", s.node.colours},
          {"source", s.node.root},
          {"chain", links},
          {"format", "nw ne sw se"},
          {"list", list},
          {"verify", verdict_text(s.check)}};
}

nlohmann::json enumerate_json(const EnumerateOptions& o, const EnumerateResult& r, const EnumerateReport& rep) {
  nlohmann::json per_depth = nlohmann::json::array(), per_source = nlohmann::json::array(),
                 leads = nlohmann::json::array();
  for (const auto& [d, c] : rep.depth)
    per_depth.push_back({{"depth", d}, {"reached", c.first}, {"expanded", c.second}});
  for (const SourceBest& s : rep.per_source)
    per_source.push_back(
        {{"source", s.source},
         {"reachable", s.reachable},
         {"expanded", rep.expanded_by_source.count(s.source) ? rep.expanded_by_source.at(s.source) : 0},
         {"smallest_corner", {{"set", s.best.hash}, {"tiles", s.best.tiles}, {"colors", s.best.colours}}},
         {"chain", stored_chain_json(s.chain, rep.graph)}});
  for (const EnumNode& n : rep.leads)
    leads.push_back(
        {{"set", n.hash}, {"tiles", n.tiles}, {"kind", std::string(kind_name(n.kind))}, {"decision", n.lead}});
  nlohmann::json j = {{"complete", r.complete},   {"interrupted", r.interrupted},
                      {"timed_out", r.timed_out}, {"resumed", r.resumed},
                      {"max_depth", o.max_depth}, {"max_tiles", o.max_tiles},
                      {"batches", r.batches},     {"expanded", r.expanded},
                      {"sets", r.nodes.size()},   {"edges", r.edges.size()},
                      {"digest", r.digest},       {"per_depth", per_depth},
                      {"per_source", per_source}, {"over_max_tiles", r.over_limit},
                      {"leads", leads},           {"checkpoints", r.checkpoints},
                      {"seconds", r.seconds},     {"total_seconds", r.total_seconds}};
  j["sources"] = o.sources.empty() ? published_enumeration_sources() : o.sources;
  j["shard"] = shard_text(o.shard);
  if (rep.smallest) j["smallest"] = smallest_json(*rep.smallest);
  if (!o.checkpoint_path.empty()) j["checkpoint"] = o.checkpoint_path;
  if (!o.db.empty()) j["db"] = o.db;
  return j;
}

void print_enumerate(const EnumerateOptions& o, const EnumerateResult& r, const EnumerateReport& rep,
                     const nlohmann::json& j) {
  fmt::print("enumerate: {} sets ({} expanded) and {} edges in {} batches, {}, {:.1f} s (digest {})\n", r.nodes.size(),
             r.expanded, r.edges.size(), r.batches,
             r.complete      ? "complete"
             : r.interrupted ? "interrupted"
                             : "stopped at the time limit",
             r.total_seconds, r.digest);
  for (const auto& [d, c] : rep.depth) fmt::print("  depth {}: {} sets reached, {} expanded\n", d, c.first, c.second);
  for (const SourceBest& s : rep.per_source)
    fmt::print("  {}: {} sets reachable, smallest corner set {} tiles\n", s.source, s.reachable, s.best.tiles);
  for (const auto& [op, n] : r.over_limit) fmt::print("  {} results over --max-tiles {}: {}\n", op, o.max_tiles, n);
  if (const auto& s = rep.smallest) {
    fmt::print("smallest corner set with a sound chain: {} tiles, {} colours ({}), verify: {}\n", s->node.tiles,
               s->node.colours, s->node.hash, verdict_text(s->check));
    for (const auto& l : j["smallest"]["chain"])
      fmt::print("  {} -> {} {} tiles [{}]: {}\n", l["step"].get<std::string>(), l["kind"].get<std::string>(),
                 l["tiles"].get<std::size_t>(), l["label"].get<std::string>(), l["check"].get<std::string>());
  }
  if (!rep.leads.empty())
    fmt::print("{} leads (unverified, not periodic or finite at k={})\n", rep.leads.size(), o.lead_max_k);
}

void run_enumerate(const EnumerateArgs& a, const Context& ctx) {
  EnumerateOptions o = enumerate_options(a);
  if (!a.trace.empty()) o.trace = std::make_shared<RunTrace>(a.trace);
  const double cpu0 = cpu_seconds();
  const EnumerateResult r = enumerate_conversions(o);
  const EnumerateReport rep = enumerate_report(r, a.smallest);
  nlohmann::json j = enumerate_json(o, r, rep);
  j["cpu_seconds"] = cpu_seconds() - cpu0;
  if (!a.record.empty() && !r.interrupted) {
    write_file_atomic(a.record, smallest_record(enumerate_command(o), r).dump(2) + "\n");
    j["record"] = a.record;
  }
  emit(ctx, j, [&] { print_enumerate(o, r, rep, j); });
  if (r.interrupted)
    throw Interrupted(interrupted_message(
        r.signal, o.checkpoint_path.empty() ? std::string("nothing kept (use --checkpoint F to resume later)")
                                            : "checkpoint written to " + o.checkpoint_path +
                                                  " (continue with --resume " + o.checkpoint_path + ")"));
}

struct LinkArgs {
  std::string source, steps;
  double time_limit = 0;
};

void run_link(const LinkArgs& a, const Context& ctx) {
  std::vector<std::string> steps;
  for (std::size_t p = 0; p <= a.steps.size() && !a.steps.empty();) {
    const auto q = a.steps.find(',', p);
    steps.push_back(a.steps.substr(p, q == std::string::npos ? std::string::npos : q - p));
    if (q == std::string::npos) break;
    p = q + 1;
  }
  TileSet last;
  bool timed_out = false;
  std::vector<ReplayedLink> links = replay_chain(a.source, steps, &last, Deadline(a.time_limit), &timed_out);
  nlohmann::json jl = nlohmann::json::array();
  bool sound = !timed_out;  // a chain cut short by the time limit proves nothing
  for (const ReplayedLink& l : links) {
    sound = sound && sound_label(l.label);
    jl.push_back({{"step", l.step}, {"label", l.label}, {"set", l.hash}, {"tiles", l.tiles}, {"colors", l.colours},
                  {"kind", std::string(kind_name(l.kind))}, {"argument", l.argument}});
  }
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t k = 0; k < last.size(); ++k) list.push_back(last.file_colours(k));
  const ReplayedLink& end = links.back();
  nlohmann::json j = {{"source", a.source}, {"links", jl},          {"set", end.hash}, {"tiles", end.tiles},
                      {"colors", end.colours}, {"kind", std::string(kind_name(end.kind))}, {"label", end.label},
                      {"sound", sound},     {"list", list}};
  j["complete"] = !timed_out;
  j["timed_out"] = timed_out;
  emit(ctx, j, [&] {
    for (const ReplayedLink& l : links)
      fmt::print("{} -> {} {} tiles, {} colours, set {} [{}]: {}\n", l.step, kind_name(l.kind), l.tiles, l.colours,
                 l.hash, l.label, l.argument);
    if (timed_out)
      fmt::print("time limit: {} of {} steps re-derived, the chain is not checked\n", links.size() - 1, steps.size());
    else
      fmt::print("chain {}: every link is {}\n", sound ? "sound" : "NOT sound",
                 sound ? "published, conjugate, lifts or prune" : "not of those labels");
    fmt::print("{}", format_tile_set_text(last));
  });
}

}  // namespace

void add_aperiodic_enumerate_commands(CLI::App* ap, Context& ctx) {
  auto a = std::make_shared<EnumerateArgs>();
  auto* cmd = ap->add_subcommand(
      "enumerate",
      "Search chains of conversions from the published aperiodic Wang sets for small corner sets with a sound chain");
  cmd->add_option("--source", a->o.sources,
                  "A published set to start from (repeatable; default: all of " +
                      fmt::format("{}", fmt::join(published_enumeration_sources(), ", ")) + ")");
  cmd->add_option("--max-depth", a->o.max_depth, "Longest chain expanded, in steps (default 3)");
  cmd->add_option("--max-tiles", a->max_tiles, "Sets with more tiles are counted, not kept (default 60)");
  cmd->add_option("--batch", a->batch, "Sets expanded per batch (default 8; part of the run's identity)");
  // Results never depend on the threads; the shard I/N continues only from the first steps whose
  // hash is I mod N; the time limit stops the run between batches.
  add_run_options(
      cmd, RunOptionFlags::Threads | RunOptionFlags::TimeLimit | RunOptionFlags::Checkpoint | RunOptionFlags::Shard,
      a->run);
  cmd->add_option("--lead-max-k", a->o.lead_max_k, "Decision of unverified results: strips up to k (default 6)");
  cmd->add_option("--operations", a->o.operations,
                  "Step operations tried, comma-separated (default: the standard ones; prune5, horizontal+prune5 and "
                  "merge-colours2 are the stronger prune and merges, aperiodic/steps.hpp)")
      ->delimiter(',');
  cmd->add_option("--db", a->o.db, "Store every set and conversion in this results database");
  cmd->add_option("--verify-period", a->smallest.verify_period,
                  "Torus periods searched on the smallest set (default 6)")
      ->check(CLI::Range(1, 16));
  cmd->add_option("--record", a->record,
                  "Write the least sound corner set's chain and this run's command and digest here (JSON, atomically): "
                  "what `aperiodic smallest` re-derives (aperiodic/data/smallest-chain.json)");
  cmd->add_option("--trace", a->trace,
                  "Write a trace of the run to this file (JSON lines, rewritten whole at every checkpoint and at the "
                  "end): every set expanded with its steps' seconds, for `tilekit cluster simulate --cost seconds`");
  cmd->add_flag("--quiet", a->quiet, "No progress output on stderr");
  add_json_flag(cmd, ctx);
  cmd->footer(
      "Exit codes: 0 ok (done: complete or time limit), 2 bad input or checkpoint, 3 interrupted (checkpoint written "
      "with --checkpoint).");
  cmd->callback([a, &ctx] { run_enumerate(*a, ctx); });

  auto link = std::make_shared<LinkArgs>();
  auto* lc = ap->add_subcommand("link", "Re-derive a chain from a published set, step by step, with each step's label");
  lc->add_option("SOURCE", link->source, "A published aperiodic Wang set (built-in name)")->required();
  lc->add_option("--steps", link->steps, "Steps separated by commas, e.g. prune,rot90:horizontal,to-wang (see enumerate)")
      ->required();
  lc->add_option("--time-limit", link->time_limit,
                 "Stop after this many seconds (0 = none): the links re-derived so far, complete: false")
      ->check(non_negative_seconds());
  add_json_flag(lc, ctx);
  lc->callback([link, &ctx] { run_link(*link, ctx); });
}

}  // namespace tilekit::cli
