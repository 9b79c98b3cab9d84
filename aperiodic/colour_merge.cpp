// Colour merges of corner sets checked by a recovery map (argument in aperiodic/colour_merge.hpp).
#include "aperiodic/colour_merge.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <map>
#include <queue>
#include <set>
#include <stdexcept>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include "base/signals.hpp"

namespace tilekit {

namespace {

constexpr Colour kMaxColour = 0xffff;  // colours are packed 16 bits each into window keys

std::uint64_t key3(Colour nw, Colour ne, Colour sw) {
  return (std::uint64_t(nw) << 32) | (std::uint64_t(ne) << 16) | sw;
}
std::uint64_t key4(Colour nw, Colour ne, Colour sw, Colour se) {
  return (key3(nw, ne, sw) << 16) | se;
}

// The windows of a corner set, indexed for extending a patch of pegs one peg at a time (row-major).
struct Windows {
  std::unordered_set<std::uint64_t> all;
  std::vector<Colour> nw;                                        // every nw colour
  std::unordered_map<Colour, std::vector<Colour>> ne_of, sw_of;  // by nw
  std::unordered_map<std::uint64_t, std::vector<Colour>> se_of;  // by (nw, ne, sw)

  explicit Windows(const std::vector<CornerTile>& tiles) {
    for (const CornerTile& t : tiles) {
      all.insert(key4(t.nw, t.ne, t.sw, t.se));
      nw.push_back(t.nw);
      ne_of[t.nw].push_back(t.ne);
      sw_of[t.nw].push_back(t.sw);
      se_of[key3(t.nw, t.ne, t.sw)].push_back(t.se);
    }
    auto unique = [](std::vector<Colour>& v) {
      std::sort(v.begin(), v.end());
      v.erase(std::unique(v.begin(), v.end()), v.end());
    };
    unique(nw);
    for (auto* m : {&ne_of, &sw_of})
      for (auto& [c, v] : *m) unique(v);
    for (auto& [k, v] : se_of) unique(v);
  }
  bool has(Colour a, Colour b, Colour c, Colour d) const { return all.count(key4(a, b, c, d)) > 0; }
};

constexpr int kMaxSide = 2 * kMaxMergeRadius + 2 + 2 * kMaxMergeMargin;
using Patch = std::array<std::array<Colour, kMaxSide>, kMaxSide>;

// Calls f(patch) for every h x w patch of pegs (h, w in 2..kMaxSide) whose every window is a tile;
// stops and returns false as soon as f does.
template <class F>
bool for_each_patch(const Windows& win, int h, int w, F&& f) {
  static const std::vector<Colour> none;
  auto get = [](const auto& m, auto k) -> const std::vector<Colour>& {
    auto it = m.find(k);
    return it == m.end() ? none : it->second;
  };
  Patch p{};
  auto place = [&](auto& self, int i) -> bool {
    if (i == h * w) return f(p);
    const int r = i / w, c = i % w;
    const std::vector<Colour>& options = r == 0 && c == 0 ? win.nw
                                         : r == 0         ? get(win.ne_of, p[0][c - 1])
                                         : c == 0         ? get(win.sw_of, p[r - 1][0])
                                                  : get(win.se_of, key3(p[r - 1][c - 1], p[r - 1][c], p[r][c - 1]));
    for (Colour v : options) {
      p[r][c] = v;
      if (!self(self, i + 1)) return false;
    }
    return true;
  };
  return place(place, 0);
}

using Neighbourhood = std::vector<Colour>;  // (2 radius + 1)^2 pegs, row-major

// V of every neighbourhood of the merged set whose centre is the merged colour: bit 1 when a
// patch of the source with centre `kept` (the middle of a valid patch `margin` pegs wider on each
// side) maps onto it, bit 2 for centre `merged`.
std::map<Neighbourhood, unsigned> centre_colours(const std::vector<CornerTile>& source, Colour kept, Colour merged,
                                                 int radius, int margin) {
  std::map<Neighbourhood, unsigned> v;
  auto pi = [&](Colour c) { return c == merged ? kept : c; };
  const int n = 2 * radius + 1, m = margin;
  const std::size_t mid = std::size_t(m + radius);
  for_each_patch(Windows(source), n + 2 * m, n + 2 * m, [&](const Patch& p) {
    if (p[mid][mid] != kept && p[mid][mid] != merged) return true;
    Neighbourhood q;
    for (int r = m; r < m + n; ++r)
      for (int c = m; c < m + n; ++c) q.push_back(pi(p[std::size_t(r)][std::size_t(c)]));
    v[q] |= p[mid][mid] == kept ? 1u : 2u;
    return true;
  });
  return v;
}

// phi at peg (r, c) of a patch of the merged set; *bits is V (0 where it is empty).
template <class Grid>
Colour recovered(const Grid& g, int r, int c, Colour kept, Colour merged, const std::map<Neighbourhood, unsigned>& v,
                 int radius, unsigned* bits) {
  *bits = 1;
  if (g[r][c] != kept) return g[r][c];
  Neighbourhood q;
  for (int i = -radius; i <= radius; ++i)
    for (int j = -radius; j <= radius; ++j) q.push_back(g[r + i][c + j]);
  auto it = v.find(q);
  *bits = it == v.end() ? 0 : it->second;
  return *bits & 1u ? kept : merged;
}

// Tiles left after merging `merged` into `kept`, unchecked.
std::size_t merged_size(const std::vector<CornerTile>& tiles, Colour kept, Colour merged) {
  auto pi = [&](Colour c) { return c == merged ? kept : c; };
  std::set<CornerTile> out;
  for (const CornerTile& t : tiles) out.insert({pi(t.ne), pi(t.se), pi(t.sw), pi(t.nw)});
  return out.size();
}

std::vector<Colour> colours_of(const std::vector<CornerTile>& tiles) {
  std::set<Colour> s;
  for (const CornerTile& t : tiles) s.insert({t.nw, t.ne, t.sw, t.se});
  return {s.begin(), s.end()};
}

}  // namespace

std::optional<std::vector<CornerTile>> merge_colours(const std::vector<CornerTile>& tiles, Colour kept, Colour merged,
                                                     bool allow_lifts, int radius, int margin, bool* conjugate,
                                                     std::size_t max_patches) {
  if (kept == merged || radius < 1 || radius > kMaxMergeRadius || margin < 0 || margin > kMaxMergeMargin)
    return std::nullopt;
  for (const CornerTile& t : tiles)
    if (std::max({t.nw, t.ne, t.sw, t.se}) > kMaxColour) return std::nullopt;
  auto pi = [&](Colour c) { return c == merged ? kept : c; };
  std::vector<CornerTile> out;
  for (const CornerTile& t : tiles) out.push_back({pi(t.ne), pi(t.se), pi(t.sw), pi(t.nw)});
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());

