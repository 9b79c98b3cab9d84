#include "aperiodic/maps.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "base/error.hpp"

namespace tilekit {

namespace {

constexpr Colour kNo = Conversion::kNoColour;
using Pegs = std::vector<std::vector<Colour>>;  // (rows+1) x (cols+1) lattice colours

void require_full(const Patch& p, const char* what) {
  if (p.rows <= 0 || p.cols <= 0) throw InputError(fmt::format("{}: empty patch", what));
  if (p.holes()) throw InputError(fmt::format("{}: the patch has {} empty cells", what, p.holes()));
}

// Corner patch from a peg lattice: cell (r,c) is the tile with these four pegs.
Patch pegs_to_patch(const Pegs& pegs, const std::vector<CornerTile>& tiles) {
  std::map<CornerTile, std::int64_t> number;
  for (std::size_t k = 0; k < tiles.size(); ++k) number[tiles[k]] = std::int64_t(k);
  Patch out(int(pegs.size()) - 1, int(pegs[0].size()) - 1);
  for (int r = 0; r < out.rows; ++r)
    for (int c = 0; c < out.cols; ++c) {
      CornerTile t{pegs[r][c + 1], pegs[r + 1][c + 1], pegs[r + 1][c], pegs[r][c]};
      auto it = number.find(t);
      if (it != number.end()) out.at(r, c) = it->second;
    }
  return out;
}

Pegs patch_to_pegs(const Patch& p, const std::vector<CornerTile>& tiles) {
  Pegs pegs(std::size_t(p.rows + 1), std::vector<Colour>(std::size_t(p.cols + 1)));
  for (int r = 0; r < p.rows; ++r)
    for (int c = 0; c < p.cols; ++c) {
      const CornerTile& t = tiles.at(std::size_t(p.at(r, c)));
      pegs[r][c] = t.nw, pegs[r][c + 1] = t.ne, pegs[r + 1][c] = t.sw, pegs[r + 1][c + 1] = t.se;
    }
  return pegs;
}

std::vector<Colour> inverse(const std::vector<Colour>& m) {
  Colour top = 0;
  for (Colour v : m)
    if (v != kNo) top = std::max(top, v + 1);
  std::vector<Colour> inv(top, kNo);
  for (std::size_t k = 0; k < m.size(); ++k)
    if (m[k] != kNo) inv[m[k]] = Colour(k);
  return inv;
}

Colour at_or_no(const std::vector<Colour>& m, Colour c) { return c < m.size() ? m[c] : kNo; }

std::int64_t find_wang(const std::vector<WangTile>& w, const WangTile& t) {
  auto it = std::find(w.begin(), w.end(), t);
  return it == w.end() ? -1 : std::int64_t(it - w.begin());
}

// Horizontal edge colour above row y (y = rows: below the last row) at column x; vertical
// edge colour left of column x (x = cols: right of the last column) in row y.
Colour h_edge(const std::vector<WangTile>& w, const Patch& p, int y, int x) {
  return y < p.rows ? w[std::size_t(p.at(y, x))].n : w[std::size_t(p.at(y - 1, x))].s;
}
Colour v_edge(const std::vector<WangTile>& w, const Patch& p, int y, int x) {
  return x < p.cols ? w[std::size_t(p.at(y, x))].w : w[std::size_t(p.at(y, x - 1))].e;
}

// One row (column) of a translation construction lifted to Wang tiles: a path in the
// transducer whose labels are the given (first, second) peg pairs (dynamic programming
// over the states reachable at each position, then a walk back).
std::vector<std::int64_t> lift_line(const std::vector<WangTile>& w, bool horizontal,
                                    const std::vector<std::pair<Colour, Colour>>& labels) {
  auto from = [&](const WangTile& t) { return horizontal ? t.w : t.n; };
  auto to = [&](const WangTile& t) { return horizontal ? t.e : t.s; };
  auto label = [&](const WangTile& t) { return horizontal ? std::pair{t.n, t.s} : std::pair{t.w, t.e}; };
  const std::size_t n = labels.size();
  // ok[i][k]: tile k can sit at position i with a valid prefix before it.
  std::vector<std::vector<bool>> ok(n, std::vector<bool>(w.size(), false));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < w.size(); ++k) {
      if (label(w[k]) != labels[i]) continue;
      if (i == 0) {
        ok[i][k] = true;
        continue;
      }
      for (std::size_t j = 0; j < w.size() && !ok[i][k]; ++j)
        if (ok[i - 1][j] && to(w[j]) == from(w[k])) ok[i][k] = true;
    }
  std::vector<std::int64_t> line(n, -1);
  for (std::size_t i = n; i-- > 0;) {
    for (std::size_t k = 0; k < w.size(); ++k)
      if (ok[i][k] && (i + 1 == n || from(w[std::size_t(line[i + 1])]) == to(w[k]))) {
        line[i] = std::int64_t(k);
        break;
      }
    if (line[i] < 0) throw InputError("a row of the corner patch does not lift to Wang tiles");
  }
  return line;
}

}  // namespace

