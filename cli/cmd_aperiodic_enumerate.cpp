// tilekit aperiodic enumerate: the search over conversion chains (aperiodic/enumerate.hpp);
// tilekit aperiodic link: re-derives one chain from its source, step by step, to check each link.
#include <fmt/format.h>
#include <sys/resource.h>

#include <memory>

#include "aperiodic/canonical.hpp"
#include "aperiodic/conversion_graph.hpp"
#include "aperiodic/enumerate.hpp"
#include "aperiodic/json.hpp"
#include "aperiodic/smallest.hpp"
#include "aperiodic/steps.hpp"
#include "aperiodic/table_checks.hpp"
#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/parse.hpp"
#include "cli/cmd_aperiodic.hpp"
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
  std::string shard = "0/1";
  std::int64_t max_tiles = 60, batch = 8;  // checked here: CLI11 would wrap a negative size_t
  bool quiet = false;
  int verify_period = 6;
  std::string record;  // --record FILE
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

void run_enumerate(const EnumerateArgs& a, const Context& ctx) {
  if (a.max_tiles < 1) throw InputError(fmt::format("--max-tiles must be >= 1, got {}", a.max_tiles));
  if (a.batch < 1 || a.batch > 1000000) throw InputError(fmt::format("--batch must be between 1 and 1000000, got {}", a.batch));
  EnumerateOptions o = a.o;
  o.max_tiles = std::size_t(a.max_tiles);
  o.batch = std::size_t(a.batch);
  const ShardSpec sh = parse_shard(a.shard);
  o.shard = sh.index;
  o.shards = sh.count;
  o.progress = !a.quiet;
  o.catch_signals = true;
  const double cpu0 = cpu_seconds();
  EnumerateResult r = enumerate_conversions(o);
  const ConversionGraph g = conversion_graph(r);

  // Sets by depth and by source; the least sound corner set overall.
  std::map<int, std::pair<std::size_t, std::size_t>> depth;  // reached, expanded
  std::map<std::string, std::size_t> expanded_by_source;
  const EnumNode* best = nullptr;
  nlohmann::json leads = nlohmann::json::array();
  for (const auto& [h, n] : r.nodes) {
    if (n.depth >= 0) {
      ++depth[n.depth].first;
      if (n.expanded >= 0) ++depth[n.depth].second, ++expanded_by_source[n.root];
      if (n.kind == TileKind::Corner &&
          (!best || std::tuple(n.tiles, n.colours, n.hash) < std::tuple(best->tiles, best->colours, best->hash)))
        best = &n;
    } else if (n.lead.rfind("unknown", 0) == 0) {
      leads.push_back({{"set", h}, {"tiles", n.tiles}, {"kind", std::string(kind_name(n.kind))}, {"decision", n.lead}});
    }
  }
  nlohmann::json per_depth = nlohmann::json::array();
  for (const auto& [d, c] : depth) per_depth.push_back({{"depth", d}, {"reached", c.first}, {"expanded", c.second}});
  nlohmann::json per_source = nlohmann::json::array();
  for (const SourceBest& s : smallest_per_source(g))
    per_source.push_back({{"source", s.source},
                          {"reachable", s.reachable},
                          {"expanded", expanded_by_source[s.source]},
                          {"smallest_corner", {{"set", s.best.hash}, {"tiles", s.best.tiles}, {"colors", s.best.colours}}},
                          {"chain", stored_chain_json(s.chain, g)}});
  nlohmann::json j = {{"complete", r.complete},
                      {"interrupted", r.interrupted},
                      {"timed_out", r.timed_out},
                      {"resumed", r.resumed},
                      {"sources", o.sources.empty() ? published_enumeration_sources() : o.sources},
                      {"max_depth", o.max_depth},
                      {"max_tiles", o.max_tiles},
                      {"shard", a.shard},
                      {"batches", r.batches},
                      {"expanded", r.expanded},
                      {"sets", r.nodes.size()},
                      {"edges", r.edges.size()},
                      {"digest", r.digest},
                      {"per_depth", per_depth},
                      {"per_source", per_source},
                      {"over_max_tiles", r.over_limit},
                      {"leads", leads},
                      {"checkpoints", r.checkpoints},
                      {"seconds", r.seconds},
                      {"total_seconds", r.total_seconds},
                      {"cpu_seconds", cpu_seconds() - cpu0}};
  std::optional<VerifyResult> check;
  if (best) {
    std::vector<ChainLink> chain = recorded_chain(r, best->hash);
    nlohmann::json links = nlohmann::json::array();
    for (const ChainLink& l : chain) links.push_back(link_json(l));
    TileSet set = set_from_canonical_text(best->text, "enumerate");
    nlohmann::json list = nlohmann::json::array();
    for (std::size_t k = 0; k < set.size(); ++k) list.push_back(set.file_colours(k));
    // An independent look at the result: no periodic tiling with small periods (the torus route).
    VerifyOptions vo;
    vo.time_limit = 10;
    vo.max_period = a.verify_period;
    check = verify_for_table(set, vo, false);
    j["smallest"] = {{"set", best->hash},   {"tiles", best->tiles},          {"colors", best->colours},
                     {"source", best->root}, {"chain", links},                {"format", "nw ne sw se"},
                     {"list", list},         {"verify", verdict_text(*check)}};
  }
  if (!a.record.empty() && !r.interrupted) {
    write_file_atomic(a.record, smallest_record(enumerate_command(o), r).dump(2) + "\n");
    j["record"] = a.record;
  }
  if (!o.checkpoint_path.empty()) j["checkpoint"] = o.checkpoint_path;
  if (!o.db.empty()) j["db"] = o.db;
  emit(ctx, j, [&] {
    fmt::print("enumerate: {} sets ({} expanded) and {} edges in {} batches, {}, {:.1f} s (digest {})\n",
               r.nodes.size(), r.expanded, r.edges.size(), r.batches,
               r.complete ? "complete" : r.interrupted ? "interrupted" : "stopped at the time limit", r.total_seconds,
               r.digest);
    for (const auto& [d, c] : depth) fmt::print("  depth {}: {} sets reached, {} expanded\n", d, c.first, c.second);
    for (const auto& s : per_source)
      fmt::print("  {}: {} sets reachable, smallest corner set {} tiles\n", s["source"].get<std::string>(),
                 s["reachable"].get<std::size_t>(), s["smallest_corner"]["tiles"].get<std::size_t>());
    for (const auto& [op, n] : r.over_limit) fmt::print("  {} results over --max-tiles {}: {}\n", op, o.max_tiles, n);
    if (best) {
      fmt::print("smallest corner set with a sound chain: {} tiles, {} colours ({}), verify: {}\n", best->tiles,
                 best->colours, best->hash, verdict_text(*check));
      for (const auto& l : j["smallest"]["chain"])
        fmt::print("  {} -> {} {} tiles [{}]: {}\n", l["step"].get<std::string>(), l["kind"].get<std::string>(),
                   l["tiles"].get<std::size_t>(), l["label"].get<std::string>(), l["check"].get<std::string>());
    }
    if (!leads.empty()) fmt::print("{} leads (unverified, not periodic or finite at k={})\n", leads.size(), o.lead_max_k);
  });
  if (r.interrupted)
    throw Interrupted(fmt::format("interrupted by signal {}; {}", r.signal,
                                  o.checkpoint_path.empty()
                                      ? std::string("no checkpoint (use --checkpoint F to resume later)")
                                      : "checkpoint written to " + o.checkpoint_path + " (continue with --resume " +
                                            o.checkpoint_path + ")"));
}

