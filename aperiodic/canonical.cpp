#include "aperiodic/canonical.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <map>
#include <numeric>

#include "base/error.hpp"
#include "base/hash.hpp"

namespace tilekit {

namespace {

// Tiles as their four colours in file order: n s w e (Wang) or nw ne sw se (corner).
using Tile4 = std::array<Colour, 4>;

std::vector<Tile4> tiles4(const TileSet& set) {
  std::vector<Tile4> out;
  for (std::size_t k = 0; k < set.size(); ++k) {
    auto c = set.file_colours(k);
    out.push_back({c[0], c[1], c[2], c[3]});
  }
  return out;
}

TileSet from_tiles4(TileKind kind, const std::vector<Tile4>& tiles, const std::string& name, const std::string& source) {
  if (kind == TileKind::Wang) {
    std::vector<WangTile> w;
    for (const Tile4& t : tiles) w.push_back({t[0], t[3], t[1], t[2]});
    return TileSet::wang(std::move(w), name, source);
  }
  std::vector<CornerTile> c;
  for (const Tile4& t : tiles) c.push_back({t[1], t[3], t[2], t[0]});
  return TileSet::corner(std::move(c), name, source);
}

// One quarter turn clockwise and the left-right mirror, in file order. Wang (n s w e): the new
// north edge is the old west, east the old north, south the old east, west the old south.
// Corner (nw ne sw se): the new nw corner is the old sw, ne the old nw, se the old ne, sw the old se.
Tile4 rotate(TileKind kind, const Tile4& t) {
  return kind == TileKind::Wang ? Tile4{t[2], t[3], t[1], t[0]} : Tile4{t[2], t[0], t[3], t[1]};
}
Tile4 mirror(TileKind kind, const Tile4& t) {
  return kind == TileKind::Wang ? Tile4{t[0], t[1], t[3], t[2]} : Tile4{t[1], t[0], t[3], t[2]};
}

// Colour refinement with individualisation over the vertices (slot class, colour): a Wang set's
// N/S colours and E/W colours are two classes relabelled separately, a corner set's one.
class Canonizer {
 public:
  Canonizer(TileKind kind, const std::vector<Tile4>& tiles, std::size_t max_leaves, const Deadline& deadline)
      : kind_(kind), max_leaves_(max_leaves), deadline_(deadline) {
    std::map<std::pair<int, Colour>, std::uint32_t> id;
    for (const Tile4& t : tiles)
      for (int j = 0; j < 4; ++j) id.emplace(std::pair{slot_class(j), t[j]}, 0);
    std::uint32_t next = 0;
    for (auto& [key, v] : id) {
      v = next++;
      class_of_.push_back(key.first);
    }
    for (const Tile4& t : tiles) {
      Tile4 v;
      for (int j = 0; j < 4; ++j) v[j] = id.at({slot_class(j), t[j]});
      tiles_.push_back(v);
    }
    occurs_.resize(next);
    for (std::size_t k = 0; k < tiles_.size(); ++k)
      for (int j = 0; j < 4; ++j) occurs_[tiles_[k][j]].push_back({std::uint32_t(k), j});
  }

  // The least relabelled, sorted tile list; exact unless the leaf budget ran out.
  std::vector<Tile4> run(bool* exact) {
    std::vector<std::uint32_t> cell(class_of_.size());
    for (std::size_t v = 0; v < cell.size(); ++v) cell[v] = std::uint32_t(class_of_[v]);
    refine(cell);
    search(cell);
    *exact = leaves_ <= max_leaves_;
    return best_;
  }

 private:
  int slot_class(int j) const { return kind_ == TileKind::Wang ? j / 2 : 0; }

