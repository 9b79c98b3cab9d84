#include "solver/search_stats.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

namespace tilekit {

const char* prune_name(Prune rule) {
  switch (rule) {
    case Prune::EmptyDomain:
      return "empty-domain";
    case Prune::ForwardCheck:
      return "forward-check";
    case Prune::ClassCheck:
      return "class-check";
    case Prune::NoSuchTile:
      return "no-such-tile";
    case Prune::TileUsed:
      return "tile-used";
    case Prune::OrbitUsed:
      return "orbit-used";
    case Prune::PatternCount:
      return "pattern-count";
    case Prune::Count_:
      break;
  }
  return "?";
}

SearchStats& SearchStats::operator+=(const SearchStats& o) {
  nodes += o.nodes;
  decisions += o.decisions;
  conflicts += o.conflicts;
  backtracks += o.backtracks;
  leaves += o.leaves;
  solutions += o.solutions;
  restarts += o.restarts;
  model += o.model;
  searches += o.searches;
  setup_seconds += o.setup_seconds;
  split_seconds += o.split_seconds;
  estimate_seconds += o.estimate_seconds;
  search_seconds += o.search_seconds;
  checkpoint_seconds += o.checkpoint_seconds;
  checkpoints += o.checkpoints;
  return *this;
}

void to_json(nlohmann::json& j, const SearchStats& s) {
  nlohmann::json prunes = nlohmann::json::object();
  for (std::size_t i = 0; i < kPruneRules; ++i) prunes[prune_name(Prune(i))] = s.model.prunes[i];
  j = {{"searches", s.searches},
       {"nodes", s.nodes},
       {"decisions", s.decisions},
       {"conflicts", s.conflicts},
       {"backtracks", s.backtracks},
       {"leaves", s.leaves},
       {"solutions", s.solutions},
       {"restarts", s.restarts},
       {"propagations", s.model.propagations},
       {"prunes", prunes},
       {"checkpoints", s.checkpoints},
       {"seconds",
        {{"setup", s.setup_seconds},
         {"split", s.split_seconds},
         {"estimate", s.estimate_seconds},
         {"search", s.search_seconds},
         {"checkpoint", s.checkpoint_seconds}}}};
}

std::string stats_table(const SearchStats& s) {
  std::string out = "statistics:\n";
  auto row = [&](const char* name, std::uint64_t v, const char* what) {
    out += fmt::format("  {:<22} {:>16}  {}\n", name, v, what);
  };
  auto time = [&](const char* name, double v) { out += fmt::format("  {:<22} {:>16.3f}  s\n", name, v); };
  row("searches", s.searches, "solve() calls");
  row("nodes", s.nodes, "");
  row("decisions", s.decisions, "values tried");
  row("conflicts", s.conflicts, "decisions refused");
  row("backtracks", s.backtracks, "");
  row("leaves", s.leaves, "");
  row("solutions", s.solutions, "");
  row("restarts", s.restarts, "");
  row("propagations", s.model.propagations, "domains revised");
  for (std::size_t i = 0; i < kPruneRules; ++i) {
    const std::string name = fmt::format("prune {}", prune_name(Prune(i)));
    row(name.c_str(), s.model.prunes[i], "");
  }
  row("checkpoints", s.checkpoints, "written");
  time("time setup", s.setup_seconds);
  time("time split", s.split_seconds);
  time("time estimate", s.estimate_seconds);
  time("time search", s.search_seconds);
  time("time checkpoint", s.checkpoint_seconds);
  return out;
}

}  // namespace tilekit
