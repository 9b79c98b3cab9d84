// The certificate checker (check.hpp). Written apart from aperiodic/: its own reading of the JSON,
// its own tile rules, patch enumeration and row graphs. Each link is checked as follows.
//
// blocks (Wang A -> corner B): B's tiles must be exactly the 2x2 blocks (a b / c d) of A's tile
//   numbers whose four inner edges match, as corner tiles (nw a, ne b, sw c, se d). A colouring of
//   the pegs by tile numbers is then a Wang tiling of A iff every 2x2 window of it is a tile of B:
//   the identity on peg grids, both ways.
// symmetry (A -> B, one kind): B is the image of A, tile for tile, under the named symmetry of the
//   square; a tiling of A moved by it is one of B and back.
// to-wang (corner A -> Wang B): tile i of B carries the pair colours of tile i of A (N (nw, ne),
//   S (sw, se) in one numbering, E (ne, se), W (nw, sw) in the other), both numberings injective;
//   two tiles side by side match in A iff they match in B: the identity on grids of tile numbers.
// translation (Wang A -> corner B, thesis 8.3.2): pegs on the midpoints of A's N/S edges (peg
//   colour c is A's colour peg_colours[c]); the corner tile of a horizontal pair (a, b), a.e = b.w,
//   is (a.n, b.n, a.s, b.s). Every such pair tile not in B must be removed by the recorded prune
//   rounds: a tile removed in a round is the centre of no (2r+1) x (2r+1) patch of the tiles still
//   there, so no tiling of the plane holds it and the image of every tiling of A is a tiling of B.
//   The inverse reads the row of peg columns (top, bottom) and gives A's tile at each column from
//   the 2N+1 columns around it (the lift table). Checked: (1) every window of 2N+1 tiles of A that
//   lies on a bi-infinite row of A and maps into B gives its centre tile back (lift after map is
//   the identity); (2) on every path of 2N+1 tiles of B's row graph that lies on a bi-infinite row,
//   the two overlapping column windows are in the table and lift to tiles that match east to west
//   and carry the columns' colours north and south (the lift of a tiling of B is a tiling of A, and
//   the map gives B's tiling back, a corner tile being its four pegs).
// prune (corner A -> corner B): B is A less the tiles of the recorded rounds, each as in a
//   translation's prune: the identity on tilings of the plane.
// merge (corner A -> corner B): B = A with each colour replaced by its class. The recovery table
//   gives, for a (2r+1) x (2r+1) neighbourhood of B's pegs, the colour of A at its centre. Checked:
//   (1) every valid peg patch of A, 2 (r + margin) + 1 wide, maps its middle neighbourhood to a table
//   entry that is its centre colour (recovery after the merge is the identity on A's tilings: the
//   neighbourhoods of a tiling are such middles); (2) every valid peg patch of B, 2 (r + merged_margin) + 2
//   wide, has its four middle neighbourhoods in the table and they recover a tile of A, each
//   recovered colour in the class of B's peg (the merge after recovery is the identity, and the
//   recovery of a tiling of B is a tiling of A).
#include "certificate/check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <map>
#include <set>
#include <stdexcept>
#include <unordered_map>