  // Splits cells by each vertex's occurrences (slot, cells of the tile's four colours) until stable.
  // Cells stay numbered by rank, so the result depends only on the set, not on the input labels.
  void refine(std::vector<std::uint32_t>& cell) const {
    const std::size_t n = cell.size();
    std::size_t cells = count_cells(cell);
    for (;;) {
      if (deadline_.expired()) throw CanonicalTimeLimit();
      std::vector<std::vector<std::uint64_t>> sig(n);
      for (std::size_t v = 0; v < n; ++v) {
        for (auto [k, j] : occurs_[v]) {
          const Tile4& t = tiles_[k];
          std::uint64_t key = std::uint64_t(j);
          for (int i = 0; i < 4; ++i) key = key * 1000003u + cell[t[i]];
          sig[v].push_back(key);
        }
        std::sort(sig[v].begin(), sig[v].end());
      }
      std::vector<std::uint32_t> order(n);
      std::iota(order.begin(), order.end(), 0u);
      std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        if (cell[a] != cell[b]) return cell[a] < cell[b];
        return sig[a] < sig[b];
      });
      std::vector<std::uint32_t> next(n);
      std::uint32_t rank = 0;
      for (std::size_t i = 0; i < n; ++i) {
        if (i > 0 && (cell[order[i]] != cell[order[i - 1]] || sig[order[i]] != sig[order[i - 1]])) ++rank;
        next[order[i]] = rank;
      }
      cell = std::move(next);
      const std::size_t now = count_cells(cell);
      if (now == cells) return;
      cells = now;
    }
  }

  static std::size_t count_cells(const std::vector<std::uint32_t>& cell) {
    std::vector<std::uint32_t> c(cell);
    std::sort(c.begin(), c.end());
    return std::size_t(std::unique(c.begin(), c.end()) - c.begin());
  }

  void search(const std::vector<std::uint32_t>& cell) {
    if (leaves_ > max_leaves_) return;
    // The first cell (least rank) holding more than one vertex.
    std::vector<std::uint32_t> size(cell.size(), 0);
    for (std::uint32_t c : cell) ++size[c];
    std::uint32_t target = kNone;
    for (std::uint32_t c = 0; c < size.size(); ++c)
      if (size[c] > 1) {
        target = c;
        break;
      }
    if (target == kNone) {
      ++leaves_;
      leaf(cell);
      return;
    }
    for (std::size_t v = 0; v < cell.size(); ++v) {
      if (cell[v] != target) continue;
      // Individualise v: it goes first in its cell, the others after it.
      std::vector<std::uint32_t> next(cell.size());
      for (std::size_t u = 0; u < cell.size(); ++u) next[u] = 2 * cell[u] + (cell[u] == target && u != v ? 1 : 0);
      refine(next);
      search(next);
      if (leaves_ > max_leaves_) return;
    }
  }

  // Every vertex alone in its cell: colours numbered by cell rank within their class.
  void leaf(const std::vector<std::uint32_t>& cell) {
    std::vector<std::uint32_t> order(cell.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return cell[a] < cell[b]; });
    std::vector<Colour> label(cell.size());
    std::array<Colour, 2> next{0, 0};
    for (std::uint32_t v : order) label[v] = next[std::size_t(class_of_[v])]++;
    std::vector<Tile4> out;
    out.reserve(tiles_.size());
    for (const Tile4& t : tiles_) out.push_back({label[t[0]], label[t[1]], label[t[2]], label[t[3]]});
    std::sort(out.begin(), out.end());
    if (best_.empty() || out < best_) best_ = std::move(out);
  }

  static constexpr std::uint32_t kNone = ~0u;
  TileKind kind_;
  std::size_t max_leaves_;
  Deadline deadline_;
  std::vector<Tile4> tiles_;                                   // vertex ids
  std::vector<int> class_of_;                                  // vertex -> slot class
  std::vector<std::vector<std::pair<std::uint32_t, int>>> occurs_;  // vertex -> (tile, slot)
  std::vector<Tile4> best_;
  std::size_t leaves_ = 0;
};

std::string canonical_text(TileKind kind, const std::vector<Tile4>& tiles) {
  std::string text = std::string(kind_name(kind)) + "\n";
  for (const Tile4& t : tiles) text += fmt::format("{} {} {} {}\n", t[0], t[1], t[2], t[3]);
  return text;
}

}  // namespace

