#include "aperiodic/conversion_graph.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <deque>
#include <functional>
#include <set>
#include <tuple>

#include "aperiodic/steps.hpp"
#include "base/error.hpp"

namespace tilekit {

namespace {

void sort_edges(ConversionGraph& g) {
  std::sort(g.edges.begin(), g.edges.end(),
            [](const GraphEdge& a, const GraphEdge& b) { return std::tie(a.from, a.step) < std::tie(b.from, b.step); });
}

bool better(const GraphSet& a, const GraphSet& b) {
  return std::tie(a.tiles, a.colours, a.hash) < std::tie(b.tiles, b.colours, b.hash);
}

}  // namespace

std::vector<std::string> StoredChain::steps() const {
  std::vector<std::string> s;
  for (const GraphEdge& e : links) s.push_back(e.step);
  return s;
}

ConversionGraph load_conversion_graph(const ResultsDb& db) {
  ConversionGraph g;
  std::map<std::int64_t, std::string> hash_of;
  for (const TilesetRecord& t : db.list_tilesets(0)) {
    hash_of[t.id] = t.content_hash;
    GraphSet& s = g.sets[t.content_hash];
    s.hash = t.content_hash;
    s.kind = t.kind;
    s.tiles = t.tiles;
    s.colours = t.colours;
    s.text = t.text;
    if (t.source.rfind("published: ", 0) == 0) s.source = t.source.substr(11);
  }
  for (const ConversionRecord& c : db.list_conversions(0)) {
    std::string argument;
    if (c.details.is_object() && c.details.contains("argument") && c.details["argument"].is_string())
      argument = c.details["argument"].get<std::string>();
    g.edges.push_back({hash_of.at(c.source_set), c.method, hash_of.at(c.result_set), c.soundness, argument});
  }
  sort_edges(g);
  return g;
}

ConversionGraph conversion_graph(const EnumerateResult& r) {
  ConversionGraph g;
  for (const auto& [h, n] : r.nodes)
    g.sets[h] = {h, std::string(kind_name(n.kind)), n.label == "published" ? n.root : "", n.tiles, n.colours, n.text};
  for (const auto& [k, e] : r.edges) g.edges.push_back({e.from, e.step, e.to, e.label, e.argument});
  sort_edges(g);
  return g;
}

std::vector<SourceBest> smallest_per_source(const ConversionGraph& g) {
  std::map<std::string, std::vector<const GraphEdge*>> out;
  for (const GraphEdge& e : g.edges)
    if (sound_label(e.label)) out[e.from].push_back(&e);
  std::vector<SourceBest> result;
  for (const auto& [hash, set] : g.sets) {
    if (set.source.empty()) continue;
    // Breadth first: the first chain found to a set is a shortest one.
    std::map<std::string, const GraphEdge*> via;
    std::set<std::string> seen{hash};
    std::deque<std::string> todo{hash};
    SourceBest best;
    best.source = set.source;
    bool found = false;
    while (!todo.empty()) {
      const std::string h = todo.front();
      todo.pop_front();
      const GraphSet& s = g.sets.at(h);
      if (s.kind == "corner" && (!found || better(s, best.best))) best.best = s, found = true;
      for (const GraphEdge* e : out[h])
        if (seen.insert(e->to).second) via[e->to] = e, todo.push_back(e->to);
    }
    best.reachable = seen.size();
    if (!found) continue;
    best.chain.source = set.source;
    for (std::string h = best.best.hash; h != hash; h = via.at(h)->from) best.chain.links.push_back(*via.at(h));
    std::reverse(best.chain.links.begin(), best.chain.links.end());
    result.push_back(std::move(best));
  }
  std::sort(result.begin(), result.end(), [](const SourceBest& a, const SourceBest& b) { return a.source < b.source; });
  return result;
}

std::vector<StoredChain> sound_chains_to(const ConversionGraph& g, const std::string& hash, std::size_t limit) {
  if (!g.sets.count(hash)) throw NotFound(fmt::format("no tile set with content hash {} in the database", hash));
  std::map<std::string, std::vector<const GraphEdge*>> in;
  for (const GraphEdge& e : g.edges)
    if (sound_label(e.label)) in[e.to].push_back(&e);
  std::vector<StoredChain> chains;
  std::vector<GraphEdge> path;  // backwards from the target
  std::set<std::string> on_path{hash};
  // Depth-first backwards over sound edges; every simple path that ends at a published set.
  std::function<void(const std::string&)> walk = [&](const std::string& h) {
    if (chains.size() >= 100000) return;
    const GraphSet& s = g.sets.at(h);
    if (!s.source.empty()) {
      StoredChain c{s.source, {path.rbegin(), path.rend()}};
      chains.push_back(std::move(c));
    }
    for (const GraphEdge* e : in[h]) {
      if (on_path.count(e->from)) continue;
      on_path.insert(e->from);
      path.push_back(*e);
      walk(e->from);
      path.pop_back();
      on_path.erase(e->from);
    }
  };
  walk(hash);
  std::stable_sort(chains.begin(), chains.end(), [](const StoredChain& a, const StoredChain& b) {
    return std::make_tuple(a.links.size(), a.source) < std::make_tuple(b.links.size(), b.source);
  });
  if (chains.size() > limit) chains.resize(limit);
  return chains;
}

}  // namespace tilekit
