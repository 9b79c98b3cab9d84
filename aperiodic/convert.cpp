// The Wang <-> corner conversions of thesis ch. 8, one short function per construction
// (translations 8.2, rotation 8.3, subdivision 8.4, corner -> Wang pairs) and the dispatcher
// over them. Kept in one file (about 460 lines, over the usual 400) because they share the
// colour maps and block iterators at the top, and reading them side by side is how a reader
// checks each against the thesis.
#include "aperiodic/convert.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <unordered_map>

#include "aperiodic/translation_lift.hpp"
#include "base/error.hpp"

namespace tilekit {

namespace {

using Map = std::vector<Colour>;
constexpr Colour kNo = Conversion::kNoColour;

// Dense relabelling of the colours in `used` (0..k-1, increasing): map[old] = new.
Map dense_map(const std::vector<Colour>& used) {
  Colour top = 0;
  for (Colour c : used) top = std::max(top, c + 1);
  Map m(top, kNo);
  for (Colour c : used) m[c] = 0;
  Colour next = 0;
  for (Colour& v : m)
    if (v != kNo) v = next++;
  return m;
}

Map horizontal_map(const std::vector<WangTile>& w) {
  std::vector<Colour> used;
  for (auto& t : w) used.push_back(t.n), used.push_back(t.s);
  return dense_map(used);
}

Map vertical_map(const std::vector<WangTile>& w) {
  std::vector<Colour> used;
  for (auto& t : w) used.push_back(t.e), used.push_back(t.w);
  return dense_map(used);
}

std::uint32_t count_mapped(const Map& m) {
  return std::uint32_t(std::count_if(m.begin(), m.end(), [](Colour c) { return c != kNo; }));
}

// Valid 2x2 blocks of Wang tiles (a b / c d): a.e == b.w, c.e == d.w, a.s == c.n,
// b.s == d.n (thesis 8.3.1: "a single tile for each valid two by two square configuration").
template <class F>
void for_each_block(const std::vector<WangTile>& w, F&& f) {
  std::unordered_map<Colour, std::vector<std::uint32_t>> by_w, by_n;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> by_nw;
  for (std::uint32_t k = 0; k < w.size(); ++k) {
    by_w[w[k].w].push_back(k);
    by_n[w[k].n].push_back(k);
    by_nw[(std::uint64_t(w[k].n) << 32) | w[k].w].push_back(k);
  }
  static const std::vector<std::uint32_t> none;
  auto get = [](auto& m, auto key) -> const std::vector<std::uint32_t>& {
    auto it = m.find(key);
    return it == m.end() ? none : it->second;
  };
  for (std::uint32_t a = 0; a < w.size(); ++a)
    for (std::uint32_t b : get(by_w, w[a].e))
      for (std::uint32_t c : get(by_n, w[a].s))
        for (std::uint32_t d : get(by_nw, (std::uint64_t(w[b].s) << 32) | w[c].e)) f(a, b, c, d);
}

template <class T>
void sort_unique(std::vector<T>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

void finish_corner(Conversion& c) {
  c.kind = TileKind::Corner;
  c.colours = c.horizontal_colours = c.vertical_colours = corner_colours(c.corner);
}

void check_source(std::size_t n, const char* what) {
  if (n == 0) throw InputError(fmt::format("{}: the source tile set has no tiles", what));
}

// Horizontal translation (thesis 8.3.2, Fig. 8.8a): the corner lattice is shifted half a
// tile sideways, so its pegs sit on the midpoints of the horizontal (N/S) Wang edges. A
// corner tile is a horizontally matching pair (a, b), a.e == b.w, and keeps
// (nw, ne, sw, se) = (a.n, b.n, a.s, b.s); the E/W colours are forgotten.
// Vertical translation is the transpose: pairs a over c (a.s == c.n) keep
// (nw, ne, sw, se) = (a.w, a.e, c.w, c.e).
Conversion translation(const std::vector<WangTile>& w, bool horizontal, std::size_t max_lift_states) {
  Conversion c;
  c.method = horizontal ? ConversionMethod::Horizontal : ConversionMethod::Vertical;
  std::unordered_map<Colour, std::vector<std::uint32_t>> by_first;  // by W (horizontal) or N (vertical)
  for (std::uint32_t k = 0; k < w.size(); ++k) by_first[horizontal ? w[k].w : w[k].n].push_back(k);
  if (horizontal) {
    c.hmap = horizontal_map(w);
    for (auto& a : w)
      if (auto it = by_first.find(a.e); it != by_first.end())
        for (std::uint32_t kb : it->second) {
          const WangTile& b = w[kb];
          c.corner.push_back({c.hmap[b.n], c.hmap[b.s], c.hmap[a.s], c.hmap[a.n]});
        }
  } else {
    c.vmap = vertical_map(w);
    for (auto& a : w)
      if (auto it = by_first.find(a.s); it != by_first.end())
        for (std::uint32_t kd : it->second) {
          const WangTile& d = w[kd];
          c.corner.push_back({c.vmap[a.e], c.vmap[d.e], c.vmap[d.w], c.vmap[a.w]});
        }
  }
  sort_unique(c.corner);
  finish_corner(c);
  if (max_lift_states == 0) {
    c.soundness = Soundness::Unverified;
    c.argument = "lift check skipped";
    return c;
  }
  // Soundness: decided by the row (column) automata of aperiodic/translation_lift.hpp.
  LiftReport lift = translation_lift(w, horizontal, max_lift_states);
  if (lift.lifts && lift.injective) {
    c.soundness = Soundness::Conjugate;
  } else if (lift.lifts) {
    c.soundness = Soundness::Lifts;
  } else {
    c.soundness = Soundness::Unverified;
  }
  c.argument = lift.detail;
  return c;
}

}  // namespace

std::string soundness_name(Soundness s) {
  switch (s) {
    case Soundness::Conjugate: return "conjugate";
    case Soundness::Lifts: return "lifts";
    case Soundness::Unverified: return "unverified";
    case Soundness::Periodic: return "periodic";
  }
  return "?";
}

std::string method_name(ConversionMethod m) {
  switch (m) {
    case ConversionMethod::Diagonal: return "diagonal";
    case ConversionMethod::Horizontal: return "horizontal";
    case ConversionMethod::Vertical: return "vertical";
    case ConversionMethod::Rotation: return "rotation";
    case ConversionMethod::Subdivision: return "subdivision";
    case ConversionMethod::ToWang: return "to-wang";
  }
  return "?";
}

ConversionMethod parse_method(const std::string& name) {
  for (auto m : {ConversionMethod::Diagonal, ConversionMethod::Horizontal, ConversionMethod::Vertical,
                 ConversionMethod::Rotation, ConversionMethod::Subdivision, ConversionMethod::ToWang})
    if (method_name(m) == name) return m;
  throw InputError(fmt::format(
      "unknown conversion method '{}' (expected diagonal, horizontal, vertical, rotation, subdivision or to-wang)", name));
}

std::vector<WangTile> relabel_wang(const std::vector<WangTile>& tiles) {
  Map h = horizontal_map(tiles), v = vertical_map(tiles);
  std::vector<WangTile> out;
  out.reserve(tiles.size());
  for (auto& t : tiles) out.push_back({h[t.n], v[t.e], h[t.s], v[t.w]});
  return out;
}

std::vector<CornerTile> relabel_corner(const std::vector<CornerTile>& tiles) {
  std::vector<Colour> used;
  for (auto& t : tiles) used.insert(used.end(), {t.ne, t.se, t.sw, t.nw});
  Map m = dense_map(used);
  std::vector<CornerTile> out;
  out.reserve(tiles.size());
  for (auto& t : tiles) out.push_back({m[t.ne], m[t.se], m[t.sw], m[t.nw]});
  return out;
}

TileSet relabel_colours(const TileSet& set) {
  if (set.kind() == TileKind::Wang) return TileSet::wang(relabel_wang(set.wang_tiles()), set.name(), set.source());
  return TileSet::corner(relabel_corner(set.corner_tiles()), set.name(), set.source());
}

std::uint32_t wang_horizontal_colours(const std::vector<WangTile>& t) { return count_mapped(horizontal_map(t)); }
std::uint32_t wang_vertical_colours(const std::vector<WangTile>& t) { return count_mapped(vertical_map(t)); }
std::uint32_t corner_colours(const std::vector<CornerTile>& tiles) {
  std::vector<Colour> used;
  for (auto& t : tiles) used.insert(used.end(), {t.ne, t.se, t.sw, t.nw});
  return count_mapped(dense_map(used));
}

// Diagonal translation (thesis 8.3.1, Fig. 8.7). The pegs of the corner lattice sit at the
// centres of the Wang tiles and take the tile's number as colour; a corner tile is a valid
// 2x2 block of Wang tiles.
// Why `conjugate`: a peg colouring is a corner tiling iff each of its 2x2 windows is a
// valid block; every horizontally or vertically adjacent pair of pegs lies in such a
// window, so that holds iff the same grid read as Wang tile numbers matches everywhere.
// The identity on grids is thus a bijection between Wang tilings and corner tilings of the
// plane that commutes with every translation (tested in test_aperiodic_roundtrip.cpp).
Conversion diagonal_translation(const std::vector<WangTile>& w) {
  check_source(w.size(), "diagonal translation");
  Conversion c;
  c.method = ConversionMethod::Diagonal;
  std::vector<bool> used(w.size(), false);
  for_each_block(w, [&](std::uint32_t a, std::uint32_t b, std::uint32_t cc, std::uint32_t d) {
    c.corner.push_back({b, d, cc, a});
    used[a] = used[b] = used[cc] = used[d] = true;
  });
  // Colours: the Wang tiles that occur in some block, renumbered densely.
  c.tile_colour.assign(w.size(), kNo);
  Colour next = 0;
  for (std::size_t k = 0; k < w.size(); ++k)
    if (used[k]) c.tile_colour[k] = next++;
  for (auto& t : c.corner) t = {c.tile_colour[t.ne], c.tile_colour[t.se], c.tile_colour[t.sw], c.tile_colour[t.nw]};
  finish_corner(c);
  c.soundness = Soundness::Conjugate;
  c.argument = "pegs are Wang tiles; a peg grid is a corner tiling iff it is a Wang tiling (identity map)";
  return c;
}

Conversion horizontal_translation(const std::vector<WangTile>& w, std::size_t max_lift_states) {
  check_source(w.size(), "horizontal translation");
  return translation(w, true, max_lift_states);
}

Conversion vertical_translation(const std::vector<WangTile>& w, std::size_t max_lift_states) {
  check_source(w.size(), "vertical translation");
  return translation(w, false, max_lift_states);
}

// Rotation (thesis 8.3.3, Figs. 8.9-8.11). The corner lattice is turned 45 degrees; its pegs
// are the midpoints of all Wang edges: a horizontal-edge peg takes the N/S colour, a
// vertical-edge peg the E/W colour plus an offset (the two colour classes are disjoint:
// this is the checkerboard superimposition of Fig. 8.10, which doubles the colours at most).
// A white tile is one Wang tile: (nw, ne, se, sw) = (W, N, E, S). A black tile is the
// vertex between four tiles (TL TR / BL BR) of a valid 2x2 block:
// (nw, ne, se, sw) = (TL.s, TL.e, TR.s, BL.e).
// Why `conjugate`: every tile has its nw/se pegs in one colour class and ne/sw in the other,
// so white and black tiles alternate in a checkerboard. Each Wang cell is the centre of a
// white tile, so the edge colours read off a corner tiling form Wang tiles that match
// along shared edges: a Wang tiling. Conversely a Wang tiling yields white tiles, and each
// vertex sees a valid 2x2 block, hence a black tile. This bijection commutes with the
// translations of the Wang lattice (an index-2 sublattice of the corner lattice), so a
// corner period v gives the Wang period 2v (thesis 8.3.3).
Conversion rotation(const std::vector<WangTile>& w) {
  check_source(w.size(), "rotation");
  Conversion c;
  c.method = ConversionMethod::Rotation;
  c.hmap = horizontal_map(w);
  c.vmap = vertical_map(w);
  const Colour off = count_mapped(c.hmap);
  for (Colour& v : c.vmap)
    if (v != kNo) v += off;
  auto H = [&](Colour x) { return c.hmap[x]; };
  auto V = [&](Colour x) { return c.vmap[x]; };
  std::vector<CornerTile> white, black;
  for (auto& t : w) white.push_back({H(t.n), V(t.e), H(t.s), V(t.w)});  // ne=N se=E sw=S nw=W
  for_each_block(w, [&](std::uint32_t a, std::uint32_t b, std::uint32_t cc, std::uint32_t) {
    black.push_back({V(w[a].e), H(w[b].s), V(w[cc].e), H(w[a].s)});
  });
  sort_unique(black);
  c.white = white.size();
  c.black = black.size();
  c.corner = std::move(white);
  c.corner.insert(c.corner.end(), black.begin(), black.end());
  finish_corner(c);
  c.soundness = Soundness::Conjugate;
  c.argument = "white tiles are the Wang tiles, black tiles the vertices of valid 2x2 blocks; colour classes force the checkerboard";
  return c;
}

// Subdivision (thesis 8.3.4, Figs. 8.12-8.13): each Wang tile becomes four corner tiles.
// Pegs: the Wang vertices take the star colour, edge midpoints the edge colour (N/S and E/W
// relabelled per direction and sharing labels, as the thesis counts colours: tiles + edge
// colours + 1), tile centres a colour naming the tile.
// Why `conjugate` (star distinct, no merges): every corner tile has one centre peg and one
// star peg on opposite corners, which forces centres onto one coset of the 2x lattice (a
// centre at nw forces a star at se, which forces the next centres two steps away); the four
// tiles around a centre spell out one Wang tile, and neighbouring Wang tiles share the
// edge-midpoint peg, i.e. match. The map is a bijection commuting with the 2x lattice.
// Merging centres of a group G keeps it a bijection when G is "rectangular": every
// (N,E,S,W) whose four quadrant pairs (N,W) (N,E) (W,S) (E,S) occur in G is a tile of G;
// then the four quadrants still spell a tile of the set (checked exactly before merging).
Conversion subdivision(const std::vector<WangTile>& w, const SubdivisionOptions& opts) {
  check_source(w.size(), "subdivision");
  Conversion c;
  c.method = ConversionMethod::Subdivision;
  c.hmap = horizontal_map(w);
  c.vmap = vertical_map(w);
  const Colour edges = std::max(count_mapped(c.hmap), count_mapped(c.vmap));
  std::vector<WangTile> r = relabel_wang(w);

  // Centre groups: singletons, or greedily merged rectangular groups.
  std::vector<std::vector<std::size_t>> groups;
  for (std::size_t k = 0; k < r.size(); ++k) groups.push_back({k});
  auto quadrants = [&](const std::vector<std::size_t>& g) {
    std::array<std::set<std::pair<Colour, Colour>>, 4> q;
    for (std::size_t k : g) {
      q[0].insert({r[k].n, r[k].w});
      q[1].insert({r[k].n, r[k].e});
      q[2].insert({r[k].w, r[k].s});
      q[3].insert({r[k].e, r[k].s});
    }
    return q;
  };
  auto rectangular = [&](const std::vector<std::size_t>& g) {
    auto q = quadrants(g);
    std::set<WangTile> members;
    for (std::size_t k : g) members.insert(r[k]);
    for (auto [n, wc] : q[0])
      for (auto [n2, e] : q[1]) {
        if (n2 != n) continue;
        for (auto [w2, s] : q[2]) {
          if (w2 != wc || !q[3].count({e, s})) continue;
          if (!members.count(WangTile{n, e, s, wc})) return false;
        }
      }
    return true;
  };
  if (opts.merge_centres) {
    // Greedy: merge the pair of groups that saves the most quadrant tiles, while any does.
    for (;;) {
      std::size_t best_gain = 0, bi = 0, bj = 0;
      for (std::size_t i = 0; i < groups.size(); ++i)
        for (std::size_t j = i + 1; j < groups.size(); ++j) {
          auto qi = quadrants(groups[i]), qj = quadrants(groups[j]);
          std::size_t gain = 0;
          for (int k = 0; k < 4; ++k)
            for (auto& p : qi[k]) gain += qj[k].count(p);
          if (gain <= best_gain) continue;
          auto merged = groups[i];
          merged.insert(merged.end(), groups[j].begin(), groups[j].end());
          if (rectangular(merged)) best_gain = gain, bi = i, bj = j;
        }
      if (best_gain == 0) break;
      groups[bi].insert(groups[bi].end(), groups[bj].begin(), groups[bj].end());
      groups.erase(groups.begin() + std::ptrdiff_t(bj));
    }
  }
  // Colours: edge colours 0..edges-1, star, then one centre colour per group.
  c.star = opts.star_is_edge_colour ? 0 : edges;
  const Colour first_centre = opts.star_is_edge_colour ? edges : edges + 1;
  c.tile_colour.assign(w.size(), kNo);
  for (std::size_t g = 0; g < groups.size(); ++g)
    for (std::size_t k : groups[g]) c.tile_colour[k] = first_centre + Colour(g);
  for (std::size_t k = 0; k < r.size(); ++k) {
    const WangTile& t = r[k];
    const Colour m = c.tile_colour[k], s = c.star;
    c.corner.push_back({t.n, m, t.w, s});  // NW quadrant: nw=*, ne=N, sw=W, se=centre
    c.corner.push_back({s, t.e, m, t.n});  // NE quadrant: nw=N, ne=*, sw=centre, se=E
    c.corner.push_back({m, t.s, s, t.w});  // SW quadrant: nw=W, ne=centre, sw=*, se=S
    c.corner.push_back({t.e, s, t.s, m});  // SE quadrant: nw=centre, ne=E, sw=S, se=*
  }
  sort_unique(c.corner);
  finish_corner(c);
  if (opts.star_is_edge_colour) {
    c.soundness = Soundness::Unverified;
    c.argument = "star shares an edge colour: tilings out of the 2x phase are not excluded by construction";
  } else {
    c.soundness = Soundness::Conjugate;
    c.argument = opts.merge_centres
                     ? fmt::format("star distinct; {} rectangular centre groups (quadrants spell a tile)", groups.size())
                     : "star distinct, one centre colour per Wang tile: quadrants spell the Wang tile";
  }
  return c;
}

// Corner -> Wang (thesis 8.4 and 2.9): the pair of corner colours along an edge becomes one
// edge colour (N: (nw,ne), S: (sw,se) share one numbering; E: (ne,se), W: (nw,sw) the
// other), relabelled densely per direction.
// Why `conjugate`: the grid of tile numbers is unchanged. Two corner tiles side by side
// match iff they agree on both shared pegs iff the pair colours of the shared edge agree;
// so a grid is a corner tiling iff it is a Wang tiling of the result (identity map).
Conversion corner_to_wang_pairs(const std::vector<CornerTile>& src) {
  check_source(src.size(), "corner to Wang");
  Conversion c;
  c.method = ConversionMethod::ToWang;
  c.kind = TileKind::Wang;
  std::map<std::pair<Colour, Colour>, Colour> hpair, vpair;
  auto id = [](auto& m, Colour a, Colour b) { return m.emplace(std::pair{a, b}, Colour(m.size())).first->second; };
  for (auto& t : src) {
    id(hpair, t.nw, t.ne), id(hpair, t.sw, t.se);
    id(vpair, t.ne, t.se), id(vpair, t.nw, t.sw);
  }
  // Renumber in sorted pair order so results do not depend on tile order.
  Colour k = 0;
  for (auto& [p, v] : hpair) v = k++;
  k = 0;
  for (auto& [p, v] : vpair) v = k++;
  for (auto& t : src)
    c.wang.push_back({hpair[{t.nw, t.ne}], vpair[{t.ne, t.se}], hpair[{t.sw, t.se}], vpair[{t.nw, t.sw}]});
  c.horizontal_colours = Colour(hpair.size());
  c.vertical_colours = Colour(vpair.size());
  c.colours = std::max(c.horizontal_colours, c.vertical_colours);
  c.soundness = Soundness::Conjugate;
  c.argument = "same grid of tile numbers; corner tiles match iff their shared pair colours match";
  return c;
}

Conversion convert(const TileSet& source, ConversionMethod method, const SubdivisionOptions& opts) {
  if (source.empty()) throw InputError(fmt::format("tile set '{}' has no tiles", source.name()));
  if (method == ConversionMethod::ToWang) {
    if (source.kind() != TileKind::Corner)
      throw InputError(fmt::format("method to-wang needs a corner tile set; '{}' is a Wang set", source.name()));
    return corner_to_wang_pairs(source.corner_tiles());
  }
  if (source.kind() != TileKind::Wang)
    throw InputError(fmt::format("method {} needs a Wang tile set; '{}' is a corner set (convert it with to-wang first)",
                                 method_name(method), source.name()));
  const auto& w = source.wang_tiles();
  switch (method) {
    case ConversionMethod::Diagonal: return diagonal_translation(w);
    case ConversionMethod::Horizontal: return horizontal_translation(w);
    case ConversionMethod::Vertical: return vertical_translation(w);
    case ConversionMethod::Rotation: return rotation(w);
    case ConversionMethod::Subdivision: return subdivision(w, opts);
    case ConversionMethod::ToWang: break;
  }
  throw InputError("unknown conversion method");
}

Soundness pruned_soundness(const std::vector<WangTile>& source, const Conversion& conv,
                           const std::vector<CornerTile>& pruned, std::string* argument) {
  const bool horizontal = conv.method == ConversionMethod::Horizontal;
  if (!horizontal && conv.method != ConversionMethod::Vertical) return conv.soundness;
  if (conv.soundness == Soundness::Conjugate || conv.soundness == Soundness::Lifts) return conv.soundness;
  // Back to the source's colours, then the row (column) lift check on the pruned rows.
  const Map& m = horizontal ? conv.hmap : conv.vmap;
  Map inv;
  for (std::size_t k = 0; k < m.size(); ++k)
    if (m[k] != kNo) {
      if (inv.size() <= m[k]) inv.resize(m[k] + 1, kNo);
      inv[m[k]] = Colour(k);
    }
  std::vector<CornerTile> src;
  for (const CornerTile& t : pruned) src.push_back({inv.at(t.ne), inv.at(t.se), inv.at(t.sw), inv.at(t.nw)});
  LiftReport lift = translation_lift(source, horizontal, src);
  if (argument) *argument = "after pruning: " + lift.detail;
  return lift.lifts ? Soundness::Lifts : conv.soundness;
}

TileSet conversion_tile_set(const Conversion& c, const std::string& name, const std::string& source) {
  if (c.kind == TileKind::Wang) {
    if (std::uint64_t(c.horizontal_colours) * c.horizontal_colours * c.vertical_colours * c.vertical_colours >
        (std::uint64_t(1) << 32))
      throw InputError(fmt::format("{} tiles over {} colours exceed 32-bit tile indices", c.size(), c.colours));
    return TileSet::wang(c.wang, name, source);
  }
  if (std::uint64_t(c.colours) * c.colours * c.colours * c.colours > (std::uint64_t(1) << 32))
    throw InputError(fmt::format("{} tiles over {} colours exceed 32-bit tile indices", c.size(), c.colours));
  return TileSet::corner(c.corner, name, source);
}

}  // namespace tilekit