namespace tilekit::certificate {

namespace {

struct Reject : std::runtime_error {
  using std::runtime_error::runtime_error;
};

constexpr std::size_t kMaxTiles = 1000000;
constexpr std::uint32_t kMaxColour = (1u << 20) - 1;  // two or three colours make one 64-bit key
constexpr std::size_t kMaxPatches = 50000000;         // patches enumerated per link, at most

struct Set {
  std::string kind;  // wang or corner
  std::vector<Tile> tiles;
};

std::uint32_t read_uint(const nlohmann::json& j, const std::string& where, std::uint32_t max = kMaxColour) {
  if (!j.is_number_integer() || j.get<std::int64_t>() < 0 || j.get<std::uint64_t>() > max)
    throw Reject(fmt::format("{}: expected an integer 0..{}", where, max));
  return j.get<std::uint32_t>();
}

const nlohmann::json& field(const nlohmann::json& j, const char* name, const std::string& where) {
  if (!j.is_object() || !j.contains(name)) throw Reject(fmt::format("{}: missing field '{}'", where, name));
  return j.at(name);
}

const nlohmann::json& array_field(const nlohmann::json& j, const char* name, const std::string& where) {
  const nlohmann::json& a = field(j, name, where);
  if (!a.is_array()) throw Reject(fmt::format("{}.{}: expected an array", where, name));
  return a;
}

std::string string_field(const nlohmann::json& j, const char* name, const std::string& where) {
  const nlohmann::json& s = field(j, name, where);
  if (!s.is_string()) throw Reject(fmt::format("{}.{}: expected a string", where, name));
  return s.get<std::string>();
}

Set read_set(const nlohmann::json& j, const std::string& where) {
  Set s;
  s.kind = string_field(j, "kind", where);
  if (s.kind != "wang" && s.kind != "corner") throw Reject(where + ".kind: expected wang or corner");
  const nlohmann::json& tiles = array_field(j, "tiles", where);
  if (tiles.empty() || tiles.size() > kMaxTiles)
    throw Reject(where + ".tiles: expected 1.." + std::to_string(kMaxTiles));
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    const std::string w = fmt::format("{}.tiles[{}]", where, i);
    if (!tiles[i].is_array() || tiles[i].size() != 4) throw Reject(w + ": expected four colours");
    Tile t;
    for (std::size_t k = 0; k < 4; ++k) t[k] = read_uint(tiles[i][k], w);
    s.tiles.push_back(t);
  }
  std::set<Tile> distinct(s.tiles.begin(), s.tiles.end());
  if (distinct.size() != s.tiles.size()) throw Reject(where + ".tiles: a tile is listed twice");
  return s;
}

void require_kind(const Set& s, const char* kind, const std::string& where) {
  if (s.kind != kind) throw Reject(fmt::format("{}: expected a {} set, found {}", where, kind, s.kind));
}

std::set<Tile> as_set(const std::vector<Tile>& v) {
  return {v.begin(), v.end()};
}

std::uint32_t colours_of(const Set& s) {
  std::set<std::uint32_t> c;
  for (const Tile& t : s.tiles) c.insert(t.begin(), t.end());
  return std::uint32_t(c.size());
}

// ---- corner peg patches ----------------------------------------------------------------------

// Every h x w grid of pegs (h, w >= 2) whose every 2x2 window is a tile; f(grid) with grid[y][x],
// y = 0 the top row. Corner tile [nw, ne, sw, se].
void for_each_patch(const std::vector<Tile>& tiles, int h, int w,
                    const std::function<void(const std::vector<std::vector<std::uint32_t>>&)>& f) {
  // Colours are below 2^20 (kMaxColour): three fit one 64-bit key.
  auto k2 = [](std::uint32_t a, std::uint32_t b) { return (std::uint64_t(a) << 20) | b; };
  auto k3 = [](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    return (std::uint64_t(a) << 40) | (std::uint64_t(b) << 20) | c;
  };
  std::unordered_map<std::uint64_t, std::vector<Tile>> by_nw_sw, by_nw_ne;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> se_of;
  for (const Tile& t : tiles) {
    by_nw_sw[k2(t[0], t[2])].push_back(t);
    by_nw_ne[k2(t[0], t[1])].push_back(t);
    se_of[k3(t[0], t[1], t[2])].push_back(t[3]);
  }
  std::vector<std::vector<std::uint32_t>> g(std::size_t(h), std::vector<std::uint32_t>(std::size_t(w), 0u));
  std::size_t count = 0;
  const int cells = (h - 1) * (w - 1);
  std::function<void(int)> fill = [&](int cell) {
    if (cell == cells) {
      if (++count > kMaxPatches) throw Reject("more than 5e7 patches to check");
      f(g);
      return;
    }
    const int y = cell / (w - 1), x = cell % (w - 1);
    auto& top = g[std::size_t(y)];
    auto& bottom = g[std::size_t(y + 1)];
    if (x == 0 && y == 0) {
      for (const Tile& t : tiles) {
        top[0] = t[0], top[1] = t[1], bottom[0] = t[2], bottom[1] = t[3];
        fill(cell + 1);
      }
    } else if (y == 0) {
      auto it = by_nw_sw.find(k2(top[std::size_t(x)], bottom[std::size_t(x)]));
      if (it == by_nw_sw.end()) return;
      for (const Tile& t : it->second) {
        top[std::size_t(x + 1)] = t[1], bottom[std::size_t(x + 1)] = t[3];
        fill(cell + 1);
      }
    } else if (x == 0) {
      auto it = by_nw_ne.find(k2(top[0], top[1]));
      if (it == by_nw_ne.end()) return;
      for (const Tile& t : it->second) {
        bottom[0] = t[2], bottom[1] = t[3];
        fill(cell + 1);
      }
    } else {
      auto it = se_of.find(k3(top[std::size_t(x)], top[std::size_t(x + 1)], bottom[std::size_t(x)]));
      if (it == se_of.end()) return;
      for (std::uint32_t se : it->second) {
        bottom[std::size_t(x + 1)] = se;
        fill(cell + 1);
      }
    }
  };
  fill(0);
}

// The tiles that are the middle tile of some (2r+1) x (2r+1) patch of `tiles`.
std::set<Tile> surroundable(const std::vector<Tile>& tiles, int r) {
  std::set<Tile> centres;
  const auto c = std::size_t(r);
  for_each_patch(tiles, 2 * r + 2, 2 * r + 2, [&](const std::vector<std::vector<std::uint32_t>>& g) {
    centres.insert({g[c][c], g[c][c + 1], g[c + 1][c], g[c + 1][c + 1]});
  });
  return centres;
}

// ---- links --------------------------------------------------------------------------------

LinkReport check_blocks(const Set& a, const Set& b, const std::string& where) {
  require_kind(a, "wang", where + " (from)");
  require_kind(b, "corner", where + " (to)");
  std::set<Tile> blocks;
  const auto n = std::uint32_t(a.tiles.size());
  for (std::uint32_t p = 0; p < n; ++p)
    for (std::uint32_t q = 0; q < n; ++q) {
      if (a.tiles[p][1] != a.tiles[q][3]) continue;  // p.e == q.w
      for (std::uint32_t c = 0; c < n; ++c) {
        if (a.tiles[p][2] != a.tiles[c][0]) continue;  // p.s == c.n
        for (std::uint32_t d = 0; d < n; ++d)
          if (a.tiles[c][1] == a.tiles[d][3] && a.tiles[q][2] == a.tiles[d][0]) blocks.insert({p, q, c, d});
      }
    }
  if (blocks != as_set(b.tiles))
    throw Reject(fmt::format("{}: the corner set is not the set of matching 2x2 blocks ({} blocks, {} tiles)", where,
                             blocks.size(), b.tiles.size()));
  return {"blocks", a.tiles.size(), b.tiles.size(),
          fmt::format("the {} corner tiles are exactly the matching 2x2 blocks of the {} Wang tiles", b.tiles.size(),
                      a.tiles.size())};
}

Tile rotate(const std::string& kind, const Tile& t) {   // a quarter turn clockwise
  if (kind == "wang") return {t[3], t[0], t[1], t[2]};  // n <- w, e <- n, s <- e, w <- s
  return {t[2], t[0], t[3], t[1]};                      // nw <- sw, ne <- nw, sw <- se, se <- ne
}
Tile mirror(const std::string& kind, const Tile& t) {  // left-right
  if (kind == "wang") return {t[0], t[3], t[2], t[1]};
  return {t[1], t[0], t[3], t[2]};
}

LinkReport check_symmetry(const Set& a, const Set& b, const nlohmann::json& link, const std::string& where) {
  if (a.kind != b.kind) throw Reject(where + ": a symmetry keeps the kind");
  const std::string name = string_field(link, "symmetry", where);
  static const std::vector<std::string> turns = {"id", "rot90", "rot180", "rot270"};
  bool m = false;
  std::string rest = name;
  if (rest.rfind("mirror", 0) == 0) {
    m = true;
    rest =
        rest == "mirror" ? "id" : rest.substr(rest.find('+') == std::string::npos ? rest.size() : rest.find('+') + 1);
  }
  const auto it = std::find(turns.begin(), turns.end(), rest);
  if (it == turns.end() || rest.empty()) throw Reject(where + ".symmetry: unknown symmetry '" + name + "'");
  const auto q = int(it - turns.begin());
  if (a.tiles.size() != b.tiles.size()) throw Reject(where + ": the image has another number of tiles");
  for (std::size_t i = 0; i < a.tiles.size(); ++i) {
    Tile t = a.tiles[i];
    if (m) t = mirror(a.kind, t);
    for (int k = 0; k < q; ++k) t = rotate(a.kind, t);
    if (t != b.tiles[i])
      throw Reject(fmt::format("{}: tile {} is not the image of the source tile under {}", where, i, name));
  }
  return {"symmetry", a.tiles.size(), b.tiles.size(), "every tile is the image of the source tile under " + name};
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> read_pairs(const nlohmann::json& link, const char* name,
                                                                const std::string& where) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> v;
  const nlohmann::json& a = array_field(link, name, where);
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string w = fmt::format("{}.{}[{}]", where, name, i);
    if (!a[i].is_array() || a[i].size() != 2) throw Reject(w + ": expected a pair");
    v.emplace_back(read_uint(a[i][0], w), read_uint(a[i][1], w));
  }
  if (std::set(v.begin(), v.end()).size() != v.size()) throw Reject(where + "." + name + ": a pair is listed twice");
  return v;
}

