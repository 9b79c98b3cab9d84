#include "solver/symmetry.hpp"

#include <algorithm>
#include <cassert>
#include <numeric>

namespace tilekit {

namespace {

bool is_complete(const TileSet& set) {
  return set.size() == complete_size(set.horizontal_radix(), set.vertical_radix());
}

std::vector<std::vector<std::uint32_t>> permutations(std::uint32_t n) {
  std::vector<std::uint32_t> p(n);
  std::iota(p.begin(), p.end(), 0u);
  std::vector<std::vector<std::uint32_t>> all;
  do all.push_back(p);
  while (std::next_permutation(p.begin(), p.end()));
  return all;
}

std::uint64_t factorial(std::uint32_t n) {
  std::uint64_t f = 1;
  for (std::uint32_t i = 2; i <= n; ++i) f *= i;
  return f;
}

}  // namespace

std::optional<PackingSymmetry> PackingSymmetry::for_problem(const TilingProblem& p, std::size_t max_order) {
  // Window tori (de Bruijn tori) get no orbits: their symmetries are not this group's.
  if (!p.packing || !p.torus || p.set.kind() == TileKind::Window || !is_complete(p.set)) return std::nullopt;
  const TileSet& set = p.set;
  const std::uint32_t ch = set.horizontal_radix(), cv = set.vertical_radix();
  const bool wang = set.kind() == TileKind::Wang;
  const bool square = p.rows == p.cols && (!wang || ch == cv);
  std::uint64_t colour_part = wang ? factorial(ch) * factorial(cv) : factorial(ch);
  if (colour_part * (square ? 8 : 4) > max_order) return std::nullopt;

  PackingSymmetry s;
  s.rows_ = p.rows, s.cols_ = p.cols, s.cells_ = p.rows * p.cols;
  const std::size_t T = set.size();
  auto perms_h = permutations(ch);
  auto perms_v = wang ? permutations(cv) : std::vector<std::vector<std::uint32_t>>{{}};
  s.tiles_ = T;
  s.colour_maps_ = perms_h.size() * perms_v.size();
  s.tile_maps_.reserve(colour_part * (square ? 8 : 4) * T);
  for (int tr = 0; tr < (square ? 2 : 1); ++tr)
    for (int fr = 0; fr < 2; ++fr)
      for (int fc = 0; fc < 2; ++fc) {
        // Cell map: transpose, then flip rows, then flip columns (a torus symmetry up to translation).
        std::vector<int> cm(std::size_t(s.cells_));
        for (int r = 0; r < p.rows; ++r)
          for (int c = 0; c < p.cols; ++c) {
            int rr = tr ? c : r, cc = tr ? r : c;
            if (fr) rr = p.rows - 1 - rr;
            if (fc) cc = p.cols - 1 - cc;
            cm[std::size_t(r * p.cols + c)] = rr * p.cols + cc;
          }
        std::vector<int> icm(cm.size());
        for (std::size_t x = 0; x < cm.size(); ++x) icm[std::size_t(cm[x])] = int(x);
        s.cell_maps_.push_back(std::move(cm));
        s.inverse_cells_.push_back(std::move(icm));
        // The geometric image of every tile, decoded once per geometry; the colour maps below
        // only relabel its colours.
        std::vector<WangTile> geo_wang(wang ? T : 0);
        std::vector<CornerTile> geo_corner(wang ? 0 : T);
        for (TileIndex i = 0; i < T; ++i) {
          if (wang) {
            WangTile t = wang_tile(i, ch, cv), u = t;
            if (tr) u = {t.w, t.s, t.e, t.n};  // N'=W, E'=S, S'=E, W'=N
            if (fr) std::swap(u.n, u.s);
            if (fc) std::swap(u.e, u.w);
            geo_wang[i] = u;
          } else {
            CornerTile u = corner_tile(i, ch);
            if (tr) std::swap(u.ne, u.sw);
            if (fr) std::swap(u.nw, u.sw), std::swap(u.ne, u.se);
            if (fc) std::swap(u.nw, u.ne), std::swap(u.sw, u.se);
            geo_corner[i] = u;
          }
        }
        for (const auto& ph : perms_h)
          for (const auto& pv : perms_v) {
            const std::size_t start = s.tile_maps_.size();
            for (TileIndex i = 0; i < T; ++i) {
              TileIndex image;
              if (wang) {
                const WangTile& u = geo_wang[i];
                image = wang_index(WangTile{ph[u.n], pv[u.e], ph[u.s], pv[u.w]}, ch, cv);
              } else {
                const CornerTile& u = geo_corner[i];
                image = corner_index(CornerTile{ph[u.ne], ph[u.se], ph[u.sw], ph[u.nw]}, ch);
              }
              s.tile_maps_.push_back(image);
              if (image == 0) s.inverse_tile0_.push_back(i);
            }
            // Each map is a bijection of the complete set, so exactly one tile maps to index 0.
            assert(s.inverse_tile0_.size() == (start / T) + 1);
            (void)start;
          }
      }
  assert(s.order() == s.cell_maps_.size() * s.colour_maps_);
  return s;
}

int PackingSymmetry::compare_image(std::size_t h, const std::vector<TileIndex>& cells,
                                   const std::vector<TileIndex>& ref) const {
  const TileIndex* tm = tile_map(h);
  const auto& icm = inverse_cell_map(h);
  // The anchor (index 0) of the image comes from the cell holding inverse_tile0_[h].
  TileIndex pre = inverse_tile0_[h];
  int src = int(std::find(cells.begin(), cells.end(), pre) - cells.begin());
  int a = cell_map(h)[std::size_t(src)];
  int ar = a / cols_, ac = a % cols_;
  for (int r = 0; r < rows_; ++r)
    for (int c = 0; c < cols_; ++c) {
      int y = ((r + ar) % rows_) * cols_ + (c + ac) % cols_;
      TileIndex v = tm[cells[std::size_t(icm[std::size_t(y)])]];
      TileIndex w = ref[std::size_t(r * cols_ + c)];
      if (v != w) return v < w ? -1 : 1;
    }
  return 0;
}

std::vector<TileIndex> PackingSymmetry::image(std::size_t h, const std::vector<TileIndex>& cells) const {
  std::vector<TileIndex> g(cells.size());
  const TileIndex* tm = tile_map(h);
  const auto& cm = cell_map(h);
  for (std::size_t x = 0; x < cells.size(); ++x) g[std::size_t(cm[x])] = tm[cells[x]];
  return g;
}

bool PackingSymmetry::is_canonical(const std::vector<TileIndex>& cells, std::uint64_t* stabiliser) const {
  std::uint64_t stab = 0;
  for (std::size_t h = 0; h < order(); ++h) {
    int cmp = compare_image(h, cells, cells);
    if (cmp < 0) return false;
    stab += cmp == 0;
  }
  if (stabiliser) *stabiliser = stab;
  return true;
}

Tiling PackingSymmetry::normal_form(const Tiling& t) const {
  int pos = int(std::find(t.cells.begin(), t.cells.end(), TileIndex{0}) - t.cells.begin());
  if (pos == int(t.cells.size())) return t;
  return translate(t, -(pos / t.cols), -(pos % t.cols));
}

Tiling PackingSymmetry::canonical(const Tiling& t, std::uint64_t* orbit_size) const {
  Tiling best = normal_form(t);
  std::vector<TileIndex> start = best.cells;
  for (std::size_t h = 0; h < order(); ++h)
    if (compare_image(h, start, best.cells) < 0) {
      Tiling img = best;
      img.cells = image(h, start);
      best.cells = normal_form(img).cells;
    }
  if (orbit_size) {
    std::uint64_t stab = 0;
    for (std::size_t h = 0; h < order(); ++h) stab += compare_image(h, best.cells, best.cells) == 0;
    *orbit_size = full_order() / std::max<std::uint64_t>(stab, 1);
  }
  return best;
}

Tiling translate(const Tiling& t, int dr, int dc) {
  Tiling out = t;
  for (int r = 0; r < t.rows; ++r)
    for (int c = 0; c < t.cols; ++c)
      out.at(((r + dr) % t.rows + t.rows) % t.rows, ((c + dc) % t.cols + t.cols) % t.cols) = t.at(r, c);
  return out;
}

}  // namespace tilekit
