#include "texture/terrain_tiles.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cstdlib>
#include <functional>
#include <set>
#include <utility>
#include <vector>

#include "base/error.hpp"
#include "base/parallel.hpp"
#include "base/random.hpp"
#include "base/signals.hpp"
#include "texture/graph_cut.hpp"
#include "texture/seam_cut.hpp"

namespace tilekit {

namespace {

// One cut between terrain `left` (positions below the cut) and terrain `right`, row by row: the
// pixels either side of it at position q of row r.
struct SeamRows {
  int rows = 0;
  std::vector<int> lo, hi;
  std::function<const std::uint8_t*(int r, int q)> left, right;
};

// The minimum-error cut of a SeamRows (seam_cut.hpp): at position q of row r, pixels < q take
// the left terrain. It pays the step it shows across it (left(q - 1) to right(q)) and, where it
// moves between rows, the step between the vertical neighbours the move leaves from the two
// terrains (CutBand::rise and fall, as corner_texture_tiles.cpp's end cuts).
CutPath terrain_cut(const SeamRows& s, int n) {
  CutBand b;
  b.rows = s.rows;
  b.width = n;
  b.lo = s.lo;
  b.hi = s.hi;
  const std::size_t size = std::size_t(s.rows) * std::size_t(n);
  b.cost.assign(size, 0);
  b.rise.assign(size, 0);
  b.fall.assign(size, 0);
  for (int r = 0; r < s.rows; ++r) {
    assert(s.lo[std::size_t(r)] >= 1 && s.hi[std::size_t(r)] <= n - 1 && s.lo[std::size_t(r)] <= s.hi[std::size_t(r)]);
    for (int q = s.lo[std::size_t(r)]; q <= s.hi[std::size_t(r)]; ++q) {
      const std::size_t i = std::size_t(r) * std::size_t(n) + std::size_t(q);
      b.cost[i] = channel_step(s.left(r, q - 1), s.right(r, q));
      if (r == 0) continue;
      b.rise[i] = channel_step(s.right(r - 1, q - 1), s.left(r, q - 1));         // from q - 1 above
      if (q + 1 < n) b.fall[i] = channel_step(s.left(r - 1, q), s.right(r, q));  // from q + 1 above
    }
  }
  return min_error_cut(b);
}

class TerrainSynthesis {
 public:
  TerrainSynthesis(std::vector<TextureTileSet> sets, int margin, int threads, TerrainSeams seams)
      : threads_(threads),
        graph_cut_(seams == TerrainSeams::GraphCut),
        sets_(std::move(sets)),
        c_(sets_[0].colours),
        n_(sets_[0].tile_px),
        mb_(margin),
        w_(seams == TerrainSeams::Straight ? 0 : n_ / 4) {}