LinkReport check_to_wang(const Set& a, const Set& b, const nlohmann::json& link, const std::string& where) {
  require_kind(a, "corner", where + " (from)");
  require_kind(b, "wang", where + " (to)");
  const auto hp = read_pairs(link, "horizontal_pairs", where);
  const auto vp = read_pairs(link, "vertical_pairs", where);
  if (a.tiles.size() != b.tiles.size()) throw Reject(where + ": tile i of the Wang set is tile i of the corner set");
  auto code = [&](const auto& pairs, std::uint32_t x, std::uint32_t y, std::size_t i) {
    const auto it = std::find(pairs.begin(), pairs.end(), std::pair{x, y});
    if (it == pairs.end()) throw Reject(fmt::format("{}: tile {}: the pair ({}, {}) has no colour", where, i, x, y));
    return std::uint32_t(it - pairs.begin());
  };
  for (std::size_t i = 0; i < a.tiles.size(); ++i) {
    const Tile& c = a.tiles[i];  // nw ne sw se
    const Tile w = {code(hp, c[0], c[1], i), code(vp, c[1], c[3], i), code(hp, c[2], c[3], i), code(vp, c[0], c[2], i)};
    if (w != b.tiles[i])
      throw Reject(fmt::format("{}: Wang tile {} does not carry the pair colours of corner tile {}", where, i, i));
  }
  return {"to-wang", a.tiles.size(), b.tiles.size(),
          fmt::format("tile for tile, {} horizontal and {} vertical pair colours, both numberings injective", hp.size(),
                      vp.size())};
}

