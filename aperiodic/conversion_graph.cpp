#include "aperiodic/conversion_graph.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <deque>
#include <map>
#include <optional>
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

namespace {

// The sound edges as an index graph with one extra node S before every published set, so that
// a chain is a simple path from S to the target (its first, virtual, edge names the source).
struct SoundGraph {
  std::vector<std::string> hashes;            // node -> hash; node n = S
  std::vector<std::pair<int, int>> ends;      // edge -> (from, to); real edges first, then S's
  std::vector<const GraphEdge*> edge;         // real edges (nullptr for S's)
  std::vector<std::vector<int>> out;          // node -> edges, in (from, step) order
  int s = 0;
};

SoundGraph sound_graph(const ConversionGraph& g) {
  SoundGraph x;
  std::map<std::string, int> id;
  for (const auto& [h, set] : g.sets) id[h] = int(x.hashes.size()), x.hashes.push_back(h);
  x.s = int(x.hashes.size());
  x.out.resize(x.hashes.size() + 1);
  auto add = [&](int from, int to, const GraphEdge* e) {
    x.out[std::size_t(from)].push_back(int(x.ends.size()));
    x.ends.push_back({from, to});
    x.edge.push_back(e);
  };
  for (const GraphEdge& e : g.edges)
    if (sound_label(e.label) && id.count(e.from) && id.count(e.to)) add(id.at(e.from), id.at(e.to), &e);
  for (const auto& [h, set] : g.sets)
    if (!set.source.empty()) add(x.s, id.at(h), nullptr);
  return x;
}

// A shortest path (fewest edges) from `from` to `to` avoiding the blocked nodes and edges;
// breadth first in edge order, so the same graph gives the same path. Empty when there is none.
std::optional<std::vector<int>> shortest_path(const SoundGraph& x, int from, int to, const std::vector<char>& blocked_node,
                                              const std::set<int>& blocked_edge) {
  std::vector<int> via(x.out.size(), -1);
  std::vector<char> seen(x.out.size(), 0);
  std::deque<int> todo{from};
  seen[std::size_t(from)] = 1;
  while (!todo.empty() && !seen[std::size_t(to)]) {
    const int v = todo.front();
    todo.pop_front();
    for (int e : x.out[std::size_t(v)]) {
      const int w = x.ends[std::size_t(e)].second;
      if (seen[std::size_t(w)] || blocked_node[std::size_t(w)] || blocked_edge.count(e)) continue;
      seen[std::size_t(w)] = 1;
      via[std::size_t(w)] = e;
      todo.push_back(w);
    }
  }
  if (!seen[std::size_t(to)]) return std::nullopt;
  std::vector<int> path;
  for (int v = to; v != from; v = x.ends[std::size_t(via[std::size_t(v)])].first) path.push_back(via[std::size_t(v)]);
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace

// Yen's k shortest simple paths (Yen 1971, "Finding the K shortest loopless paths in a network"),
// with breadth-first search for the unit-length spur paths: at most `limit` paths, each found with
// at most (its length) searches of the graph, so the work is bounded by limit x length x edges
// however dense the graph is (every simple path of a dense graph is exponentially many).
std::vector<StoredChain> sound_chains_to(const ConversionGraph& g, const std::string& hash, std::size_t limit) {
  if (!g.sets.count(hash)) throw NotFound(fmt::format("no tile set with content hash {} in the database", hash));
  const SoundGraph x = sound_graph(g);
  const int target = int(std::find(x.hashes.begin(), x.hashes.end(), hash) - x.hashes.begin());
  auto nodes_of = [&](const std::vector<int>& path) {
    std::vector<int> n{x.s};
    for (int e : path) n.push_back(x.ends[std::size_t(e)].second);
    return n;
  };
  std::vector<std::vector<int>> found;
  std::set<std::pair<std::size_t, std::vector<int>>> candidates;  // by length, then edges
  std::vector<char> none(x.out.size(), 0);
  if (auto first = shortest_path(x, x.s, target, none, {}); first && limit > 0) found.push_back(*first);
  while (!found.empty() && found.size() < limit) {
    const std::vector<int>& last = found.back();
    const std::vector<int> on_last = nodes_of(last);
    for (std::size_t i = 0; i < last.size(); ++i) {
      const std::vector<int> root(last.begin(), last.begin() + std::ptrdiff_t(i));
      std::set<int> blocked_edge;
      for (const auto& p : found)
        if (p.size() > i && std::equal(root.begin(), root.end(), p.begin())) blocked_edge.insert(p[i]);
      std::vector<char> blocked_node(x.out.size(), 0);
      for (std::size_t k = 0; k < i; ++k) blocked_node[std::size_t(on_last[k])] = 1;
      if (auto spur = shortest_path(x, on_last[i], target, blocked_node, blocked_edge)) {
        std::vector<int> path = root;
        path.insert(path.end(), spur->begin(), spur->end());
        candidates.insert({path.size(), std::move(path)});
      }
    }
    if (candidates.empty()) break;
    found.push_back(candidates.begin()->second);
    candidates.erase(candidates.begin());
  }
  std::vector<StoredChain> chains;
  for (const auto& p : found) {
    StoredChain c;
    c.source = g.sets.at(x.hashes[std::size_t(x.ends[std::size_t(p.front())].second)]).source;
    for (std::size_t k = 1; k < p.size(); ++k) c.links.push_back(*x.edge[std::size_t(p[k])]);
    chains.push_back(std::move(c));
  }
  std::stable_sort(chains.begin(), chains.end(), [](const StoredChain& a, const StoredChain& b) {
    return std::make_tuple(a.links.size(), a.source) < std::make_tuple(b.links.size(), b.source);
  });
  return chains;
}

}  // namespace tilekit
