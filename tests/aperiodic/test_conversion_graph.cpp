// The stored conversions as a graph (aperiodic/conversion_graph.hpp): the shortest sound chains
// to a set are the k shortest simple paths, found with bounded work even when the graph is dense.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "aperiodic/conversion_graph.hpp"
#include "base/error.hpp"

using namespace tilekit;

namespace {

// `n` sets, the first `published` of them published sources, every ordered pair linked by a
// sound edge (and, when `twice`, by a second step too).
ConversionGraph dense_graph(int n, int published, bool twice) {
  ConversionGraph g;
  auto h = [](int i) { return "set" + std::to_string(100 + i); };
  for (int i = 0; i < n; ++i)
    g.sets[h(i)] = {h(i), "corner", i < published ? "source-" + std::to_string(i) : "", std::size_t(20 + i), 4, ""};
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      if (a != b) {
        g.edges.push_back({h(a), "prune", h(b), "prune", ""});
        if (twice) g.edges.push_back({h(a), "rot90:prune", h(b), "conjugate", ""});
      }
  g.edges.push_back({h(0), "diagonal", h(n - 1), "unverified", ""});  // not sound: never a link
  return g;
}

// Every simple sound chain to `target`, by brute force: their lengths, sorted.
std::vector<std::size_t> all_chain_lengths(const ConversionGraph& g, const std::string& target) {
  std::vector<std::size_t> out;
  std::set<std::string> on;
  std::function<void(const std::string&, std::size_t)> walk = [&](const std::string& v, std::size_t len) {
    if (!g.sets.at(v).source.empty()) out.push_back(len);
    for (const GraphEdge& e : g.edges)
      if (e.to == v && e.label != "unverified" && !on.count(e.from)) {
        on.insert(e.from);
        walk(e.from, len + 1);
        on.erase(e.from);
      }
  };
  on.insert(target);
  walk(target, 0);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST(ConversionGraph, TheShortestChainsAreTheKShortestSimplePaths) {
  const ConversionGraph g = dense_graph(5, 2, true);
  const std::string target = "set104";
  const std::vector<std::size_t> all = all_chain_lengths(g, target);
  for (std::size_t limit : {std::size_t(1), std::size_t(7), std::size_t(40), all.size(), all.size() + 5}) {
    const std::vector<StoredChain> chains = sound_chains_to(g, target, limit);
    ASSERT_EQ(chains.size(), std::min(limit, all.size())) << limit;
    std::set<std::vector<std::string>> distinct;
    for (std::size_t i = 0; i < chains.size(); ++i) {
      EXPECT_EQ(chains[i].links.size(), all[i]) << limit << " " << i;  // the i-th shortest length
      ASSERT_FALSE(chains[i].links.empty());
      EXPECT_EQ(chains[i].links.back().to, target);
      std::set<std::string> visited{chains[i].links.front().from};
      std::vector<std::string> key{chains[i].source};
      for (const GraphEdge& e : chains[i].links) {
        EXPECT_TRUE(visited.insert(e.to).second) << "not simple";
        key.push_back(e.from + " " + e.step);
      }
      EXPECT_TRUE(distinct.insert(key).second) << "a chain twice";
    }
  }
  // A published target is its own chain of no links.
  EXPECT_TRUE(sound_chains_to(g, "set100", 1).front().links.empty());
  EXPECT_THROW(sound_chains_to(g, "nope", 3), NotFound);
}

TEST(ConversionGraph, ADenseGraphIsAnsweredWithBoundedWork) {
  // 16 sets, every pair linked twice: about 10^13 simple paths, which listing them all never ends.
  const ConversionGraph g = dense_graph(16, 1, true);
  const std::vector<StoredChain> chains = sound_chains_to(g, "set115", 20);
  ASSERT_EQ(chains.size(), 20u);
  EXPECT_EQ(chains.front().links.size(), 1u);
  for (std::size_t i = 1; i < chains.size(); ++i) EXPECT_LE(chains[i - 1].links.size(), chains[i].links.size());
}