  const Windows source(tiles);
  const std::map<Neighbourhood, unsigned> v = centre_colours(tiles, kept, merged, radius, margin);
  bool unique = true;
  std::size_t patches = 0;
  const int side = 2 * radius + 2 + 2 * margin;
  std::set<Neighbourhood> checked;
  const bool ok = for_each_patch(Windows(out), side, side, [&](const Patch& big) {
    if (++patches > max_patches) return false;
    Patch p{};
    Neighbourhood centre;
    for (int r = 0; r < 2 * radius + 2; ++r)
      for (int c = 0; c < 2 * radius + 2; ++c)
        centre.push_back(p[std::size_t(r)][std::size_t(c)] = big[std::size_t(r + margin)][std::size_t(c + margin)]);
    if (margin > 0 && !checked.insert(centre).second) return true;
    std::array<std::array<Colour, 2>, 2> w{};
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 2; ++c) {
        unsigned bits = 0;
        w[std::size_t(r)][std::size_t(c)] = recovered(p, radius + r, radius + c, kept, merged, v, radius, &bits);
        if (bits == 0) return false;
        if (bits == 3) {
          unique = false;
          if (!allow_lifts) return false;
        }
      }
    return source.has(w[0][0], w[0][1], w[1][0], w[1][1]);
  });
  if (!ok) return std::nullopt;
  if (conjugate) *conjugate = unique;
  return out;
}

std::string MergeSearch::argument() const {
  if (merges.empty()) return "no colour merge applies";
  std::vector<std::string> m;
  for (const ColourMerge& x : merges)
    m.push_back(
        fmt::format("{}+{} (r={}, m={}{})", x.kept, x.merged, x.radius, x.margin, x.conjugate ? "" : ", lifts"));
  return fmt::format(
      "colours merged {}: the pegs within radius r of each peg give back its colour, checked on "
      "every (2r+2)^2 patch of the merged set in the middle of a valid patch m pegs wider on each side{}",
      fmt::join(m, ", "),
      conjugate ? " (a unique colour: a conjugacy)" : " (a choice where two fit: the tilings lift)");
}

