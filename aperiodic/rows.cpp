#include "aperiodic/rows.hpp"

#include <algorithm>
#include <chrono>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>

namespace tilekit {
namespace {

// The row transducer of a Wang set: states are the E/W colours, one edge per tile (W -> E), and
// reach[k][u][v] says whether a walk of exactly k steps leads from u to v (k <= q).
struct RowTransducer {
  std::vector<WangTile> tiles;
  std::map<Colour, std::size_t> state;            // E/W colour -> state
  std::vector<std::vector<std::size_t>> leaving;  // tiles leaving each state
  std::vector<std::vector<std::vector<bool>>> reach;

  RowTransducer(const std::vector<WangTile>& input, int q, bool rows) {
    // Columns are the rows of the transposed set (n <-> w, s <-> e).
    for (const WangTile& t : input) tiles.push_back(rows ? t : WangTile{t.w, t.s, t.e, t.n});
    for (const WangTile& t : tiles) state.emplace(t.w, state.size()), state.emplace(t.e, state.size());
    const std::size_t ns = state.size();
    leaving.resize(ns);
    for (std::size_t k = 0; k < tiles.size(); ++k) leaving[state[tiles[k].w]].push_back(k);
    reach.assign(std::size_t(q) + 1, std::vector<std::vector<bool>>(ns, std::vector<bool>(ns, false)));
    for (std::size_t u = 0; u < ns; ++u) reach[0][u][u] = true;
    for (int k = 1; k <= q; ++k)
      for (std::size_t u = 0; u < ns; ++u)
        for (std::size_t e : leaving[u]) {
          std::size_t v = state[tiles[e].e];
          for (std::size_t x = 0; x < ns; ++x)
            if (reach[std::size_t(k - 1)][v][x]) reach[std::size_t(k)][u][x] = true;
        }
  }
};

// The word x in its least rotation, as a map key (one byte a colour when every colour fits).
std::string least_rotation_key(const std::vector<Colour>& x, bool narrow) {
  const std::size_t n = x.size();
  std::size_t best = 0;  // least rotation by direct comparison (q is small)
  for (std::size_t r = 1; r < n; ++r)
    for (std::size_t i = 0; i < n; ++i) {
      Colour a = x[(r + i) % n], b = x[(best + i) % n];
      if (a != b) {
        if (a < b) best = r;
        break;
      }
    }
  std::string key;
  key.reserve(narrow ? n : n * sizeof(Colour));
  for (std::size_t i = 0; i < n; ++i) {
    Colour c = x[(best + i) % n];
    if (narrow)
      key.push_back(char(c));
    else
      key.append(reinterpret_cast<const char*>(&c), sizeof c);
  }
  return key;
}

// The q-periodic rows as edges (north word -> south word) between words up to rotation.
struct RowGraph {
  std::vector<std::pair<std::size_t, std::size_t>> edges;
  std::size_t words = 0;
};

// Closed walks of length q, depth first, up to rotation: the first tile is the row's least tile
// number (later tiles are >= it), and words are stored in their least rotation. G_q commutes with
// rotating all rows, so its recurrent part is empty iff the recurrent part of this quotient
// (vertices = words up to rotation) is empty: a bi-infinite path in the quotient lifts by rotating
// each row into place. nullopt past max_rows rows or the deadline.
std::optional<RowGraph> enumerate_rows(RowTransducer& t, int q, std::size_t max_rows, const Deadline& deadline,
                                       bool catch_signals) {
  const std::vector<WangTile>& w = t.tiles;
  const bool narrow = std::all_of(w.begin(), w.end(), [](const WangTile& x) { return x.n < 256 && x.s < 256; });
  std::unordered_map<std::string, std::size_t> word_id;
  auto id = [&](const std::vector<Colour>& x) {
    return word_id.emplace(least_rotation_key(x, narrow), word_id.size()).first->second;
  };
  RowGraph g;
  const std::size_t len = static_cast<std::size_t>(q);
  std::vector<Colour> north(len), south(len);
  std::vector<std::size_t> choice(len, 0), states(len + 1);
  std::size_t steps = 0;
  StopToken stop;
  auto past_deadline = [&] {
    return (deadline.limited() || catch_signals) && (++steps & 1023) == 0 && poll_stop(stop, deadline, catch_signals);
  };
  for (std::size_t first = 0; first < w.size(); ++first) {
    const std::size_t home = t.state[w[first].w], after = t.state[w[first].e];
    if (!t.reach[len - 1][after][home]) continue;
    north[0] = w[first].n;
    south[0] = w[first].s;
    if (q == 1) {
      g.edges.emplace_back(id(north), id(south));
      continue;
    }
    int depth = 1;
    states[1] = after;
    choice[1] = 0;
    while (depth >= 1) {
      if (past_deadline()) return std::nullopt;
      const std::size_t d = std::size_t(depth);
      auto& opts = t.leaving[states[d]];
      bool advanced = false;
      while (choice[d] < opts.size()) {
        std::size_t e = opts[choice[d]++];
        if (e < first) continue;  // the first tile is the least of the row
        std::size_t v = t.state[w[e].e];
        if (!t.reach[len - d - 1][v][home]) continue;
        north[d] = w[e].n;
        south[d] = w[e].s;
        if (d + 1 == len) {
          g.edges.emplace_back(id(north), id(south));
          if (g.edges.size() > max_rows) return std::nullopt;
          continue;
        }
        states[d + 1] = v;
        choice[d + 1] = 0;
        ++depth;
        advanced = true;
        break;
      }
      if (!advanced) --depth;
    }
  }
  g.words = word_id.size();
  return g;
}

// Recurrent part: repeatedly drop rows whose north word is no alive row's south word or whose
// south word is no alive row's north word; the rows left.
std::size_t recurrent_rows(const RowGraph& g) {
  const auto& edges = g.edges;
  std::vector<std::size_t> as_north(g.words, 0), as_south(g.words, 0);
  for (auto [a, b] : edges) ++as_north[a], ++as_south[b];
  std::vector<std::vector<std::size_t>> by_north(g.words), by_south(g.words);
  for (std::size_t k = 0; k < edges.size(); ++k)
    by_north[edges[k].first].push_back(k), by_south[edges[k].second].push_back(k);
  std::vector<bool> alive(edges.size(), true);
  std::deque<std::size_t> dead;
  auto kill = [&](std::size_t k) {
    if (!alive[k]) return;
    alive[k] = false;
    dead.push_back(k);
  };
  for (std::size_t k = 0; k < edges.size(); ++k)
    if (as_south[edges[k].first] == 0 || as_north[edges[k].second] == 0) kill(k);
  while (!dead.empty()) {
    std::size_t k = dead.front();
    dead.pop_front();
    auto [a, b] = edges[k];
    if (--as_north[a] == 0)  // word a is no longer any row's north: rows below nothing end there
      for (std::size_t j : by_south[a]) kill(j);
    if (--as_south[b] == 0)
      for (std::size_t j : by_north[b]) kill(j);
  }
  return std::size_t(std::count(alive.begin(), alive.end(), true));
}

}  // namespace

PeriodicRows periodic_rows(const std::vector<WangTile>& input, int q, bool rows, std::size_t max_rows,
                           const Deadline& deadline, bool catch_signals) {
  PeriodicRows res;
  if (q < 1) return res;
  RowTransducer t(input, q, rows);
  std::optional<RowGraph> g = enumerate_rows(t, q, max_rows, deadline, catch_signals);
  if (!g) return res;  // too many rows, or the deadline passed: nothing is known
  res.enumerated = true;
  res.rows = g->edges.size();
  res.recurrent = recurrent_rows(*g);
  return res;
}

}  // namespace tilekit
