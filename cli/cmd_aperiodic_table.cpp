// tilekit aperiodic table: thesis Tables 8.1-8.7 recomputed, next to the printed values;
// every corner set of Table 8.1 (and its pruned form) verified; the smallest corner set
// whose aperiodicity follows from a sound chain. tilekit aperiodic smallest: that set alone.
#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <tuple>

#include "aperiodic/conversion_graph.hpp"
#include "aperiodic/json.hpp"
#include "aperiodic/smallest.hpp"
#include "aperiodic/table_checks.hpp"
#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/input.hpp"
#include "cli/cmd_aperiodic.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit::cli {

namespace {

struct TableArgs {
  TableOptions opts;
  TableCheckOptions checks;
  bool no_verify = false;
};

nlohmann::json size_json(const SetSize& s) {
  nlohmann::json j = {{"tiles", s.tiles}, {"colors", s.colours}, {"soundness", soundness_name(s.soundness)}};
  if (s.rotation) j["white"] = s.white, j["black"] = s.black;
  return j;
}

nlohmann::json tables_json(const TablesReport& r) {
  nlohmann::json tables = nlohmann::json::array();
  for (const Table& t : r.tables) {
    nlohmann::json cells = nlohmann::json::array();
    for (auto& row : t.cells) {
      nlohmann::json jr = nlohmann::json::array();
      for (auto& e : row)
        jr.push_back({{"ours", e.ours ? size_json(*e.ours) : nlohmann::json()},
                      {"text", e.ours ? format_size(*e.ours) : "missing"},
                      {"thesis", e.thesis},
                      {"differs", e.differs},
                      {"explained", e.explained},
                      {"note", e.note}});
      cells.push_back(jr);
    }
    tables.push_back({{"id", t.id}, {"title", t.title}, {"columns", t.columns}, {"rows", t.rows}, {"cells", cells}});
  }
  return {{"tables", tables}, {"largest_set", r.largest}};
}

nlohmann::json chain_json(const CornerSetCandidate& c) {
  nlohmann::json steps = nlohmann::json::array();
  for (auto& s : c.chain)
    steps.push_back({{"step", s.step},
                     {"set", s.set},
                     {"tiles", s.tiles},
                     {"colors", s.colours},
                     {"kind", s.kind},
                     {"label", s.label},
                     {"argument", s.argument},
                     {"check", check_command(s.derivation)}});
  return steps;
}

// The set, its chain (re-derived), the search that found it, and the independent verify.
nlohmann::json smallest_json(const CornerSetCandidate& c, const VerifyResult& v) {
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t k = 0; k < c.set.size(); ++k) list.push_back(c.set.file_colours(k));
  nlohmann::json j = {{"name", c.set.name()},    {"set", c.record.set},    {"source", c.source},
                      {"tiles", c.tiles},        {"colors", c.colours},    {"soundness", c.soundness},
                      {"chain", chain_json(c)},  {"verify", verify_json(v)}, {"format", "nw ne sw se"},
                      {"list", list}};
  if (!c.record.command.empty())  // a search's record (a database holds no command)
    j["found_by"] = {{"command", c.record.command}, {"digest", c.record.digest}, {"complete", c.record.complete},
                     {"expanded", c.record.expanded}, {"sets", c.record.sets}};
  return j;
}

void print_smallest(const CornerSetCandidate& c, const VerifyResult& v) {
  fmt::print("### The smallest corner set that is really aperiodic: {} tiles, {} colours (set {})\n\n", c.tiles,
             c.colours, c.record.set);
  if (!c.record.command.empty())
    fmt::print("Found by `{}` ({}, {} sets expanded, digest {}); re-derived now:\n", c.record.command,
               c.record.complete ? "complete" : "stopped early", c.record.expanded, c.record.digest);
  int k = 1;
  for (auto& s : c.chain)
    fmt::print("{}. {} -> {} {} tiles, {} colours [{}]: {}\n", k++, s.step, s.tiles, s.kind, s.colours, s.label,
               s.argument);
  fmt::print("Check: `aperiodic verify` finds {}.\n", verdict_text(v));
  fmt::print("Re-check each link: {}\n", [&] {
    std::vector<std::string> cmds;
    for (const ChainStep& s : c.chain) cmds.push_back("`" + check_command(s.derivation) + "`");
    return fmt::format("{}", fmt::join(cmds, "; "));
  }());
  fmt::print("For comparison: the thesis claims 44 (Fig. 8.6); Nurmi (Bridges 2016) published 30.\n\n");
  fmt::print("{}\n", format_tile_set_text(c.set));
}

