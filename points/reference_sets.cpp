#include "points/reference_sets.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "base/error.hpp"
#include "base/random.hpp"
#include "base/resources.hpp"

namespace tilekit::points {

std::vector<double> bridson_points(const Window& w, double d, std::uint64_t seed, bool torus, int candidates) {
  if (!(d > 0)) throw InputError("Bridson sampling needs a positive minimum distance");
  const double cell = d / std::sqrt(2.0);  // at most one point per cell
  const int nx = int(std::ceil(w.width() / cell)), ny = int(std::ceil(w.height() / cell));
  if (double(nx) * double(ny) > 4e8) throw InputError("Bridson sampling: the window is too large for its grid");
  // On a torus the cells must tile the window exactly; they may be slightly smaller than d / sqrt 2.
  const double cw = w.width() / nx, ch = w.height() / ny;
  std::vector<int> grid(std::size_t(nx) * std::size_t(ny), -1);
  std::vector<Point2> pts;
  std::vector<int> active;
  SplitMix64 rng(seed);
  const double d2 = d * d;
  auto cell_of = [&](Point2 p, int& cx, int& cy) {
    cx = std::min(nx - 1, int((p.x - w.x0) / cw));
    cy = std::min(ny - 1, int((p.y - w.y0) / ch));
  };
  auto fits = [&](Point2 p) {
    int cx, cy;
    cell_of(p, cx, cy);
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) {
        int x = cx + dx, y = cy + dy;
        if (torus) {
          x = (x + nx) % nx, y = (y + ny) % ny;
        } else if (x < 0 || y < 0 || x >= nx || y >= ny) {
          continue;
        }
        const int id = grid[std::size_t(y) * std::size_t(nx) + std::size_t(x)];
        if (id < 0) continue;
        double ex = p.x - pts[std::size_t(id)].x, ey = p.y - pts[std::size_t(id)].y;
        if (torus) ex = wrap_centred(ex, w.width()), ey = wrap_centred(ey, w.height());
        if (ex * ex + ey * ey < d2) return false;
      }
    return true;
  };
  auto add = [&](Point2 p) {
    int cx, cy;
    cell_of(p, cx, cy);
    grid[std::size_t(cy) * std::size_t(nx) + std::size_t(cx)] = int(pts.size());
    active.push_back(int(pts.size()));
    pts.push_back(p);
  };
  add({w.x0 + rng.uniform() * w.width(), w.y0 + rng.uniform() * w.height()});
  while (!active.empty()) {
    const std::size_t k = rng.below(active.size());
    const Point2 p = pts[std::size_t(active[k])];
    bool placed = false;
    for (int t = 0; t < candidates && !placed; ++t) {
      const double radius = d * (1 + rng.uniform()), angle = 2 * std::numbers::pi * rng.uniform();
      Point2 q{p.x + radius * std::cos(angle), p.y + radius * std::sin(angle)};
      if (torus) {
        q = {w.x0 + wrap(q.x - w.x0, w.width()), w.y0 + wrap(q.y - w.y0, w.height())};
      } else if (q.x < w.x0 || q.y < w.y0 || q.x >= w.x1 || q.y >= w.y1) {
        continue;
      }
      if (fits(q)) {
        add(q);
        placed = true;
      }
    }
    if (!placed) {
      active[k] = active.back();
      active.pop_back();
    }
  }
  std::vector<double> out;
  out.reserve(2 * pts.size());
  for (const Point2& p : pts) out.insert(out.end(), {p.x, p.y});
  return out;
}

std::vector<double> white_noise_points(const Window& w, std::uint64_t count, std::uint64_t seed) {
  SplitMix64 rng(seed);
  std::vector<double> out;
  out.reserve(2 * count);
  advise_huge_pages(out.data(), 2 * count * sizeof(double));  // as the tile generator's output
  for (std::uint64_t i = 0; i < count; ++i)
    out.insert(out.end(), {w.x0 + rng.uniform() * w.width(), w.y0 + rng.uniform() * w.height()});
  return out;
}

std::vector<double> grid_points(const Window& w, double density, bool jitter, std::uint64_t seed) {
  if (!(density > 0)) throw RequestError("density", fmt::format("`density` must be positive, got {}", density));
  const double a = 1 / std::sqrt(density);
  const long nx = long(std::ceil(w.width() / a - 1e-9)), ny = long(std::ceil(w.height() / a - 1e-9));
  if (double(nx) * double(ny) > 1e9) throw InputError("the grid would hold over 10^9 points");
  SplitMix64 rng(seed);
  std::vector<double> out;
  out.reserve(std::size_t(2 * nx * ny));
  for (long j = 0; j < ny; ++j)
    for (long i = 0; i < nx; ++i) {
      const double u = jitter ? rng.uniform() : 0.5, v = jitter ? rng.uniform() : 0.5;
      const double x = w.x0 + (double(i) + u) * a, y = w.y0 + (double(j) + v) * a;
      if (x < w.x1 && y < w.y1) out.insert(out.end(), {x, y});
    }
  return out;
}

}  // namespace tilekit::points
