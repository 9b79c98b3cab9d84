// tilekit db smallest | db chains: what `aperiodic enumerate` stored, read as a graph of
// conversions (aperiodic/conversion_graph.hpp): the least corner set per published source, and
// every sound chain to one set, each link with the command that re-derives it. Both report the
// chains as stored, without re-deriving them (`"rederived": false` in the JSON): a database is
// what some run wrote, so each link carries its check command, and `aperiodic smallest --db`
// re-derives the least set's chain before it reports it.
#include <fmt/format.h>

#include <memory>

#include "aperiodic/conversion_graph.hpp"
#include "cli/cmd_aperiodic.hpp"
#include "cli/command.hpp"
#include "results/results_db.hpp"

namespace tilekit::cli {

namespace {

struct ChainArgs {
  std::string db, hash;
  std::size_t limit = 20;
};

ResultsDb open_db(const std::string& path) {
  return ResultsDb(path.empty() ? ResultsDb::default_path() : path, DbOpenOptions{.create = false, .read_only = true});
}

nlohmann::json chain_json(const StoredChain& c, const ConversionGraph& g) {
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
                     {"check", check_command({c.source, steps})}});
  }
  return {{"source", c.source}, {"links", links}};
}

void print_chain(const StoredChain& c, const ConversionGraph& g) {
  fmt::print("  {}", c.source);
  for (const GraphEdge& e : c.links) fmt::print(" -[{} {}]-> {} ({} tiles)", e.step, e.label, e.to, g.sets.at(e.to).tiles);
  fmt::print("\n");
}

void run_db_smallest(const ChainArgs& a, const Context& ctx) {
  ConversionGraph g = load_conversion_graph(open_db(a.db));
  nlohmann::json list = nlohmann::json::array();
  std::vector<SourceBest> best = smallest_per_source(g);
  for (const SourceBest& b : best)
    list.push_back({{"source", b.source}, {"set", b.best.hash}, {"tiles", b.best.tiles}, {"colors", b.best.colours},
                    {"reachable", b.reachable}, {"chain", chain_json(b.chain, g)}});
  emit(ctx, {{"sources", list}, {"rederived", false}}, [&] {
    if (best.empty()) fmt::print("no corner set with a sound chain from a published source in this database\n");
    else fmt::print("(chains as stored, not re-derived: each link's check command re-derives it)\n");
    for (const SourceBest& b : best) {
      fmt::print("{}: {} tiles, {} colours ({}), {} sets reachable\n", b.source, b.best.tiles, b.best.colours,
                 b.best.hash, b.reachable);
      print_chain(b.chain, g);
    }
  });
}

void run_db_chains(const ChainArgs& a, const Context& ctx) {
  ConversionGraph g = load_conversion_graph(open_db(a.db));
  std::vector<StoredChain> chains = sound_chains_to(g, a.hash, a.limit);
  nlohmann::json list = nlohmann::json::array();
  for (const StoredChain& x : chains) list.push_back(chain_json(x, g));
  emit(ctx, {{"set", a.hash}, {"chains", list}, {"rederived", false}}, [&] {
    fmt::print("{} sound chain{} to {}\n", chains.size(), chains.size() == 1 ? "" : "s", a.hash);
    for (const StoredChain& x : chains) print_chain(x, g);
  });
}

}  // namespace

void add_db_chain_commands(CLI::App& db, Context& ctx) {
  {
    auto a = std::make_shared<ChainArgs>();
    auto* s = db.add_subcommand("smallest",
                                "Per published source, the least corner set reached by sound conversions, as stored "
                                "(not re-derived; `aperiodic smallest --db` re-derives the least one)");
    s->add_option("--db", a->db, "Results database file (default: $TILEKIT_DB, else the per-user data directory)");
    add_json_flag(s, ctx);
    s->callback([a, &ctx] { run_db_smallest(*a, ctx); });
  }
  auto a = std::make_shared<ChainArgs>();
  auto* c = db.add_subcommand("chains",
                              "The shortest sound chains of stored conversions from a published source to one set, as "
                              "stored (not re-derived: each link's check command re-derives it)");
  c->add_option("HASH", a->hash, "The set's content hash (tilesets.content_hash)")->required();
  c->add_option("--db", a->db, "Results database file (default: $TILEKIT_DB, else the per-user data directory)");
  c->add_option("--limit", a->limit, "At most this many chains, shortest first (default 20)")->check(CLI::Range(1, 100000));
  add_json_flag(c, ctx);
  c->callback([a, &ctx] { run_db_chains(*a, ctx); });
}

}  // namespace tilekit::cli
