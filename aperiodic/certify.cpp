#include "aperiodic/certify.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <map>
#include <set>
#include <stdexcept>
#include <unordered_map>

#include "aperiodic/canonical.hpp"
#include "aperiodic/colour_merge.hpp"
#include "aperiodic/convert.hpp"
#include "aperiodic/prune.hpp"
#include "aperiodic/steps.hpp"
#include "base/error.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit {

namespace {

using Json = nlohmann::json;
using Grid = std::vector<std::vector<Colour>>;

// Tiles in the certificate's order: Wang [n, e, s, w], corner [nw, ne, sw, se].
Json tiles_json(const TileSet& s) {
  Json t = Json::array();
  if (s.kind() == TileKind::Wang)
    for (const WangTile& w : s.wang_tiles()) t.push_back({w.n, w.e, w.s, w.w});
  else
    for (const CornerTile& c : s.corner_tiles()) t.push_back({c.nw, c.ne, c.sw, c.se});
  return t;
}
Json set_json(const TileSet& s) {
  return {{"kind", kind_name(s.kind())}, {"tiles", tiles_json(s)}};
}

Json corner_list_json(const std::vector<CornerTile>& v) {
  Json t = Json::array();
  for (const CornerTile& c : v) t.push_back({c.nw, c.ne, c.sw, c.se});
  return t;
}

// Every h x w peg grid whose 2x2 windows are tiles of `tiles` (row 0 the top).
void for_each_grid(const std::vector<CornerTile>& tiles, int h, int w, const std::function<void(const Grid&)>& f) {
  std::map<std::pair<Colour, Colour>, std::vector<const CornerTile*>> by_left, by_top;
  std::map<std::array<Colour, 3>, std::vector<Colour>> se;
  for (const CornerTile& t : tiles) {
    by_left[{t.nw, t.sw}].push_back(&t);
    by_top[{t.nw, t.ne}].push_back(&t);
    se[{t.nw, t.ne, t.sw}].push_back(t.se);
  }
  Grid g(std::size_t(h), std::vector<Colour>(std::size_t(w), 0));
  const int cells = (h - 1) * (w - 1);
  std::function<void(int)> go = [&](int cell) {
    if (cell == cells) return f(g);
    const auto y = std::size_t(cell / (w - 1)), x = std::size_t(cell % (w - 1));
    if (x == 0 && y == 0) {
      for (const CornerTile& t : tiles) g[0][0] = t.nw, g[0][1] = t.ne, g[1][0] = t.sw, g[1][1] = t.se, go(cell + 1);
    } else if (y == 0) {
      if (auto it = by_left.find({g[0][x], g[1][x]}); it != by_left.end())
        for (const CornerTile* t : it->second) g[0][x + 1] = t->ne, g[1][x + 1] = t->se, go(cell + 1);
    } else if (x == 0) {
      if (auto it = by_top.find({g[y][0], g[y][1]}); it != by_top.end())
        for (const CornerTile* t : it->second) g[y + 1][0] = t->sw, g[y + 1][1] = t->se, go(cell + 1);
    } else if (auto it = se.find({g[y][x], g[y][x + 1], g[y + 1][x]}); it != se.end()) {
      for (Colour c : it->second) g[y + 1][x + 1] = c, go(cell + 1);
    }
  };
  go(0);
}

char digit(Colour c) {
  return c < 10 ? char('0' + c) : char('a' + (c - 10));
}

// ---- translation ----

// The tiles of `current` that are the centre of no (2r+1) x (2r+1) patch of `current`.
std::vector<CornerTile> unsurroundable(const std::vector<CornerTile>& current, int r) {
  std::set<CornerTile> centres;
  const auto c = std::size_t(r);
  for_each_grid(current, 2 * r + 2, 2 * r + 2, [&](const Grid& g) {
    centres.insert({g[c][c + 1], g[c + 1][c + 1], g[c + 1][c], g[c][c]});
  });
  std::vector<CornerTile> out;
  for (const CornerTile& t : current)
    if (!centres.count(t)) out.push_back(t);
  return out;
}

// The rounds that prune `start` down to `target`: 3x3 patches until they remove nothing, then 5x5
// ones, again and again. InputError when they stop above `target` (an SCC filter removed more).
Json prune_rounds(std::vector<CornerTile> current, const std::vector<CornerTile>& target_tiles) {
  const std::set<CornerTile> target(target_tiles.begin(), target_tiles.end());
  Json rounds = Json::array();
  while (current.size() > target.size()) {
    int r = 1;
    std::vector<CornerTile> removed = unsurroundable(current, r);
    if (removed.empty()) removed = unsurroundable(current, r = 2);
    if (removed.empty()) break;
    for (const CornerTile& t : removed)
      if (target.count(t)) throw std::logic_error("certify: the surround rounds remove a tile of the pruned set");
    rounds.push_back({{"radius", r}, {"removed", corner_list_json(removed)}});
    std::set<CornerTile> gone(removed.begin(), removed.end());
    std::erase_if(current, [&](const CornerTile& t) { return gone.count(t) > 0; });
  }
  if (std::set<CornerTile>(current.begin(), current.end()) != target)
    throw InputError(
        "certify: the pruning removed tiles that surround rounds (3x3, 5x5) do not (the SCC filter): "
        "no certificate form for it");
  return rounds;
}

// Edge indices of `edges` that lie on a bi-infinite path.
template <class S>
std::vector<bool> alive_edges(const std::vector<std::pair<S, S>>& edges) {
  std::vector<bool> alive(edges.size(), true);
  for (bool changed = true; changed;) {
    changed = false;
    std::set<S> in, out;
    for (std::size_t i = 0; i < edges.size(); ++i)
      if (alive[i]) out.insert(edges[i].first), in.insert(edges[i].second);
    for (std::size_t i = 0; i < edges.size(); ++i)
      if (alive[i] && (!in.count(edges[i].first) || !out.count(edges[i].second))) alive[i] = false, changed = true;
  }
  return alive;
}

Json translation_link(const TileSet& a, const TileSet& b, const CertifyOptions& o) {
  const std::vector<WangTile>& w = a.wang_tiles();
  const Conversion c = horizontal_translation(w, 0);  // the pair tiles before pruning, c.hmap
  std::vector<Colour> peg_colours(c.colours, Conversion::kNoColour);
  for (Colour x = 0; x < c.hmap.size(); ++x)
    if (c.hmap[x] != Conversion::kNoColour) peg_colours[c.hmap[x]] = x;
  const std::set<CornerTile> target(b.corner_tiles().begin(), b.corner_tiles().end());
  const Json rounds = prune_rounds(c.corner, b.corner_tiles());
  // The lift table at the least radius whose Wang windows give their centre back.
  std::vector<std::pair<Colour, Colour>> edges;
  for (const WangTile& t : w) edges.emplace_back(t.w, t.e);
  const std::vector<bool> alive = alive_edges(edges);
  std::map<Colour, std::vector<std::size_t>> out;
  for (std::size_t i = 0; i < edges.size(); ++i)
    if (alive[i]) out[edges[i].first].push_back(i);
  auto pair_in_b = [&](const WangTile& x, const WangTile& y) {
    return target.count({c.hmap[y.n], c.hmap[y.s], c.hmap[x.s], c.hmap[x.n]}) > 0;
  };
  for (int n = 0; n <= o.max_lift_radius; ++n) {
    const std::size_t width = std::size_t(2 * n + 1);
    std::map<std::vector<Colour>, std::set<std::size_t>> centres;
    std::vector<std::size_t> path;
    std::function<void()> grow = [&]() {
      if (path.size() == width) {
        std::vector<Colour> key;
        for (std::size_t e : path) key.push_back(c.hmap[w[e].n]), key.push_back(c.hmap[w[e].s]);
        centres[key].insert(path[std::size_t(n)]);
        return;
      }
      if (auto it = out.find(edges[path.back()].second); it != out.end())
        for (std::size_t e : it->second)
          if (pair_in_b(w[path.back()], w[e])) path.push_back(e), grow(), path.pop_back();
    };
    for (std::size_t i = 0; i < edges.size(); ++i)
      if (alive[i]) path = {i}, grow();
    if (std::any_of(centres.begin(), centres.end(), [](const auto& kv) { return kv.second.size() > 1; })) continue;
    Json table = Json::array();
    for (const auto& [key, tiles] : centres) table.push_back({key, *tiles.begin()});
    return {{"op", "translation"},
            {"peg_colours", peg_colours},
            {"prune", rounds},
            {"lift", {{"radius", n}, {"table", table}}},
            {"to", set_json(b)}};
  }
  throw InputError(fmt::format("certify: the translation's rows do not lift within radius {}", o.max_lift_radius));
}

// ---- merge ----

Json merge_link(const TileSet& a, const TileSet& b, const MergeSearch& m, const CertifyOptions& o) {
  // The composite of the merges: each colour's class, a colour of b.
  std::set<Colour> colours;
  for (const CornerTile& t : a.corner_tiles()) colours.insert({t.nw, t.ne, t.sw, t.se});
  std::map<Colour, Colour> cls;
  for (Colour x : colours) {
    Colour y = x;
    for (const ColourMerge& step : m.merges)
      if (y == step.merged) y = step.kept;
    cls[x] = y;
  }
  for (const auto& [x, y] : cls)
    if (y >= 36) throw InputError("certify: a merged colour over 35 (the recovery table's digits)");
  auto key = [&](const Grid& g, std::size_t y0, std::size_t x0, std::size_t side, bool merge) {
    std::string k;
    for (std::size_t y = y0; y < y0 + side; ++y)
      for (std::size_t x = x0; x < x0 + side; ++x) k += digit(merge ? cls.at(g[y][x]) : g[y][x]);
    return k;
  };
  for (int r = 1; r <= o.max_merge_radius; ++r)
    for (int mg = 0; mg <= o.max_merge_margin; ++mg) {
      const auto side = std::size_t(2 * r + 1);
      std::unordered_map<std::string, std::set<Colour>> v;
      const int wa = 2 * (r + mg) + 1;
      for_each_grid(a.corner_tiles(), wa, wa, [&](const Grid& g) {
        v[key(g, std::size_t(mg), std::size_t(mg), side, true)].insert(g[std::size_t(r + mg)][std::size_t(r + mg)]);
      });
      if (std::any_of(v.begin(), v.end(), [](const auto& kv) { return kv.second.size() > 1; })) continue;
      // The merged set's patches, mb pegs wider than the pegs the recovery of one cell reads: every
      // one must have its middle neighbourhoods in the table (those of a tiling do).
      int mb = mg;
      for (; mb <= mg + o.max_merged_margin; ++mb) {
        bool covered = true;
        const int wb = 2 * (r + mb) + 2;
        for_each_grid(b.corner_tiles(), wb, wb, [&](const Grid& g) {
          for (int k = 0; k < 4 && covered; ++k)
            covered = v.count(key(g, std::size_t(mb + k / 2), std::size_t(mb + k % 2), side, false)) > 0;
        });
        if (covered) break;
      }
      if (mb > mg + o.max_merged_margin) continue;
      std::map<std::string, Colour> sorted;
      for (const auto& [k, c] : v) sorted[k] = *c.begin();
      Json classes = Json::array(), table = Json::array();
      for (const auto& [x, y] : cls) classes.push_back({x, y});
      for (const auto& [k, c] : sorted) table.push_back({k, c});
      return {{"op", "merge"}, {"merges", m.merges.size()}, {"classes", classes}, {"radius", r},
              {"margin", mg},  {"merged_margin", mb},       {"recovery", table},  {"to", set_json(b)}};
    }
  throw InputError(
      fmt::format("certify: no recovery table of radius {}..{}, margin <= {} (merged set: {} more) is a "
                  "conjugacy",
                  1, o.max_merge_radius, o.max_merge_margin, o.max_merged_margin));
}

}  // namespace