std::string Dihedral::name() const {
  static const char* turns[] = {"id", "rot90", "rot180", "rot270"};
  if (!mirror) return turns[quarter_turns];
  return quarter_turns == 0 ? "mirror" : fmt::format("mirror+{}", turns[quarter_turns]);
}

std::vector<Dihedral> Dihedral::all() {
  std::vector<Dihedral> g;
  for (bool m : {false, true})
    for (int q = 0; q < 4; ++q) g.push_back({q, m});
  return g;
}

Dihedral Dihedral::parse(const std::string& name) {
  for (const Dihedral& g : all())
    if (g.name() == name) return g;
  throw InputError(fmt::format(
      "unknown symmetry '{}' (expected id, rot90, rot180, rot270, mirror, mirror+rot90, mirror+rot180 or mirror+rot270)",
      name));
}

TileSet transform(const TileSet& set, const Dihedral& g) {
  std::vector<Tile4> t = tiles4(set);
  for (Tile4& x : t) {
    if (g.mirror) x = mirror(set.kind(), x);
    for (int q = 0; q < g.quarter_turns; ++q) x = rotate(set.kind(), x);
  }
  return from_tiles4(set.kind(), t, set.name(), set.source());
}

CanonicalForm relabel_canonical(const TileSet& set, std::size_t max_leaves, const Deadline& deadline) {
  CanonicalForm f;
  Canonizer c(set.kind(), tiles4(set), max_leaves, deadline);
  std::vector<Tile4> tiles = c.run(&f.exact);
  assert(tiles.size() == set.size());
  f.text = canonical_text(set.kind(), tiles);
  f.hash = fmt::format("{:016x}", fnv1a64(f.text));
  f.set = from_tiles4(set.kind(), tiles, "enum-" + f.hash, set.source());
  return f;
}

CanonicalForm canonical_form(const TileSet& set, std::size_t max_leaves, const Deadline& deadline) {
  CanonicalForm best;
  bool first = true, exact = true;
  for (const Dihedral& g : Dihedral::all()) {
    CanonicalForm f = relabel_canonical(transform(set, g), max_leaves, deadline);
    exact = exact && f.exact;
    if (first || f.text < best.text) {
      best = std::move(f);
      best.from = g;
      first = false;
    }
  }
  best.exact = exact;
  return best;
}

TileSet set_from_canonical_text(const std::string& text, const std::string& origin) {
  auto bad = [&](const std::string& why) { return InputError(fmt::format("{}: not a canonical tile set ({})", origin, why)); };
  const auto eol = text.find('\n');
  if (eol == std::string::npos) throw bad("no kind line");
  const std::string kind = text.substr(0, eol);
  if (kind != "wang" && kind != "corner") throw bad("kind '" + kind + "'");
  std::vector<Tile4> tiles;
  std::size_t pos = eol + 1;
  while (pos < text.size()) {
    const auto end = text.find('\n', pos);
    if (end == std::string::npos) throw bad("a line without its newline");
    Tile4 t;
    std::size_t p = pos;
    for (int j = 0; j < 4; ++j) {
      std::size_t used = 0;
      unsigned long v = 0;
      try {
        v = std::stoul(text.substr(p, end - p), &used);
      } catch (const std::exception&) {
        throw bad("a colour is not a number");
      }
      if (v > std::uint64_t(kMaxTileSetColour)) throw bad("a colour over the limit");
      t[std::size_t(j)] = Colour(v);
      p += used + (j < 3 ? 1 : 0);
    }
    if (p != end) throw bad("more than four colours on a line");
    tiles.push_back(t);
    pos = end + 1;
  }
  if (tiles.empty()) throw bad("no tiles");
  const std::string hash = fmt::format("{:016x}", fnv1a64(text));
  return from_tiles4(kind == "wang" ? TileKind::Wang : TileKind::Corner, tiles, "enum-" + hash, "");
}

}  // namespace tilekit
