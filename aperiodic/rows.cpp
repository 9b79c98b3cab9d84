#include "aperiodic/rows.hpp"

#include <algorithm>
#include <chrono>
#include <deque>
#include <map>
#include <string>
#include <unordered_map>

namespace tilekit {

PeriodicRows periodic_rows(const std::vector<WangTile>& input, int q, bool rows, std::size_t max_rows,
                           std::chrono::steady_clock::time_point deadline) {
  PeriodicRows res;
  if (q < 1) return res;
  // Columns are the rows of the transposed set (n <-> w, s <-> e).
  std::vector<WangTile> w;
  for (const WangTile& t : input) w.push_back(rows ? t : WangTile{t.w, t.s, t.e, t.n});
  std::map<Colour, std::size_t> sid;
  for (const WangTile& t : w) sid.emplace(t.w, sid.size()), sid.emplace(t.e, sid.size());
  const std::size_t ns = sid.size();
  std::vector<std::vector<std::size_t>> out(ns);  // tiles leaving each state
  for (std::size_t k = 0; k < w.size(); ++k) out[sid[w[k].w]].push_back(k);
  // back[k][u]: bitset of states v with a walk of exactly k steps from u to v.
  std::vector<std::vector<std::vector<bool>>> reach(std::size_t(q) + 1,
                                                    std::vector<std::vector<bool>>(ns, std::vector<bool>(ns, false)));
  for (std::size_t u = 0; u < ns; ++u) reach[0][u][u] = true;
  for (int k = 1; k <= q; ++k)
    for (std::size_t u = 0; u < ns; ++u)
      for (std::size_t e : out[u]) {
        std::size_t v = sid[w[e].e];
        for (std::size_t x = 0; x < ns; ++x)
          if (reach[std::size_t(k - 1)][v][x]) reach[std::size_t(k)][u][x] = true;
      }

  // Closed walks of length q, depth first, up to rotation: the first tile is the row's
  // least tile number (later tiles are >= it), and words are stored in their least
  // rotation. G_q commutes with rotating all rows, so its recurrent part is empty iff the
  // recurrent part of this quotient (vertices = words up to rotation) is empty: a
  // bi-infinite path in the quotient lifts by rotating each row into place.
  const bool narrow = std::all_of(w.begin(), w.end(), [](const WangTile& t) { return t.n < 256 && t.s < 256; });
  std::unordered_map<std::string, std::size_t> word_id;
  auto canonical = [&](const std::vector<Colour>& x) {
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
  };
  auto id = [&](const std::vector<Colour>& x) { return word_id.emplace(canonical(x), word_id.size()).first->second; };
  std::vector<std::pair<std::size_t, std::size_t>> edges;
  const std::size_t len = static_cast<std::size_t>(q);
  std::vector<Colour> north(len), south(len);
  std::vector<std::size_t> choice(len, 0), states(len + 1);
  bool overflow = false;  // too many rows, or the deadline passed: nothing is known
  std::size_t steps = 0;
  auto past_deadline = [&] {
    return deadline != std::chrono::steady_clock::time_point::max() && (++steps & 1023) == 0 &&
           std::chrono::steady_clock::now() >= deadline;
  };
  for (std::size_t first = 0; first < w.size() && !overflow; ++first) {
    const std::size_t home = sid[w[first].w], after = sid[w[first].e];
    if (!reach[len - 1][after][home]) continue;
    north[0] = w[first].n;
    south[0] = w[first].s;
    if (q == 1) {
      edges.emplace_back(id(north), id(south));
      continue;
    }
    int depth = 1;
    states[1] = after;
    choice[1] = 0;
    while (depth >= 1) {
      if (past_deadline()) {
        overflow = true;
        break;
      }
      const std::size_t d = std::size_t(depth);
      auto& opts = out[states[d]];
      bool advanced = false;
      while (choice[d] < opts.size()) {
        std::size_t e = opts[choice[d]++];
        if (e < first) continue;  // the first tile is the least of the row
        std::size_t v = sid[w[e].e];
        if (!reach[len - d - 1][v][home]) continue;
        north[d] = w[e].n;
        south[d] = w[e].s;
        if (d + 1 == len) {
          edges.emplace_back(id(north), id(south));
          if (edges.size() > max_rows) {
            overflow = true;
            break;
          }
          continue;
        }
        states[d + 1] = v;
        choice[d + 1] = 0;
        ++depth;
        advanced = true;
        break;
      }
      if (overflow) break;
      if (!advanced) --depth;
    }
  }
  if (overflow) return res;
  res.enumerated = true;
  res.rows = edges.size();
  // Recurrent part: repeatedly drop rows whose north word is no alive row's south word or
  // whose south word is no alive row's north word.
  const std::size_t nw = word_id.size();
  std::vector<std::size_t> as_north(nw, 0), as_south(nw, 0);
  for (auto [a, b] : edges) ++as_north[a], ++as_south[b];
  std::vector<std::vector<std::size_t>> by_north(nw), by_south(nw);
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
  for (bool a : alive) res.recurrent += a;
  return res;
}

}  // namespace tilekit
