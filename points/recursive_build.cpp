// Building recursive Wang tiles (Kopf et al. 2006): see recursive_tiles.hpp for the steps.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "base/error.hpp"
#include "base/parallel.hpp"
#include "base/progress.hpp"
#include "base/random.hpp"
#include "points/recursive_internal.hpp"
#include "points/recursive_tiles.hpp"
#include "tilesets/tile.hpp"

namespace tilekit::points {

using recursive::RankedPoint;

int RecursiveWangTiles::type_of(std::uint32_t wang_index) const {
  for (std::size_t t = 0; t < wang.size(); ++t)
    if (wang[t] == wang_index) return int(t);
  return -1;
}

namespace {

constexpr std::uint32_t kColours = 2;

std::vector<RankedPoint> turned(std::vector<RankedPoint> pts, int q) {
  for (auto& p : pts) p.p = rotate_quarter(p.p, q, {0.5, 0.5});
  return pts;
}

// Step 4: one n-colour sequence per edge colour and direction, summing to the colour (mod 2),
// then each tile's interior by scanline: E free (random) except in the last column, S = E + W - N.
std::vector<std::vector<std::uint32_t>> subdivision_rules(const RecursiveWangTiles& t, SplitMix64& rng) {
  const int n = t.n;
  std::vector<std::uint32_t> seq[2][kColours];  // [horizontal/vertical][colour]
  for (auto& dir : seq)
    for (std::uint32_t c = 0; c < kColours; ++c) {
      auto& s = dir[c];
      std::uint32_t sum = 0;
      for (int i = 0; i + 1 < n; ++i) s.push_back(std::uint32_t(rng.below(kColours))), sum += s.back();
      s.push_back((c + kColours - sum % kColours) % kColours);
    }
  std::vector<std::vector<std::uint32_t>> rules(t.types());
  for (std::size_t type = 0; type < t.types(); ++type) {
    const WangTile base = wang_tile(t.wang[type], kColours, kColours);
    std::vector<WangTile> cell(std::size_t(n) * std::size_t(n));
    for (int r = 0; r < n; ++r)
      for (int q = 0; q < n; ++q) {
        WangTile& w = cell[std::size_t(r * n + q)];
        w.n = r == 0 ? seq[0][base.n][std::size_t(q)] : cell[std::size_t((r - 1) * n + q)].s;
        w.w = q == 0 ? seq[1][base.w][std::size_t(r)] : cell[std::size_t(r * n + q - 1)].e;
        if (q == n - 1)
          w.e = seq[1][base.e][std::size_t(r)];
        else if (r == n - 1)
          w.e = (seq[0][base.s][std::size_t(q)] + w.n + kColours - w.w) % kColours;
        else
          w.e = std::uint32_t(rng.below(kColours));
        w.s = (w.e + w.w + kColours - w.n) % kColours;  // thesis sec. 3.3.2.2: N + S = E + W (mod C)
        if (r == n - 1 && w.s != seq[0][base.s][std::size_t(q)])
          throw std::logic_error("subdivision rule does not close (colour parity)");
        const int sub = t.type_of(wang_index(w, kColours, kColours));
        if (sub < 0) throw std::logic_error("subdivision produced a tile outside the compact set");
        rules[type].push_back(std::uint32_t(sub));
      }
  }
  return rules;
}

// The subdivision set of a type: sub-tile j's point i at index j N + i, in tile coordinates.
std::vector<Point2> subdivision_set(const RecursiveWangTiles& t, const std::vector<std::vector<Point2>>& base,
                                    std::size_t type) {
  std::vector<Point2> out;
  const int n = t.n;
  for (int j = 0; j < n * n; ++j)
    for (const Point2& p : base[t.rule[type][std::size_t(j)]]) out.push_back({(j % n + p.x) / n, (j / n + p.y) / n});
  return out;
}

// The seed of step `step`, item i, of a build with seed `seed`.
std::uint64_t step_seed(std::uint64_t seed, std::uint64_t step, std::uint64_t i) {
  return derive_seed(derive_seed(seed, step), i);
}

// Steps 1-3: progressive sources ([0, 2) horizontal edge colours, [2, 4) vertical, then one per
// tile), merged N, E, S, W into each tile's own source and ranked progressively; every tile keeps
// exactly N points, the first N by rank.
void build_base_tiles(RecursiveWangTiles& t, const RecursiveTileParams& p, ProgressReporter& progress) {
  const std::size_t types = t.wang.size();
  const std::uint32_t n = p.points;
  // The sources hold 6% more than N, so that every merged tile has N to keep.
  std::vector<std::vector<RankedPoint>> source(4 + types);
  const std::uint32_t source_points = n + n / 16 + 8;
  parallel_for(std::int64_t(source.size()), p.threads, [&](std::int64_t s) {
    const auto pts = recursive::progressive_source(source_points, step_seed(p.seed, 1, std::uint64_t(s)));
    for (std::uint32_t r = 0; r < pts.size(); ++r) source[std::size_t(s)].push_back({pts[r], std::uint32_t(s), r});
  });
  progress.add(4);
  t.base.resize(types);
  parallel_for(std::int64_t(types), p.threads, [&](std::int64_t type) {
    const WangTile w = wang_tile(t.wang[std::size_t(type)], kColours, kColours);
    std::vector<RankedPoint> tile = source[4 + std::size_t(type)];
    // Turns that bring each edge to the east: E 0, N 1, W 2, S 3 (rotate_quarter about the centre).
    const std::pair<int, std::uint32_t> edges[4] = {{1, w.n}, {0, 2 + w.e}, {3, w.s}, {2, 2 + w.w}};
    for (const auto& [q, src] : edges)
      tile = turned(recursive::merge_east(turned(tile, q), turned(source[src], q)), -q);
    t.base[std::size_t(type)] = recursive::progressive_order(tile, step_seed(p.seed, 2, std::uint64_t(type)));
    progress.add(1);
  });
  for (auto& b : t.base) {
    if (b.size() < n)
      throw RequestError("seed",
                         fmt::format("a merged tile holds only {} of {} points; try another `seed`", b.size(), n));
    b.resize(n);
  }
}

// Step 5, first part (Fig. 8, alpha = 0.1, epsilon = 1e-6): base points move towards their
// nearest subdivision points, all tiles at once. `cell`: the neighbour grid's cell size.
void relax_towards_subdivision(RecursiveWangTiles& t, double cell) {
  constexpr double kAlpha = 0.1, kEpsilon = 1e-6;
  constexpr int kMaxIterations = 400;
  for (int it = 0; it < kMaxIterations; ++it) {
    double moved = 0;
    std::vector<std::vector<Point2>> next = t.base;
    for (std::size_t type = 0; type < t.types(); ++type) {
      const auto sub = subdivision_set(t, t.base, type);
      PointGrid grid(0, 0, 1, 1, cell, false);
      for (std::size_t i = 0; i < sub.size(); ++i) grid.insert(int(i), sub[i]);
      for (std::uint32_t k = 0; k < t.points; ++k) {
        const Point2 q = t.base[type][k], s = sub[std::size_t(grid.nearest(q, sub))];
        next[type][k] = {q.x + kAlpha * (s.x - q.x), q.y + kAlpha * (s.y - q.y)};
        moved += std::sqrt(squared_distance(q, s));
      }
    }
    t.base = std::move(next);
    t.relax_iterations = it + 1;
    if (moved < kEpsilon) break;
  }
}

// Step 5, second part: unique matches between base points and subdivision points, closest pairs
// first; match[type][k] is the subdivision point of base point k.
std::vector<std::vector<std::size_t>> match_subdivision(const RecursiveWangTiles& t, double cell) {
  const std::uint32_t n = t.points;
  std::vector<std::vector<std::size_t>> match(t.types(), std::vector<std::size_t>(n));
  for (std::size_t type = 0; type < t.types(); ++type) {
    const auto sub = subdivision_set(t, t.base, type);
    std::vector<std::tuple<double, std::uint32_t, std::size_t>> pairs;
    PointGrid grid(0, 0, 1, 1, cell, false);
    for (std::size_t i = 0; i < sub.size(); ++i) grid.insert(int(i), sub[i]);
    for (std::uint32_t k = 0; k < n; ++k)
      grid.for_near(t.base[type][k], 2, [&](int i) {
        pairs.emplace_back(squared_distance(t.base[type][k], sub[std::size_t(i)]), k, std::size_t(i));
      });
    std::sort(pairs.begin(), pairs.end());
    std::vector<char> base_done(n, 0), sub_used(sub.size(), 0);
    for (const auto& [d2, k, i] : pairs)
      if (!base_done[k] && !sub_used[i]) base_done[k] = 1, sub_used[i] = 1, match[type][k] = i;
    for (std::uint32_t k = 0; k < n; ++k)
      if (!base_done[k]) {  // no free subdivision point nearby: the nearest free one anywhere
        std::size_t best = 0;
        double bd = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < sub.size(); ++i)
          if (!sub_used[i] && squared_distance(t.base[type][k], sub[i]) < bd)
            bd = squared_distance(t.base[type][k], sub[i]), best = i;
        sub_used[best] = 1, match[type][k] = best;
      }
  }
  return match;
}

// Step 5, last part: every base point snaps onto its match, a contraction by 1/n iterated to
// double precision; t.relax_residual is how far that moved a point.
void snap_to_matches(RecursiveWangTiles& t, const std::vector<std::vector<std::size_t>>& match) {
  const auto before = t.base;
  for (int it = 0; it < 200; ++it) {
    double change = 0;
    std::vector<std::vector<Point2>> next = t.base;
    for (std::size_t type = 0; type < t.types(); ++type) {
      const auto sub = subdivision_set(t, t.base, type);
      for (std::uint32_t k = 0; k < t.points; ++k) {
        next[type][k] = sub[match[type][k]];
        change = std::max(change, squared_distance(next[type][k], t.base[type][k]));
      }
    }
    t.base = std::move(next);
    if (change == 0) break;
  }
  // A chain of matches can converge onto a tile border (y = (1 + y) / 2 has its fixed point at 1);
  // tile coordinates stay inside [0, 1), 1e-6 from the borders, so that every point has one tile.
  constexpr double kInset = 1e-6;
  for (std::size_t type = 0; type < t.types(); ++type)
    for (std::uint32_t k = 0; k < t.points; ++k) {
      Point2& q = t.base[type][k];
      q = {std::clamp(q.x, kInset, 1 - kInset), std::clamp(q.y, kInset, 1 - kInset)};
      t.relax_residual = std::max(t.relax_residual, std::sqrt(squared_distance(before[type][k], q)));
    }
}

// Step 6: the subdivision set's ranking of one type: base points first (their base rank), then
// dart throwing over the rest with a radius shrinking by 1% after 50 consecutive failures
// (Fig. 8).
std::vector<std::uint32_t> subdivision_ranks(const RecursiveWangTiles& t, const std::vector<std::size_t>& match,
                                             std::size_t type, std::uint64_t seed) {
  const std::uint32_t n = t.points;
  const auto sub = subdivision_set(t, t.base, type);
  std::vector<std::uint32_t> rank(sub.size(), 0);
  std::vector<char> ranked(sub.size(), 0);
  PointGrid grid(0, 0, 1, 1, 0.5 / std::sqrt(double(sub.size())), true);
  for (std::uint32_t k = 0; k < n; ++k) {
    rank[match[k]] = k, ranked[match[k]] = 1;
    grid.insert(int(match[k]), sub[match[k]]);
  }
  std::vector<std::size_t> left;
  for (std::size_t i = 0; i < sub.size(); ++i)
    if (!ranked[i]) left.push_back(i);
  SplitMix64 r(seed);
  double radius = 2 * max_poisson_radius(n);
  std::uint32_t next_rank = n;
  for (int failures = 0; !left.empty();) {
    const std::size_t pick = r.below(left.size()), i = left[pick];
    bool far = true;
    grid.for_near(sub[i], int(std::ceil(radius / grid.cell())), [&](int id) {
      const Point2 d = grid.delta(sub[i], sub[std::size_t(id)]);
      if (d.x * d.x + d.y * d.y < radius * radius) far = false;
    });
    if (far) {
      rank[i] = next_rank++;
      grid.insert(int(i), sub[i]);
      left[pick] = left.back();
      left.pop_back();
      failures = 0;
    } else if (++failures >= 50) {
      radius *= 0.99;
      failures = 0;
    }
  }
  return rank;
}

}  // namespace

