// Generating points from recursive Wang tiles (Kopf et al. 2006 sec. 3, 5): a base tiling by
// the direct stochastic tiling of compact Wang tiles, ranks against the target density, and
// subdivision where the density asks for more than a level can give.
#include <fmt/format.h>

#include <cmath>

#include "base/error.hpp"
#include "base/parallel.hpp"
#include "points/recursive_tiles.hpp"
#include "tilesets/tile.hpp"

namespace tilekit::points {

RecursiveGenerator::RecursiveGenerator(const RecursiveWangTiles& tiles, HashKind hash, std::uint64_t seed,
                                       std::int64_t period)
    : t_(tiles), hash_(hash, tiles.colours, seed), period_(period) {
  if (period < 0) throw RequestError("period", "`period` must be positive");
}

std::uint32_t RecursiveGenerator::base_type(std::int64_t tx, std::int64_t ty) const {
  const auto h = [&](std::int64_t x, std::int64_t y) {
    if (period_ > 0) x = ((x % period_) + period_) % period_, y = ((y % period_) + period_) % period_;
    return hash_.colour(x, y);
  };
  const std::uint32_t c = t_.colours, nw = h(tx, ty), ne = h(tx + 1, ty), sw = h(tx, ty + 1), se = h(tx + 1, ty + 1);
  // thesis sec. 3.3.2.2: N = NW + NE, E = NE + SE, S = SE + SW, W = SW + NW (mod C)
  const WangTile w{(nw + ne) % c, (ne + se) % c, (se + sw) % c, (sw + nw) % c};
  const int type = t_.type_of(wang_index(w, c, c));
  return std::uint32_t(type);
}

// The points born in `type`'s subdivision set (ranks N and above) whose rank is below the density
// times the tile's area; sub-tiles where the density exceeds what this set gives are visited.
void RecursiveGenerator::visit(std::uint32_t type, double x0, double y0, double size, int level, const Window& w,
                               const DensityFunction& d, int max_levels, std::vector<double>& out) const {
  const double area = size * size;
  const std::uint32_t n = t_.points;
  const int k = t_.n;
  if (d.upper_bound(x0, y0, x0 + size, y0 + size) * area < n) return;  // no rank >= N passes
  const double capacity = double(k * k) * n, sub = size / k;
  for (int j = 0; j < k * k; ++j) {
    const double sx = x0 + (j % k) * sub, sy = y0 + (j / k) * sub;
    if (sx >= w.x1 || sy >= w.y1 || sx + sub <= w.x0 || sy + sub <= w.y0) continue;
    const std::uint32_t st = t_.rule[type][std::size_t(j)];
    const auto& pts = t_.base[st];
    const std::uint32_t* rank = t_.rank[type].data() + std::size_t(j) * n;
    bool deeper = false;
    for (std::uint32_t i = 0; i < n; ++i) {
      const double x = sx + pts[i].x * sub, y = sy + pts[i].y * sub;
      const double want = d(x, y) * area;
      deeper |= want >= capacity;
      if (rank[i] >= n && rank[i] < want && x >= w.x0 && x < w.x1 && y >= w.y0 && y < w.y1)
        out.insert(out.end(), {x, y});
    }
    if (deeper && level + 1 < max_levels) visit(st, sx, sy, sub, level + 1, w, d, max_levels, out);
  }
}

std::vector<double> RecursiveGenerator::generate(const Window& w, const DensityFunction& d, double base_size,
                                                int max_levels, int threads) const {
  if (!(base_size > 0) || !std::isfinite(base_size)) throw RequestError("tile_size", "`tile_size` must be positive");
  if (max_levels < 0 || max_levels > 40) throw RequestError("levels", "`levels` must be 0..40");
  const std::int64_t tx0 = std::int64_t(std::floor(w.x0 / base_size)), tx1 = std::int64_t(std::floor(w.x1 / base_size));
  const std::int64_t ty0 = std::int64_t(std::floor(w.y0 / base_size)), ty1 = std::int64_t(std::floor(w.y1 / base_size));
  if (double(tx1 - tx0 + 1) * double(ty1 - ty0 + 1) > 1e9) throw InputError("the window covers over 10^9 base tiles");
  const std::int64_t rows = ty1 - ty0 + 1;
  std::vector<std::vector<double>> parts(static_cast<std::size_t>(rows));
  const double area = base_size * base_size;
  parallel_for(rows, threads, [&](std::int64_t r) {
    auto& out = parts[std::size_t(r)];
    const std::int64_t ty = ty0 + r;
    for (std::int64_t tx = tx0; tx <= tx1; ++tx) {
      const std::uint32_t type = base_type(tx, ty);
      const double x0 = double(tx) * base_size, y0 = double(ty) * base_size;
      const auto& pts = t_.base[type];
      for (std::uint32_t k = 0; k < pts.size(); ++k) {  // level 0: rank k below the density times the area
        const double x = x0 + pts[k].x * base_size, y = y0 + pts[k].y * base_size;
        if (k < d(x, y) * area && x >= w.x0 && x < w.x1 && y >= w.y0 && y < w.y1)
          out.insert(out.end(), {x, y});
      }
      if (max_levels > 0) visit(type, x0, y0, base_size, 0, w, d, max_levels, out);
    }
  });
  std::vector<double> all;
  for (const auto& p : parts) all.insert(all.end(), p.begin(), p.end());
  return all;
}

}  // namespace tilekit::points