  TerrainTileSet run() {
    border_cuts();
    TerrainTileSet r;
    TextureTileSet& s = r.set;
    s.kind = TileKind::Corner;
    s.colours = c_;
    s.tile_px = n_;
    s.method = "terrain-corner";
    s.thin_bands = std::any_of(sets_.begin(), sets_.end(), [](const TextureTileSet& x) { return x.thin_bands; });
    const std::size_t count = sets_[0].tiles.size(), px = std::size_t(n_) * std::size_t(n_);
    // source ids: every terrain's shared samples first (terrain k's from shared_offset[k]), then
    // terrain k's centre patch of tile t (marked by kCentreBit while the tiles are composed)
    std::vector<std::uint32_t> shared_offset(c_);
    for (std::uint32_t k = 0; k < c_; ++k) {
      shared_offset[k] = s.shared_sources;
      s.shared_sources += sets_[k].shared_sources;
      s.samples.insert(s.samples.end(), sets_[k].samples.begin(), sets_[k].samples.end());
    }
    s.tiles.assign(count, Image{n_, n_, std::vector<std::uint8_t>(px * 4)});
    s.sources.assign(count, std::vector<std::uint32_t>(px, 0));
    std::vector<std::vector<std::size_t>> shown(count, std::vector<std::size_t>(c_, 0));
    std::vector<std::pair<double, std::size_t>> seam(count);  // per tile: summed step across terrains, pairs
    parallel_for(std::int64_t(count), threads_, [&](std::int64_t ti) {
      throw_if_interrupted();
      const TileIndex t = TileIndex(ti);
      const std::vector<Colour> label = tile_labels(t);
      for (std::size_t i = 0; i < px; ++i) {
        const Colour k = label[i];
        const TextureTileSet& from = sets_[k];
        std::copy_n(from.tiles[t].pixels.data() + 4 * i, 4, s.tiles[t].pixels.data() + 4 * i);
        const std::uint32_t src = from.sources[t][i];
        s.sources[t][i] = src < from.shared_sources
                              ? shared_offset[k] + src
                              : kCentreBit | (std::uint32_t(k * count) + (src - from.shared_sources));
        ++shown[t][k];
      }
      // the step shown between 4-neighbours of different terrains
      const int n = n_;
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const std::size_t i = std::size_t(y) * std::size_t(n) + std::size_t(x);
          for (const std::size_t j : {x + 1 < n ? i + 1 : i, y + 1 < n ? i + std::size_t(n) : i})
            if (j != i && label[i] != label[j]) {
              seam[t].first += channel_step(s.tiles[t].pixels.data() + 4 * i, s.tiles[t].pixels.data() + 4 * j);
              ++seam[t].second;
            }
        }
    });
    // terrain k's centre patch of tile t: shared_sources + k * count + t
    for (auto& v : s.sources)
      for (std::uint32_t& id : v)
        if (id & kCentreBit) id = s.shared_sources + (id & ~kCentreBit);
    r.texel_fraction.assign(c_, 0);
    std::size_t shared = 0;
    for (std::size_t t = 0; t < count; ++t) {
      for (std::uint32_t k = 0; k < c_; ++k) r.texel_fraction[k] += double(shown[t][k]) / double(px * count);
      for (std::uint32_t id : s.sources[t]) shared += id < s.shared_sources;
    }
    s.shared_fraction = double(shared) / double(px * count);
    double steps = 0;
    std::size_t pairs = 0;
    for (const auto& [step, count_pairs] : seam) steps += step, pairs += count_pairs;
    r.seam_step = pairs ? steps / double(pairs) : 0.0;
    for (const TextureTileSet& x : sets_) {
      r.cut_error.push_back(x.cut_error);
      s.cut_error += x.cut_error;
      s.cut_error_initial += x.cut_error_initial;
      s.centre_cost += x.centre_cost / double(c_);
      s.overlap += x.overlap / double(c_);
    }
    return r;
  }

 private:
  static constexpr std::uint32_t kCentreBit = 0x80000000u;

  const std::uint8_t* px(Colour k, TileIndex t, int x, int y) const { return sets_[k].tiles[t].at(x, y); }

  // The cut across every border whose two corners differ, per ordered pair: rows r = 0 .. 2 mb - 1
  // across the border (r < mb: the last mb rows of the tile before it, r >= mb: the first mb of
  // the tile after it), from the tile whose two opposite borders both carry the pair.
  void border_cuts() {
    hcut_.assign(std::size_t(c_) * c_, {});
    vcut_.assign(std::size_t(c_) * c_, {});
    for (Colour a = 0; a < c_; ++a)
      for (Colour b = 0; b < c_; ++b) {
        if (a == b) continue;
        SeamRows s;
        s.rows = 2 * mb_;
        s.lo.assign(std::size_t(s.rows), n_ / 2 - w_);
        s.hi.assign(std::size_t(s.rows), n_ / 2 + w_);
        auto across = [&](int r) { return r < mb_ ? n_ - mb_ + r : r - mb_; };
        // horizontal border, a west of b: the tile a b / a b
        const TileIndex u = corner_index(CornerTile{b, b, a, a}, c_);
        s.left = [&, u, a](int r, int q) { return px(a, u, q, across(r)); };
        s.right = [&, u, b](int r, int q) { return px(b, u, q, across(r)); };
        CutPath h = terrain_cut(s, n_);
        // vertical border, a north of b: the tile a a / b b
        const TileIndex v = corner_index(CornerTile{a, b, b, a}, c_);
        s.left = [&, v, a](int r, int q) { return px(a, v, across(r), q); };
        s.right = [&, v, b](int r, int q) { return px(b, v, across(r), q); };
        CutPath vc = terrain_cut(s, n_);
        hcut_[std::size_t(a) * c_ + b] = std::move(h.pos);
        vcut_[std::size_t(a) * c_ + b] = std::move(vc.pos);
      }
  }