// Edges of a row graph (from state, to state) that lie on a bi-infinite path: repeatedly drop
// edges out of a state nothing enters or into a state nothing leaves.
template <class State>
std::vector<bool> on_biinfinite_paths(const std::vector<std::pair<State, State>>& edges) {
  std::vector<bool> alive(edges.size(), true);
  for (bool changed = true; changed;) {
    changed = false;
    std::set<State> has_in, has_out;
    for (std::size_t i = 0; i < edges.size(); ++i)
      if (alive[i]) has_out.insert(edges[i].first), has_in.insert(edges[i].second);
    for (std::size_t i = 0; i < edges.size(); ++i)
      if (alive[i] && (!has_in.count(edges[i].first) || !has_out.count(edges[i].second)))
        alive[i] = false, changed = true;
  }
  return alive;
}

// Every path of `len` edges (indices) in the graph of alive edges: f(path).
template <class State>
void for_each_path(const std::vector<std::pair<State, State>>& edges, const std::vector<bool>& alive, int len,
                   const std::function<void(const std::vector<std::size_t>&)>& f) {
  std::map<State, std::vector<std::size_t>> out;
  for (std::size_t i = 0; i < edges.size(); ++i)
    if (alive[i]) out[edges[i].first].push_back(i);
  std::vector<std::size_t> path;
  std::size_t count = 0;
  std::function<void()> grow = [&]() {
    if (int(path.size()) == len) {
      if (++count > kMaxPatches) throw Reject("more than 5e7 row windows to check");
      f(path);
      return;
    }
    const auto it = out.find(edges[path.back()].second);
    if (it == out.end()) return;
    for (std::size_t e : it->second) {
      path.push_back(e);
      grow();
      path.pop_back();
    }
  };
  for (std::size_t i = 0; i < edges.size(); ++i)
    if (alive[i]) {
      path = {i};
      grow();
    }
}