Json certify_chain(const RecordedChain& record, const CertifyOptions& o) {
  const TileSet source = resolve_tile_set(record.source);
  if (source.kind() != TileKind::Wang) throw InputError("certify: the source is not a Wang set");
  Json links = Json::array();
  // The set the chain's next step applies to: the canonical form of the last result up to its
  // colour names and tile order, reached from the raw result by a symmetry link.
  TileSet current = source;
  auto to_canonical_orientation = [&](const TileSet& raw) {
    const CanonicalForm f = canonical_form(raw);
    if (f.from.name() == "id") return raw;
    TileSet moved = transform(raw, f.from);
    links.push_back({{"op", "symmetry"}, {"symmetry", f.from.name()}, {"to", set_json(moved)}});
    return moved;
  };
  current = to_canonical_orientation(current);
  for (const std::string& step : record.steps) {
    const auto colon = step.find(':');
    const std::string op = colon == std::string::npos ? step : step.substr(colon + 1);
    if (colon != std::string::npos) {
      const Dihedral g = Dihedral::parse(step.substr(0, colon));
      current = transform(current, g);
      links.push_back({{"op", "symmetry"}, {"symmetry", g.name()}, {"to", set_json(current)}});
    }
    TileSet next;
    if (op == "blocks") {
      std::optional<StepResult> r = apply_step(current, "blocks");
      if (!r) throw InputError("certify: blocks does not apply");
      next = r->set;
      links.push_back({{"op", "blocks"}, {"to", set_json(next)}});
    } else if (op == "to-wang") {
      std::map<std::pair<Colour, Colour>, Colour> h, v;
      for (const CornerTile& t : current.corner_tiles())
        h.emplace(std::pair{t.nw, t.ne}, 0), h.emplace(std::pair{t.sw, t.se}, 0), v.emplace(std::pair{t.ne, t.se}, 0),
            v.emplace(std::pair{t.nw, t.sw}, 0);
      Json hp = Json::array(), vp = Json::array();
      Colour k = 0;
      for (auto& [p, c] : h) c = k++, hp.push_back({p.first, p.second});
      k = 0;
      for (auto& [p, c] : v) c = k++, vp.push_back({p.first, p.second});
      std::vector<WangTile> wt;
      for (const CornerTile& t : current.corner_tiles())
        wt.push_back({h[{t.nw, t.ne}], v[{t.ne, t.se}], h[{t.sw, t.se}], v[{t.nw, t.sw}]});
      next = TileSet::wang(std::move(wt));
      links.push_back({{"op", "to-wang"}, {"horizontal_pairs", hp}, {"vertical_pairs", vp}, {"to", set_json(next)}});
    } else if (op == "prune" || op == "prune5") {
      std::optional<StepResult> r = apply_step(current, op);
      if (!r || current.kind() != TileKind::Corner) throw InputError("certify: " + op + " of a Wang set has no form");
      next = r->set;
      links.push_back({{"op", "prune"},
                       {"prune", prune_rounds(current.corner_tiles(), next.corner_tiles())},
                       {"to", set_json(next)}});
    } else if (op == "horizontal+prune" || op == "horizontal+prune5" || op == "horizontal") {
      std::optional<StepResult> r = apply_step(current, op);
      if (!r || r->label != "conjugate") throw InputError("certify: the translation is not conjugate");
      next = r->set;
      links.push_back(translation_link(current, next, o));
    } else if (op == "merge-colours" || op == "merge-colours2") {
      const MergeSearch m = least_colour_merge(current.corner_tiles(), false, op == "merge-colours2" ? 2 : 1, 1);
      if (m.merges.empty() || !m.conjugate) throw InputError("certify: merge-colours gives no conjugate merge");
      next = TileSet::corner(m.tiles);
      links.push_back(merge_link(current, next, m, o));
    } else {
      throw InputError(
          fmt::format("certify: no certificate form for step '{}' (blocks, to-wang, horizontal, "
                      "horizontal+prune, horizontal+prune5, prune, prune5, merge-colours, merge-colours2)",
                      step));
    }
    current = to_canonical_orientation(next);
  }
  const CanonicalForm last = canonical_form(current);
  if (last.hash != record.set)
    throw std::logic_error(fmt::format("certify: the chain gives set {}, not the recorded {}", last.hash, record.set));
  return {{"format", "tilekit-aperiodic-certificate"},
          {"version", 1},
          {"claim", fmt::format("the {} corner tiles of 'result' tile the plane, and only aperiodically, if the "
                                "Wang set '{}' does: every link is a conjugacy",
                                current.size(), record.source)},
          {"chain", {{"source", record.source}, {"steps", record.steps}, {"set", record.set}}},
          {"source",
           {{"name", record.source}, {"provenance", source.source()}, {"kind", "wang"}, {"tiles", tiles_json(source)}}},
          {"links", links},
          {"result", set_json(current)}};
}

}  // namespace tilekit