  // A cut inside tile t from `first` (the border's cut, its last row next to the tile's inside, or
  // -1 for none) over rows whose pixels `left`/`right` give, each row r within lo..hi, ending
  // within one of `last` (or anywhere for -1).
  std::vector<int> inner_cut(SeamRows s, int first, int last) const {
    if (first >= 0) {
      s.lo[0] = std::max(s.lo[0], first - 1);
      s.hi[0] = std::min(s.hi[0], first + 1);
    }
    if (last >= 0) {
      s.lo.back() = std::max(s.lo.back(), last - 1);
      s.hi.back() = std::min(s.hi.back(), last + 1);
    }
    return terrain_cut(s, n_).pos;
  }

  // The terrain of every texel of tile t (row-major): the cuts, refined by a graph cut in a tile
  // of two terrains.
  std::vector<Colour> tile_labels(TileIndex t) const {
    std::vector<Colour> label = cut_labels(t);
    const CornerTile c = corner_tile(t, c_);
    const std::set<Colour> terrains = {c.nw, c.ne, c.sw, c.se};
    if (graph_cut_ && terrains.size() == 2) refine(t, *terrains.begin(), *terrains.rbegin(), label);
    return label;
  }

  // Graph-cut patch merging (graph_cut.hpp, Kwatra et al. 2003) of S_b's tile over S_a's where
  // the cuts put terrain b: free in a band of n/8 (Chebyshev) around the cuts' boundary, at least
  // `margin` from every border (so the texels a border decides stay as they are), b forced
  // everywhere else the cuts put it. The frame the graph cut may not hold (the first column and
  // row, the last two) shows what the cuts chose.
  void refine(TileIndex t, Colour a, Colour b, std::vector<Colour>& label) const {
    const int n = n_, reach = std::max(1, n / 8);
    const std::size_t px = std::size_t(n) * std::size_t(n);
    auto index = [n](int x, int y) { return std::size_t(y) * std::size_t(n) + std::size_t(x); };
    std::vector<std::uint8_t> near(px, 0);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const bool edge = (x + 1 < n && label[index(x, y)] != label[index(x + 1, y)]) ||
                          (y + 1 < n && label[index(x, y)] != label[index(x, y + 1)]);
        if (!edge) continue;
        for (int v = std::max(0, y - reach); v <= std::min(n - 1, y + reach); ++v)
          for (int u = std::max(0, x - reach); u <= std::min(n - 1, x + reach); ++u) near[index(u, v)] = 1;
      }
    Image A = sets_[a].tiles[t];
    const Image& B = sets_[b].tiles[t];
    std::vector<std::uint8_t> region(px, 0), forced(px, 0);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const std::size_t i = index(x, y);
        const int depth = std::min({x, y, n - 1 - x, n - 1 - y});
        if (x < 1 || y < 1 || x > n - 3 || y > n - 3) {  // graph_cut_merge's frame
          if (label[i] == b) std::copy_n(B.at(x, y), 4, A.at(x, y));
        } else if (near[i] && depth >= mb_) {
          region[i] = 1;
        } else if (label[i] == b) {
          region[i] = forced[i] = 1;
        }
      }
    const GraphCutResult r = graph_cut_merge(A, B, region, forced);
    for (std::size_t i = 0; i < px; ++i)
      if (region[i]) label[i] = r.take_new[i] ? b : a;  // forced texels take b (the cut honours them)
  }

  // The terrain of every texel of tile t by the cuts alone.
  std::vector<Colour> cut_labels(TileIndex t) const {
    const CornerTile c = corner_tile(t, c_);
    const int n = n_, h = n / 2, mb = mb_;
    const bool N = c.nw != c.ne, S = c.sw != c.se, W = c.nw != c.sw, E = c.ne != c.se;
    std::vector<Colour> label(std::size_t(n) * std::size_t(n), c.nw);
    auto at = [&](int x, int y) -> Colour& { return label[std::size_t(y) * std::size_t(n) + std::size_t(x)]; };
    const std::vector<int>& north = hcut_[std::size_t(c.nw) * c_ + c.ne];  // rows mb.. are this tile's 0..
    const std::vector<int>& south = hcut_[std::size_t(c.sw) * c_ + c.se];  // rows ..mb-1 are its n-mb..
    const std::vector<int>& west = vcut_[std::size_t(c.nw) * c_ + c.sw];
    const std::vector<int>& east = vcut_[std::size_t(c.ne) * c_ + c.se];
    // rows of a cut along y (vertical, left terrain l, right terrain r) or along x (horizontal,
    // above terrain l, below r), from row `from` in steps of `step`, `rows` of them
    auto rows_of = [&](bool vertical, Colour l, Colour r, int from, int step, int rows) {
      SeamRows s;
      s.rows = rows;
      s.lo.assign(std::size_t(rows), h - w_);
      s.hi.assign(std::size_t(rows), h + w_);
      if (vertical) {
        s.left = [=, this](int k, int q) { return px(l, t, q, from + step * k); };
        s.right = [=, this](int k, int q) { return px(r, t, q, from + step * k); };
      } else {
        s.left = [=, this](int k, int q) { return px(l, t, from + step * k, q); };
        s.right = [=, this](int k, int q) { return px(r, t, from + step * k, q); };
      }
      return s;
    };
    if (!N && !S && !W && !E) return label;
    if (!N && !S) {  // a a / b b: one cut from the west border to the east one
      std::vector<int> cut(static_cast<std::size_t>(n), 0);
      for (int x = 0; x < mb; ++x) cut[std::size_t(x)] = west[std::size_t(mb + x)];
      for (int x = n - mb; x < n; ++x) cut[std::size_t(x)] = east[std::size_t(x - (n - mb))];
      const std::vector<int> mid = inner_cut(rows_of(false, c.nw, c.sw, mb, 1, n - 2 * mb), west.back(), east.front());
      std::copy(mid.begin(), mid.end(), cut.begin() + mb);
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) at(x, y) = y < cut[std::size_t(x)] ? c.nw : c.sw;
      return label;
    }
    if (!W && !E) {  // a b / a b: one cut from the north border to the south one
      std::vector<int> cut(static_cast<std::size_t>(n), 0);
      for (int y = 0; y < mb; ++y) cut[std::size_t(y)] = north[std::size_t(mb + y)];
      for (int y = n - mb; y < n; ++y) cut[std::size_t(y)] = south[std::size_t(y - (n - mb))];
      const std::vector<int> mid = inner_cut(rows_of(true, c.nw, c.ne, mb, 1, n - 2 * mb), north.back(), south.front());
      std::copy(mid.begin(), mid.end(), cut.begin() + mb);
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) at(x, y) = x < cut[std::size_t(y)] ? c.nw : c.ne;
      return label;
    }
    // Four half-cuts, each in its own triangle between a border and the centre. In row y of the
    // north triangle (y < h) its texels are x = y .. n-1-y, so a cut at q in y+1 .. n-1-y leaves
    // both terrains a texel there and reaches q = h at row h-1; the others alike.
    std::vector<int> vn(std::size_t(h), h), vs(std::size_t(h), h), hw(std::size_t(h), h), he(std::size_t(h), h);
    auto half = [&](bool vertical, Colour l, Colour r, const std::vector<int>& border, bool far_side,
                    std::vector<int>& out) {
      // far_side: the border at row n (south or east): rows run inwards from n-1
      for (int k = 0; k < mb; ++k)
        out[std::size_t(k)] = far_side ? border[std::size_t(mb - 1 - k)] : border[std::size_t(mb + k)];
      const int rows = h - mb;
      SeamRows s = far_side ? rows_of(vertical, l, r, n - 1 - mb, -1, rows) : rows_of(vertical, l, r, mb, 1, rows);
      for (int k = 0; k < rows; ++k) {
        const int y = far_side ? n - 1 - mb - k : mb + k;  // the row in the tile
        const int d = far_side ? y - h : h - 1 - y;        // rows between it and the centre
        s.lo[std::size_t(k)] = std::max(h - w_, h - d);
        s.hi[std::size_t(k)] = std::min(h + w_, h + d);
      }
      const std::vector<int> mid = inner_cut(std::move(s), far_side ? border.front() : border.back(), -1);
      std::copy(mid.begin(), mid.end(), out.begin() + mb);
    };
    if (N) half(true, c.nw, c.ne, north, false, vn);
    if (S) half(true, c.sw, c.se, south, true, vs);
    if (W) half(false, c.nw, c.sw, west, false, hw);
    if (E) half(false, c.ne, c.se, east, true, he);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const int dx = 2 * x - n + 1, dy = 2 * y - n + 1;  // doubled offsets from the centre
        if (std::abs(dx) <= std::abs(dy))
          at(x, y) = dy < 0 ? (x < vn[std::size_t(y)] ? c.nw : c.ne) : (x < vs[std::size_t(n - 1 - y)] ? c.sw : c.se);
        else
          at(x, y) = dx < 0 ? (y < hw[std::size_t(x)] ? c.nw : c.sw) : (y < he[std::size_t(n - 1 - x)] ? c.ne : c.se);
      }
    return label;
  }

  int threads_;
  bool graph_cut_;
  std::vector<TextureTileSet> sets_;
  std::uint32_t c_;
  int n_, mb_, w_;                             // w_: how far a cut may stray from the tile's middle line
  std::vector<std::vector<int>> hcut_, vcut_;  // by a * C + b
};