// The prune rounds of a link applied to `current`: every removed tile is there and is the centre
// of no (2r+1) x (2r+1) patch of the tiles still there (so no tiling of the plane holds it).
std::size_t check_prune_rounds(std::set<Tile>& current, const nlohmann::json& link, const std::string& where) {
  const nlohmann::json& rounds = array_field(link, "prune", where);
  std::size_t removed_total = 0;
  for (std::size_t k = 0; k < rounds.size(); ++k) {
    const std::string w = fmt::format("{}.prune[{}]", where, k);
    const int r = int(read_uint(field(rounds[k], "radius", w), w + ".radius", 4));
    if (r < 1) throw Reject(w + ".radius: at least 1");
    const Set removed = read_set({{"kind", "corner"}, {"tiles", field(rounds[k], "removed", w)}}, w);
    const std::set<Tile> centres = surroundable({current.begin(), current.end()}, r);
    for (const Tile& t : removed.tiles) {
      if (!current.count(t)) throw Reject(w + ": removes a tile that is not there");
      if (centres.count(t))
        throw Reject(fmt::format("{}: a removed tile is the centre of a {}x{} patch", w, 2 * r + 1, 2 * r + 1));
    }
    for (const Tile& t : removed.tiles) current.erase(t);
    removed_total += removed.tiles.size();
  }
  return removed_total;
}

LinkReport check_prune(const Set& a, const Set& b, const nlohmann::json& link, const std::string& where) {
  require_kind(a, "corner", where + " (from)");
  require_kind(b, "corner", where + " (to)");
  std::set<Tile> current = as_set(a.tiles);
  const std::size_t removed = check_prune_rounds(current, link, where);
  if (current != as_set(b.tiles)) throw Reject(where + ": the set less the pruned tiles is not the pruned set");
  return {"prune", a.tiles.size(), b.tiles.size(),
          fmt::format("{} tiles removed in {} rounds, each the centre of no patch of the tiles before it", removed,
                      array_field(link, "prune", where).size())};
}

