#pragma once
// The sets and conversions a search stored (aperiodic/enumerate.hpp), as a graph: the queries
// behind `tilekit db smallest`, `tilekit db chains` and `tilekit aperiodic smallest --db`, and the
// per-source report of `aperiodic enumerate`. Built from a results database or from a search
// result, so both answer the same way.
#include <map>
#include <string>
#include <vector>

#include "aperiodic/enumerate.hpp"
#include "results/results_db.hpp"

namespace tilekit {

struct GraphSet {
  std::string hash, kind, source;  // source: the published name for a published set, else ""
  std::size_t tiles = 0;
  std::uint32_t colours = 0;
  std::string text;  // the canonical text (from a search) or the stored tile-set file
};

struct GraphEdge {
  std::string from, step, to, label, argument;
};

struct ConversionGraph {
  std::map<std::string, GraphSet> sets;  // by hash
  std::vector<GraphEdge> edges;          // sorted by (from, step)
};

// Tile sets whose source is "published: NAME" are the sources; every conversion is an edge.
ConversionGraph load_conversion_graph(const ResultsDb& db);
ConversionGraph conversion_graph(const EnumerateResult& r);

struct StoredChain {
  std::string source;
  std::vector<GraphEdge> links;  // from the source to the set
  std::vector<std::string> steps() const;
};

// Per published source: the least corner set (tiles, then colours, then hash) reachable by sound
// edges, with a shortest such chain to it; sources that reach none are left out.
struct SourceBest {
  std::string source;
  std::size_t reachable = 0;  // sets reachable by sound edges (the source included)
  GraphSet best;
  StoredChain chain;
};
std::vector<SourceBest> smallest_per_source(const ConversionGraph& g);

// The `limit` shortest sound chains (simple paths of sound edges) from a published source to
// `hash`, shortest first (Yen's k shortest loopless paths: the work is bounded by limit x chain
// length x edges, however dense the graph). NotFound when the graph has no such set.
std::vector<StoredChain> sound_chains_to(const ConversionGraph& g, const std::string& hash, std::size_t limit);

}  // namespace tilekit