RecursiveWangTiles build_recursive_tiles(const RecursiveTileParams& p) {
  if (p.points < 8 || p.points > 65536)
    throw RequestError("points", fmt::format("`points` must be 8..65536, got {}", p.points));
  if (p.subdivision < 2 || p.subdivision > 8)
    throw RequestError("subdivision", fmt::format("`subdivision` must be 2..8, got {}", p.subdivision));
  const auto start = std::chrono::steady_clock::now();
  RecursiveWangTiles t;
  t.points = p.points;
  t.n = p.subdivision;
  t.seed = p.seed;
  for (std::uint32_t i = 0; i < kColours * kColours * kColours * kColours; ++i) {
    const WangTile w = wang_tile(i, kColours, kColours);
    if ((w.n + w.s) % kColours == (w.e + w.w) % kColours) t.wang.push_back(i);
  }
  const std::size_t types = t.wang.size();
  ProgressReporter progress(fmt::format("points recursive build N={} n={}", p.points, t.n), double(4 + 2 * types),
                            p.progress);
  build_base_tiles(t, p, progress);  // 1-3
  SplitMix64 rng(step_seed(p.seed, 3, 0));
  t.rule = subdivision_rules(t, rng);  // 4
  const double cell = 1.5 / std::sqrt(double(p.points) * t.n * t.n);
  relax_towards_subdivision(t, cell);  // 5
  progress.add(1);
  const std::vector<std::vector<std::size_t>> match = match_subdivision(t, cell);
  snap_to_matches(t, match);
  progress.add(1);
  t.rank.assign(types, {});  // 6
  parallel_for(std::int64_t(types), p.threads, [&](std::int64_t ti) {
    const std::size_t type = std::size_t(ti);
    t.rank[type] = subdivision_ranks(t, match[type], type, step_seed(p.seed, 4, type));
    progress.add(1);
  });
  progress.finish();
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return t;
}

}  // namespace tilekit::points