LinkReport check_translation(const Set& a, const Set& b, const nlohmann::json& link, const std::string& where) {
  require_kind(a, "wang", where + " (from)");
  require_kind(b, "corner", where + " (to)");
  // Peg colours of B -> N/S colours of A, injective.
  const nlohmann::json& pc = array_field(link, "peg_colours", where);
  std::map<std::uint32_t, std::uint32_t> to_peg;  // A's N/S colour -> B's colour
  for (std::size_t i = 0; i < pc.size(); ++i)
    if (!to_peg.emplace(read_uint(pc[i], fmt::format("{}.peg_colours[{}]", where, i)), std::uint32_t(i)).second)
      throw Reject(where + ".peg_colours: two pegs name one colour");
  auto peg = [&](std::uint32_t ns) {
    const auto it = to_peg.find(ns);
    if (it == to_peg.end()) throw Reject(fmt::format("{}: the N/S colour {} has no peg colour", where, ns));
    return it->second;
  };
  // The pair tiles, then the prune rounds down to B.
  std::set<Tile> current;
  for (const Tile& p : a.tiles)
    for (const Tile& q : a.tiles)
      if (p[1] == q[3]) current.insert({peg(p[0]), peg(q[0]), peg(p[2]), peg(q[2])});
  const std::size_t pairs = current.size();
  const std::size_t removed_total = check_prune_rounds(current, link, where);
  const nlohmann::json& rounds = array_field(link, "prune", where);
  if (current != as_set(b.tiles))
    throw Reject(fmt::format("{}: the pair tiles less the pruned ones ({}) are not the corner set ({})", where,
                             current.size(), b.tiles.size()));
  // The lift table: window of 2N+1 columns (top, bottom peg colours) -> A's tile number.
  const nlohmann::json& lift = field(link, "lift", where);
  const int n = int(read_uint(field(lift, "radius", where + ".lift"), where + ".lift.radius", 64));
  const std::size_t width = std::size_t(2 * n + 1);
  std::map<std::vector<std::uint32_t>, std::uint32_t> table;
  const nlohmann::json& entries = array_field(lift, "table", where + ".lift");
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const std::string w = fmt::format("{}.lift.table[{}]", where, i);
    if (!entries[i].is_array() || entries[i].size() != 2 || !entries[i][0].is_array() ||
        entries[i][0].size() != 2 * width)
      throw Reject(fmt::format("{}: expected [[{} colours], tile]", w, 2 * width));
    std::vector<std::uint32_t> key;
    for (const auto& c : entries[i][0]) key.push_back(read_uint(c, w));
    const std::uint32_t tile = read_uint(entries[i][1], w);
    if (tile >= a.tiles.size()) throw Reject(w + ": no such tile");
    if (!table.emplace(key, tile).second) throw Reject(w + ": a window listed twice");
  }
  auto lookup = [&](const std::vector<std::uint32_t>& key, const char* what) {
    const auto it = table.find(key);
    if (it == table.end())
      throw Reject(fmt::format("{}: {}: a window of columns has no entry in the lift table", where, what));
    return it->second;
  };
  // (1) map then lift: A's row windows that map into B.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> wang_edges;  // w -> e
  for (const Tile& t : a.tiles) wang_edges.emplace_back(t[3], t[1]);
  std::size_t wang_windows = 0;
  const std::set<Tile> bset = as_set(b.tiles);
  for_each_path<std::uint32_t>(
      wang_edges, on_biinfinite_paths(wang_edges), int(width), [&](const std::vector<std::size_t>& p) {
        for (std::size_t i = 0; i + 1 < p.size(); ++i) {
          const Tile& x = a.tiles[p[i]];
          const Tile& y = a.tiles[p[i + 1]];
          if (!bset.count({peg(x[0]), peg(y[0]), peg(x[2]), peg(y[2])})) return;  // in no tiling of the plane
        }
        std::vector<std::uint32_t> key;
        for (std::size_t e : p) key.push_back(peg(a.tiles[e][0])), key.push_back(peg(a.tiles[e][2]));
        if (lookup(key, "lift after map") != p[std::size_t(n)])
          throw Reject(fmt::format("{}: lift after map: a window of tiles does not give its centre tile back", where));
        ++wang_windows;
      });
  // (2) lift then map: B's row windows of 2N+1 tiles.
  using Column = std::pair<std::uint32_t, std::uint32_t>;
  std::vector<std::pair<Column, Column>> corner_edges;  // (nw, sw) -> (ne, se)
  for (const Tile& t : b.tiles) corner_edges.push_back({{t[0], t[2]}, {t[1], t[3]}});
  std::size_t corner_windows = 0;
  for_each_path<Column>(
      corner_edges, on_biinfinite_paths(corner_edges), int(width), [&](const std::vector<std::size_t>& p) {
        std::vector<Column> cols;
        for (std::size_t e : p) cols.push_back(corner_edges[e].first);
        cols.push_back(corner_edges[p.back()].second);
        std::vector<std::uint32_t> k1, k2;
        for (std::size_t i = 0; i < width; ++i) {
          k1.push_back(cols[i].first), k1.push_back(cols[i].second);
          k2.push_back(cols[i + 1].first), k2.push_back(cols[i + 1].second);
        }
        const Tile& t1 = a.tiles[lookup(k1, "map after lift")];
        const Tile& t2 = a.tiles[lookup(k2, "map after lift")];
        const Column c1 = cols[std::size_t(n)], c2 = cols[std::size_t(n) + 1];
        if (t1[1] != t2[3] || peg(t1[0]) != c1.first || peg(t1[2]) != c1.second || peg(t2[0]) != c2.first ||
            peg(t2[2]) != c2.second)
          throw Reject(
              fmt::format("{}: map after lift: two lifted neighbours do not match or miss their columns", where));
        ++corner_windows;
      });
  return {"translation", a.tiles.size(), b.tiles.size(),
          fmt::format("{} pair tiles, {} removed in {} prune rounds; lift radius {} ({} entries): {} Wang row windows "
                      "give their centre back, {} corner row windows lift to matching tiles",
                      pairs, removed_total, rounds.size(), n, table.size(), wang_windows, corner_windows)};
}

int digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'z') return c - 'a' + 10;
  return -1;
}
char to_digit(std::uint32_t v) {
  return v < 10 ? char('0' + v) : char('a' + v - 10);
}

LinkReport check_merge(const Set& a, const Set& b, const nlohmann::json& link, const std::string& where) {
  require_kind(a, "corner", where + " (from)");
  require_kind(b, "corner", where + " (to)");
  std::map<std::uint32_t, std::uint32_t> cls;
  const nlohmann::json& classes = array_field(link, "classes", where);
  for (std::size_t i = 0; i < classes.size(); ++i) {
    const std::string w = fmt::format("{}.classes[{}]", where, i);
    if (!classes[i].is_array() || classes[i].size() != 2) throw Reject(w + ": expected [colour, class]");
    if (!cls.emplace(read_uint(classes[i][0], w), read_uint(classes[i][1], w, 35)).second)
      throw Reject(w + ": a colour in two classes");
  }
  auto class_of = [&](std::uint32_t c) {
    const auto it = cls.find(c);
    if (it == cls.end()) throw Reject(fmt::format("{}: colour {} has no class", where, c));
    return it->second;
  };
  std::set<Tile> image;
  for (const Tile& t : a.tiles) image.insert({class_of(t[0]), class_of(t[1]), class_of(t[2]), class_of(t[3])});
  if (image != as_set(b.tiles)) throw Reject(where + ": the merged set is not the image of the set under the classes");
  const int r = int(read_uint(field(link, "radius", where), where + ".radius", 4));
  const int m = int(read_uint(field(link, "margin", where), where + ".margin", 4));
  const int mb = int(read_uint(field(link, "merged_margin", where), where + ".merged_margin", 8));
  const std::size_t side = std::size_t(2 * r + 1);
  std::unordered_map<std::string, std::uint32_t> table;
  const nlohmann::json& rec = array_field(link, "recovery", where);
  for (std::size_t i = 0; i < rec.size(); ++i) {
    const std::string w = fmt::format("{}.recovery[{}]", where, i);
    if (!rec[i].is_array() || rec[i].size() != 2 || !rec[i][0].is_string())
      throw Reject(w + ": expected [neighbourhood, colour]");
    const std::string key = rec[i][0].get<std::string>();
    if (key.size() != side * side)
      throw Reject(fmt::format("{}: a radius-{} neighbourhood has {} pegs, not {}", w, r, side * side, key.size()));
    for (char c : key)
      if (digit(c) < 0) throw Reject(w + ": a peg is not a digit 0-9a-z");
    const std::uint32_t colour = read_uint(rec[i][1], w);
    if (class_of(colour) != std::uint32_t(digit(key[key.size() / 2])))
      throw Reject(w + ": the recovered colour is not in the class of the centre peg");
    if (!table.emplace(key, colour).second) throw Reject(w + ": a neighbourhood listed twice");
  }
  auto key_at = [&](const std::vector<std::vector<std::uint32_t>>& g, std::size_t y0, std::size_t x0, bool merge) {
    std::string k;
    for (std::size_t y = y0; y < y0 + side; ++y)
      for (std::size_t x = x0; x < x0 + side; ++x) k += to_digit(merge ? class_of(g[y][x]) : g[y][x]);
    return k;
  };
  // (1) recovery after the merge, on A's patches.
  std::size_t a_patches = 0;
  const int wa = 2 * (r + m) + 1;
  for_each_patch(a.tiles, wa, wa, [&](const std::vector<std::vector<std::uint32_t>>& g) {
    const auto it = table.find(key_at(g, std::size_t(m), std::size_t(m), true));
    const std::uint32_t centre = g[std::size_t(r + m)][std::size_t(r + m)];
    if (it == table.end())
      throw Reject(fmt::format("{}: recovery after merge: a neighbourhood of the merged set has no entry", where));
    if (it->second != centre)
      throw Reject(fmt::format("{}: recovery after merge: neighbourhood {} gives colour {}, the patch has {}", where,
                               it->first, it->second, centre));
    ++a_patches;
  });
  // (2) the merge after recovery, on B's patches.
  std::size_t b_patches = 0;
  const std::set<Tile> aset = as_set(a.tiles);
  const int wb = 2 * (r + mb) + 2;
  for_each_patch(b.tiles, wb, wb, [&](const std::vector<std::vector<std::uint32_t>>& g) {
    std::uint32_t rc[4];
    for (int k = 0; k < 4; ++k) {
      const auto it = table.find(key_at(g, std::size_t(mb + k / 2), std::size_t(mb + k % 2), false));
      if (it == table.end())
        throw Reject(fmt::format("{}: merge after recovery: a neighbourhood of the merged set has no entry", where));
      rc[k] = it->second;
    }
    if (!aset.count({rc[0], rc[1], rc[2], rc[3]}))
      throw Reject(fmt::format("{}: merge after recovery: the recovered pegs of a cell are no tile", where));
    ++b_patches;
  });
  return {"merge", a.tiles.size(), b.tiles.size(),
          fmt::format("{} colours into {} classes; recovery radius {} ({} entries): {} patches of the set ({}x{} pegs) "
                      "give their centre back, {} patches of the merged set ({}x{} pegs) recover tiles",
                      cls.size(), colours_of(b), r, table.size(), a_patches, wa, wa, b_patches, wb, wb)};
}

}  // namespace

