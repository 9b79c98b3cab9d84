#pragma once
// What an `aperiodic enumerate` run found, read off its result: sets per depth and per source,
// the leads, and the least corner set with a sound chain, with its chain and an independent look
// at it (the torus route within a time limit: no periodic tiling with small periods).
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "aperiodic/conversion_graph.hpp"
#include "aperiodic/enumerate.hpp"
#include "aperiodic/verify.hpp"

namespace tilekit {

struct SmallestCheckOptions {
  int verify_period = 6;          // torus periods p, q <= this are searched on the smallest set
  double verify_time_limit = 10;  // seconds for that search (0: none)
};

struct SmallestFound {
  EnumNode node;                 // the least sound corner set (tiles, colours, hash)
  std::vector<ChainLink> chain;  // its first shortest sound chain from its source
  TileSet set;
  VerifyResult check;  // the torus route on it
};

struct EnumerateReport {
  ConversionGraph graph;                                     // the run's sets and edges as a graph
  std::map<int, std::pair<std::size_t, std::size_t>> depth;  // depth -> (sets reached, expanded)
  std::vector<SourceBest> per_source;                        // least corner set per published source
  std::map<std::string, std::size_t> expanded_by_source;
  std::vector<EnumNode> leads;  // unverified results the decision left unknown
  std::optional<SmallestFound> smallest;
};

EnumerateReport enumerate_report(const EnumerateResult& r, const SmallestCheckOptions& o);

}  // namespace tilekit