void run_table_command(const TableArgs& a, const Context& ctx) {
  TableRun run = run_table(a.opts, a.checks, !a.no_verify);
  const TablesReport& r = run.tables;
  nlohmann::json j = tables_json(r);
  if (!a.no_verify) {
    nlohmann::json jc = nlohmann::json::array();
    for (const CellCheck& c : run.checks)
      jc.push_back({{"source", c.source},
                    {"method", c.method},
                    {"thesis", c.thesis},
                    {"tiles", c.tiles},
                    {"soundness", soundness_name(c.soundness)},
                    {"verdict", c.plain.verdict},
                    {"route", c.plain.route},
                    {"period", c.plain.period ? nlohmann::json::array({c.plain.period->first, c.plain.period->second})
                                              : nlohmann::json()},
                    {"pruned_tiles", c.pruned_tiles},
                    {"pruned_verdict", c.pruned.verdict},
                    {"status", c.status},
                    {"claim", c.claim}});
    j["verification"] = jc;
    j["smallest"] = smallest_json(*run.smallest, run.smallest_verify);
  }
  j["differences"] = r.differences;
  j["unexplained"] = r.unexplained;
  j["missing"] = r.missing;
  j["seconds"] = run.seconds;
  if (!a.no_verify) j["smallest_seconds"] = run.smallest_seconds;
  j["max_period"] = a.checks.verify.max_period;
  j["time_limit"] = a.checks.verify.time_limit;
  emit(ctx, j, [&] {
    fmt::print("{}", tables_markdown(r));
    if (!run.checks.empty()) {
      fmt::print(
          "### Verification of the Table 8.1 corner sets (torus search up to {}, then the transducer method for "
          "{} s where no chain is sound; pruned with R={})\n\n",
          a.checks.verify.max_period, a.checks.verify.time_limit, a.checks.prune);
      fmt::print(
          "| Wang set | method | tiles | soundness | verify | pruned tiles | verify (pruned) | thesis' claim |\n");
      fmt::print("|---|---|---|---|---|---|---|---|\n");
      for (const CellCheck& c : run.checks)
        fmt::print("| {} | {} | {} | {} | {} | {} | {} | {} |\n", c.source, c.method, c.tiles,
                   soundness_name(c.soundness), verdict_text(c.plain), c.pruned_tiles, verdict_text(c.pruned), c.claim);
      fmt::print("\n");
    }
    if (run.smallest) print_smallest(*run.smallest, run.smallest_verify);
    fmt::print(
        "{} entries differ from the thesis ({} not explained), {} are missing data; largest set {} tiles; {:.2f} s "
        "(and {:.2f} s for the smallest set)\n",
        r.differences, r.unexplained, r.missing, r.largest, run.seconds, run.smallest_seconds);
  });
}

// The least corner set over every published source's sound chains in a database, as a record.
RecordedChain stored_smallest(const std::string& path) {
  ResultsDb rdb(path, DbOpenOptions{.create = false, .read_only = true});
  const ConversionGraph g = load_conversion_graph(rdb);
  std::vector<SourceBest> all = smallest_per_source(g);
  if (all.empty()) throw NotFound(fmt::format("{} holds no corner set with a sound chain from a published source", path));
  const SourceBest& b = *std::min_element(all.begin(), all.end(), [](const SourceBest& x, const SourceBest& y) {
    return std::tie(x.best.tiles, x.best.colours, x.best.hash) < std::tie(y.best.tiles, y.best.colours, y.best.hash);
  });
  RecordedChain r;
  r.source = b.source;
  r.steps = b.chain.steps();
  r.set = b.best.hash;
  r.tiles = b.best.tiles;
  r.colours = b.best.colours;
  return r;
}

struct SmallestArgs {
  VerifyOptions vo;
  std::string out, db, record;
};

// The chain the recorded enumeration found (or the database's best), re-derived link by link
// (rederive_chain), then verified by the independent routes.
void run_smallest_command(const SmallestArgs& a, const Context& ctx) {
  if (!a.db.empty() && !a.record.empty()) throw InputError("give --db or --record, not both");
  const RecordedChain record = !a.db.empty()       ? stored_smallest(a.db)
                               : !a.record.empty() ? parse_smallest_record(read_input_file(a.record, "chain record", 1 << 20), a.record)
                                                   : embedded_smallest_record();
  const CornerSetCandidate best = rederive_chain(record);
  VerifyResult v = verify_for_table(best.set, a.vo, false);
  nlohmann::json j = smallest_json(best, v);
  if (!a.db.empty()) j["db"] = a.db;
  if (!a.out.empty()) write_file_atomic(a.out, format_tile_set_text(best.set)), j["out"] = a.out;
  emit(ctx, j, [&] { print_smallest(best, v); });
}

void add_smallest_command(CLI::App* ap, Context& ctx) {
  auto* cmd = ap->add_subcommand(
      "smallest", "The smallest corner set whose aperiodicity follows from a sound chain that `aperiodic enumerate` found");
  auto a = std::make_shared<SmallestArgs>();
  a->vo.time_limit = 5;
  cmd->add_option("--time-limit", a->vo.time_limit, "verify: transducer seconds at most (default 5)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--max-period", a->vo.max_period, "verify: the torus search up to this period (default 8)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--out", a->out, "Write the set as a tile-set file (atomically)");
  cmd->add_option("--db", a->db,
                  "Take the best sound chain in this database (what `aperiodic enumerate --db` stored) instead of "
                  "the recorded enumeration's (aperiodic/data/smallest-chain.json)");
  cmd->add_option("--record", a->record,
                  "Re-derive the chain of this record (what `aperiodic enumerate --record` wrote) instead of the "
                  "embedded one");
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_smallest_command(*a, ctx); });
}

}  // namespace

void add_aperiodic_table_command(CLI::App* ap, Context& ctx) {
  auto* cmd = ap->add_subcommand(
      "table", "Recompute thesis Tables 8.1-8.7, verify Table 8.1, report the smallest sound corner set");
  auto a = std::make_shared<TableArgs>();
  cmd->add_option("--levels", a->opts.levels, "Corner sets per iteration column (thesis: 4)")->check(CLI::Range(1, 6));
  a->checks.verify.time_limit = 5;
  cmd->add_option("--time-limit", a->checks.verify.time_limit, "verify: transducer seconds per set at most (default 5)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--max-period", a->checks.verify.max_period,
                  "verify: the torus search up to this period where the transducer reached less (default 8)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--prune", a->checks.prune, "Pruning radius for the pruned forms (default 3)")
      ->check(CLI::Range(0, 10));
  cmd->add_flag("--no-verify", a->no_verify, "Only the tables: no verify, no smallest-set report");
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_table_command(*a, ctx); });

  add_smallest_command(ap, ctx);
}

}  // namespace tilekit::cli