Report check(const nlohmann::json& cert, const std::vector<Tile>& reference) {
  Report rep;
  try {
    if (!cert.is_object() || !cert.contains("format") || cert["format"] != "tilekit-aperiodic-certificate")
      throw Reject("not a certificate: 'format' must be tilekit-aperiodic-certificate");
    if (read_uint(field(cert, "version", "certificate"), "version", 1000) != 1) throw Reject("version: expected 1");
    const nlohmann::json& src = field(cert, "source", "certificate");
    rep.source = string_field(src, "name", "source");
    Set current = read_set(src, "source");
    require_kind(current, "wang", "source");
    rep.source_tiles = current.tiles.size();
    rep.source_matches_reference =
        !reference.empty() && as_set(reference) == as_set(current.tiles) && reference.size() == current.tiles.size();
    if (!rep.source_matches_reference)
      throw Reject("source: the stated tiles are not the published set's (" + rep.source + ")");
    const nlohmann::json& links = array_field(cert, "links", "certificate");
    if (links.empty()) throw Reject("links: none");
    for (std::size_t i = 0; i < links.size(); ++i) {
      const std::string where = fmt::format("links[{}]", i);
      const std::string op = string_field(links[i], "op", where);
      Set next = read_set(field(links[i], "to", where), where + ".to");
      if (op == "blocks")
        rep.links.push_back(check_blocks(current, next, where));
      else if (op == "symmetry")
        rep.links.push_back(check_symmetry(current, next, links[i], where));
      else if (op == "to-wang")
        rep.links.push_back(check_to_wang(current, next, links[i], where));
      else if (op == "translation")
        rep.links.push_back(check_translation(current, next, links[i], where));
      else if (op == "merge")
        rep.links.push_back(check_merge(current, next, links[i], where));
      else if (op == "prune")
        rep.links.push_back(check_prune(current, next, links[i], where));
      else
        throw Reject(where + ".op: unknown link '" + op + "'");
      current = std::move(next);
    }
    const Set result = read_set(field(cert, "result", "certificate"), "result");
    if (result.kind != current.kind || as_set(result.tiles) != as_set(current.tiles))
      throw Reject("result: not the last link's set");
    rep.result_tiles = result.tiles.size();
    rep.result_colours = colours_of(result);
    rep.accepted = true;
  } catch (const Reject& e) {
    rep.error = e.what();
  } catch (const nlohmann::json::exception& e) {
    rep.error = std::string("malformed certificate: ") + e.what();
  }
  return rep;
}

}  // namespace tilekit::certificate