std::size_t Patch::holes() const { return std::size_t(std::count(cells.begin(), cells.end(), -1)); }

Patch map_forward(const TileSet& source, const Conversion& conv, const Patch& p) {
  require_full(p, "map_forward");
  if (conv.method == ConversionMethod::ToWang) return p;  // the same grid of tile numbers
  const auto& w = source.wang_tiles();
  auto H = [&](Colour c) { return at_or_no(conv.hmap, c); };
  auto V = [&](Colour c) { return at_or_no(conv.vmap, c); };
  Pegs pegs;
  switch (conv.method) {
    case ConversionMethod::Diagonal:  // pegs at tile centres (thesis Fig. 8.7)
      pegs.assign(std::size_t(p.rows), std::vector<Colour>(std::size_t(p.cols)));
      for (int r = 0; r < p.rows; ++r)
        for (int c = 0; c < p.cols; ++c) pegs[r][c] = conv.tile_colour[std::size_t(p.at(r, c))];
      break;
    case ConversionMethod::Horizontal:  // pegs on horizontal edge midpoints (Fig. 8.8a)
      pegs.assign(std::size_t(p.rows + 1), std::vector<Colour>(std::size_t(p.cols)));
      for (int y = 0; y <= p.rows; ++y)
        for (int c = 0; c < p.cols; ++c) pegs[y][c] = H(h_edge(w, p, y, c));
      break;
    case ConversionMethod::Vertical:  // pegs on vertical edge midpoints (Fig. 8.8b)
      pegs.assign(std::size_t(p.rows), std::vector<Colour>(std::size_t(p.cols + 1)));
      for (int r = 0; r < p.rows; ++r)
        for (int x = 0; x <= p.cols; ++x) pegs[r][x] = V(v_edge(w, p, r, x));
      break;
    case ConversionMethod::Rotation: {  // pegs on all edge midpoints, lattice turned (Fig. 8.9)
      const int n = p.rows;
      if (p.cols != n || n % 2 == 0) throw InputError("rotation map needs an n x n source patch with n odd");
      // Doubled coordinates: edge midpoints have X + Y odd; peg (i,j) sits at
      // X = i + j, Y = n + i - j, so the corner tile's east is (+1,-1) and south (+1,+1).
      pegs.assign(std::size_t(n + 1), std::vector<Colour>(std::size_t(n + 1)));
      for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
          int X = i + j, Y = n + i - j;
          pegs[i][j] = Y % 2 == 0 ? H(h_edge(w, p, Y / 2, (X - 1) / 2)) : V(v_edge(w, p, (Y - 1) / 2, X / 2));
        }
      break;
    }
    case ConversionMethod::Subdivision:  // each tile split in four (Fig. 8.12)
      pegs.assign(std::size_t(2 * p.rows + 1), std::vector<Colour>(std::size_t(2 * p.cols + 1)));
      for (int y = 0; y <= 2 * p.rows; ++y)
        for (int x = 0; x <= 2 * p.cols; ++x) {
          Colour& g = pegs[y][x];
          if (y % 2 == 0 && x % 2 == 0) g = conv.star;
          else if (y % 2 == 0) g = H(h_edge(w, p, y / 2, x / 2));
          else if (x % 2 == 0) g = V(v_edge(w, p, y / 2, x / 2));
          else g = conv.tile_colour[std::size_t(p.at(y / 2, x / 2))];
        }
      break;
    case ConversionMethod::ToWang: break;
  }
  if (pegs.size() < 2 || pegs[0].size() < 2) throw InputError("map_forward: the source patch is too small");
  return pegs_to_patch(pegs, conv.corner);
}