MergeSearch least_colour_merge(const std::vector<CornerTile>& tiles, bool allow_lifts, int max_radius, int max_margin,
                               std::size_t max_expansions) {
  struct Node {
    std::vector<CornerTile> tiles;
    std::size_t parent;
    ColourMerge how;
    bool conjugate;
    std::size_t colours;
  };
  std::vector<CornerTile> start = tiles;
  std::sort(start.begin(), start.end());
  start.erase(std::unique(start.begin(), start.end()), start.end());
  std::vector<Node> nodes{{start, 0, {}, true, colours_of(start).size()}};
  std::set<std::vector<CornerTile>> seen{start};
  // Best first by (tiles, colours, order of discovery): deterministic. A merge keeps the lesser
  // colour, so one partition of the colours is one set. A larger radius is tried only for merges
  // that save tiles at once (its check enumerates far more patches).
  using Key = std::tuple<std::size_t, std::size_t, std::size_t>;
  std::priority_queue<Key, std::vector<Key>, std::greater<>> open;
  open.push({start.size(), nodes[0].colours, 0});
  for (std::size_t expanded = 0; !open.empty() && expanded < max_expansions; ++expanded) {
    const std::size_t i = std::get<2>(open.top());
    open.pop();
    const std::vector<Colour> cs = colours_of(nodes[i].tiles);
    for (std::size_t a = 0; a < cs.size(); ++a)
      for (std::size_t b = a + 1; b < cs.size(); ++b) {
        throw_if_interrupted();  // a whole search takes minutes on a large set
        bool conj = false;
        std::optional<std::vector<CornerTile>> r;
        // (radius, margin) pairs, cheapest check first; past the first only for merges that save tiles.
        const bool saves = merged_size(nodes[i].tiles, cs[a], cs[b]) < nodes[i].tiles.size();
        ColourMerge how{cs[a], cs[b], 1, 0, false};
        for (int sum = 1; !r && (sum == 1 || saves) && sum <= max_radius + max_margin; ++sum)
          for (int radius = std::min(sum, max_radius); radius >= 1 && sum - radius <= max_margin; --radius) {
            if ((r = merge_colours(nodes[i].tiles, cs[a], cs[b], allow_lifts, radius, sum - radius, &conj))) {
              how.radius = radius;
              how.margin = sum - radius;
              break;
            }
          }
        if (!r || !seen.insert(*r).second) continue;
        how.conjugate = conj;
        const std::size_t colours = colours_of(*r).size();
        open.push({r->size(), colours, nodes.size()});
        nodes.push_back({std::move(*r), i, how, nodes[i].conjugate && conj, colours});
      }
  }
  std::size_t best = 0;
  for (std::size_t i = 1; i < nodes.size(); ++i)
    if (std::pair(nodes[i].tiles.size(), nodes[i].colours) < std::pair(nodes[best].tiles.size(), nodes[best].colours))
      best = i;
  MergeSearch out;
  out.tiles = nodes[best].tiles;
  out.conjugate = nodes[best].conjugate;
  out.sets = nodes.size();
  for (std::size_t i = best; i != 0; i = nodes[i].parent) out.merges.push_back(nodes[i].how);
  std::reverse(out.merges.begin(), out.merges.end());
  return out;
}

std::vector<std::vector<Colour>> recover_pegs(const std::vector<CornerTile>& source, Colour kept, Colour merged,
                                              int radius, int margin, const std::vector<std::vector<Colour>>& pegs) {
  const std::map<Neighbourhood, unsigned> v = centre_colours(source, kept, merged, radius, margin);
  const std::size_t rad = std::size_t(radius + margin);
  std::vector<std::vector<Colour>> out;
  for (std::size_t r = rad; r + rad < pegs.size(); ++r) {
    out.emplace_back();
    for (std::size_t c = rad; c + rad < pegs[r].size(); ++c) {
      unsigned bits = 0;
      Colour x = recovered(pegs, int(r), int(c), kept, merged, v, radius, &bits);
      if (bits == 0) throw std::invalid_argument(fmt::format("no colour fits the peg at ({}, {})", r, c));
      out.back().push_back(x);
    }
  }
  return out;
}

}  // namespace tilekit