struct LinkArgs {
  std::string source, steps;
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
  std::vector<ReplayedLink> links = replay_chain(a.source, steps, &last);
  nlohmann::json jl = nlohmann::json::array();
  bool sound = true;
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
  emit(ctx, j, [&] {
    for (const ReplayedLink& l : links)
      fmt::print("{} -> {} {} tiles, {} colours, set {} [{}]: {}\n", l.step, kind_name(l.kind), l.tiles, l.colours,
                 l.hash, l.label, l.argument);
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
  cmd->add_option("--threads", a->o.threads, "Threads (default: all; results never depend on it)")
      ->check(CLI::Range(1, kMaxThreads));
  cmd->add_option("--shard", a->shard, "I/N: continue only from the first steps whose hash is I mod N");
  cmd->add_option("--lead-max-k", a->o.lead_max_k, "Decision of unverified results: strips up to k (default 6)");
  cmd->add_option("--time-limit", a->o.time_limit, "Seconds for this run; it stops between batches (0 = none)");
  cmd->add_option("--checkpoint", a->o.checkpoint_path, "Write checkpoints here (atomically)");
  cmd->add_option("--checkpoint-every", a->o.checkpoint_every, "Seconds between checkpoints (default 60; 0: every batch)");
  cmd->add_option("--resume", a->o.resume_path, "Continue the run this checkpoint holds");
  cmd->add_option("--db", a->o.db, "Store every set and conversion in this results database");
  cmd->add_option("--verify-period", a->verify_period, "Torus periods searched on the smallest set (default 6)")
      ->check(CLI::Range(1, 16));
  cmd->add_option("--record", a->record,
                  "Write the least sound corner set's chain and this run's command and digest here (JSON, atomically): "
                  "what `aperiodic smallest` re-derives (aperiodic/data/smallest-chain.json)");
  cmd->add_flag("--quiet", a->quiet, "No progress output on stderr");
  add_json_flag(cmd, ctx);
  cmd->footer(
      "Exit codes: 0 ok (done: complete or time limit), 2 bad input or checkpoint, 3 interrupted after a "
      "checkpoint.");
  cmd->callback([a, &ctx] { run_enumerate(*a, ctx); });

  auto link = std::make_shared<LinkArgs>();
  auto* lc = ap->add_subcommand("link", "Re-derive a chain from a published set, step by step, with each step's label");
  lc->add_option("SOURCE", link->source, "A published aperiodic Wang set (built-in name)")->required();
  lc->add_option("--steps", link->steps, "Steps separated by commas, e.g. prune,rot90:horizontal,to-wang (see enumerate)")
      ->required();
  add_json_flag(lc, ctx);
  lc->callback([link, &ctx] { run_link(*link, ctx); });
}

}  // namespace tilekit::cli