Patch map_backward(const TileSet& source, const Conversion& conv, const Patch& p) {
  require_full(p, "map_backward");
  if (conv.method == ConversionMethod::ToWang) return p;
  if (conv.soundness == Soundness::Unverified || conv.soundness == Soundness::Periodic)
    throw InputError(fmt::format("{} result is {}: no inverse map", method_name(conv.method), soundness_name(conv.soundness)));
  const auto& w = source.wang_tiles();
  const Pegs pegs = patch_to_pegs(p, conv.corner);
  const auto hinv = inverse(conv.hmap), vinv = inverse(conv.vmap), tinv = inverse(conv.tile_colour);
  auto Hs = [&](Colour c) { return at_or_no(hinv, c); };
  auto Vs = [&](Colour c) { return at_or_no(vinv, c); };
  const int R = int(pegs.size()), K = int(pegs[0].size());
  switch (conv.method) {
    case ConversionMethod::Diagonal: {
      Patch out(R, K);
      for (int r = 0; r < R; ++r)
        for (int c = 0; c < K; ++c) out.at(r, c) = std::int64_t(at_or_no(tinv, pegs[r][c]));
      return out;
    }
    case ConversionMethod::Horizontal: {
      Patch out(R - 1, K);
      for (int r = 0; r + 1 < R; ++r) {
        std::vector<std::pair<Colour, Colour>> labels;
        for (int c = 0; c < K; ++c) labels.emplace_back(Hs(pegs[r][c]), Hs(pegs[r + 1][c]));
        auto line = lift_line(w, true, labels);
        for (int c = 0; c < K; ++c) out.at(r, c) = line[std::size_t(c)];
      }
      return out;
    }
    case ConversionMethod::Vertical: {
      Patch out(R, K - 1);
      for (int c = 0; c + 1 < K; ++c) {
        std::vector<std::pair<Colour, Colour>> labels;
        for (int r = 0; r < R; ++r) labels.emplace_back(Vs(pegs[r][c]), Vs(pegs[r][c + 1]));
        auto line = lift_line(w, false, labels);
        for (int r = 0; r < R; ++r) out.at(r, c) = line[std::size_t(r)];
      }
      return out;
    }
    case ConversionMethod::Rotation: {
      const int n = p.rows;
      if (p.cols != n || n % 2 == 0) throw InputError("rotation map needs an n x n corner patch with n odd");
      Patch out(n, n);
      for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) {
          int i = c + r + (1 - n) / 2, j = c - r + (n - 1) / 2;  // the white tile of Wang cell (r,c)
          if (i < 0 || j < 0 || i >= n || j >= n) continue;
          // white tile: nw = W, ne = N, se = E, sw = S
          WangTile t{Hs(pegs[i][j + 1]), Vs(pegs[i + 1][j + 1]), Hs(pegs[i + 1][j]), Vs(pegs[i][j])};
          out.at(r, c) = find_wang(w, t);
        }
      return out;
    }
    case ConversionMethod::Subdivision: {
      if (p.rows % 2 || p.cols % 2) throw InputError("subdivision map needs an even-sized corner patch");
      Patch out(p.rows / 2, p.cols / 2);
      for (int r = 0; r < out.rows; ++r)
        for (int c = 0; c < out.cols; ++c) {
          WangTile t{Hs(pegs[2 * r][2 * c + 1]), Vs(pegs[2 * r + 1][2 * c + 2]), Hs(pegs[2 * r + 2][2 * c + 1]),
                     Vs(pegs[2 * r + 1][2 * c])};
          std::int64_t k = find_wang(w, t);
          if (k >= 0 && conv.tile_colour[std::size_t(k)] != pegs[2 * r + 1][2 * c + 1]) k = -1;
          out.at(r, c) = k;
        }
      return out;
    }
    case ConversionMethod::ToWang: break;
  }
  return p;
}

Tiling patch_to_tiling(const TileSet& set, const Patch& p) {
  require_full(p, "patch_to_tiling");
  Tiling t(set.kind(), set.horizontal_radix(), p.rows, p.cols, false);
  if (set.kind() == TileKind::Wang) t.vertical_colours = set.vertical_radix();
  for (int r = 0; r < p.rows; ++r)
    for (int c = 0; c < p.cols; ++c) t.at(r, c) = set.index_of(std::size_t(p.at(r, c)));
  return t;
}

}  // namespace tilekit