bool valid_terrain_name(const std::string& s) {
  return !s.empty() && s.size() <= 64 && std::all_of(s.begin(), s.end(), [](char ch) {
    return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '-' || ch == '_' ||
           ch == '.';
  });
}

}  // namespace

void check_terrain_options(const std::vector<TerrainTexture>& terrains, const SynthesisOptions& o) {
  if (terrains.size() < kMinTerrains || terrains.size() > kMaxTerrains)
    throw InputError(
        fmt::format("a terrain set needs {} to {} terrains, got {}", kMinTerrains, kMaxTerrains, terrains.size()));
  if (o.kind != TileKind::Corner) throw InputError("terrain sets are corner sets (corner colour k: terrain k)");
  std::set<std::string> names;
  for (const TerrainTexture& t : terrains) {
    if (!valid_terrain_name(t.name))
      throw InputError(fmt::format("terrain name '{}': use 1-64 letters, digits, '-', '_' or '.'", t.name));
    if (!names.insert(t.name).second) throw InputError(fmt::format("terrain '{}' is named twice", t.name));
    SynthesisOptions one = o;
    one.colours = std::uint32_t(terrains.size());
    check_synthesis_options(t.exemplar, one);
  }
}

TerrainTileSet synthesize_terrain_tiles(const std::vector<TerrainTexture>& terrains, SynthesisOptions o,
                                        TerrainSeams seams) {
  o.colours = std::uint32_t(terrains.size());
  check_terrain_options(terrains, o);
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<TextureTileSet> sets;
  int margin = o.tile_px;
  for (std::uint32_t k = 0; k < o.colours; ++k) {
    SynthesisOptions one = o;
    one.seed = derive_seed(o.seed, k);
    one.record_coords = false;
    sets.push_back(synthesize_corner_tiles(terrains[k].exemplar, one));
    margin = std::min(margin, TileGeometry(o.tile_px, sets.back().thin_bands).margin);
  }
  TerrainTileSet r = TerrainSynthesis(std::move(sets), margin, o.threads, seams).run();
  r.set.seed = o.seed;
  for (const TerrainTexture& t : terrains) {
    r.names.push_back(t.name);
    r.terrain_step += t.exemplar.mean_step / double(terrains.size());
  }
  r.set.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace tilekit
