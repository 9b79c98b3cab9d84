#include "points/sampler.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "base/error.hpp"
#include "base/random.hpp"

namespace tilekit::points {

namespace {

class Sampler {
 public:
  Sampler(const SamplingProblem& p, const SamplingOptions& o)
      : p_(p),
        o_(o),
        d_(o.min_distance),
        grid_(p.torus ? p.x0 : p.x0 - 2 * o.min_distance, p.torus ? p.y0 : p.y0 - 2 * o.min_distance,
              p.torus ? p.w : p.w + 4 * o.min_distance, p.torus ? p.h : p.h + 4 * o.min_distance, o.min_distance,
              p.torus) {
    for (const Point2& f : p.fixed) {
      const Point2 q = p.torus ? Point2{wrap(f.x - p.x0, p.w) + p.x0, wrap(f.y - p.y0, p.h) + p.y0} : f;
      // Fixed points farther than 3 distances from a plain domain constrain nothing in it.
      if (!p.torus &&
          (q.x < p.x0 - 3 * d_ || q.y < p.y0 - 3 * d_ || q.x > p.x0 + p.w + 3 * d_ || q.y > p.y0 + p.h + 3 * d_))
        continue;
      fixed_.push_back(q);
    }
    g_ = p.symmetry_order;
    step_ = 4 / g_;
    if (o_.lloyd > 0) make_samples();
  }

  bool run(SplitMix64& rng, SamplingResult& out) {
    pos_ = fixed_;
    if (!throw_darts(rng)) return false;
    relax_hard_disks(rng);
    // `lloyd` iterations of Lloyd's relaxation, then pairs still too close push each other apart
    // until the distance is met.
    for (int it = 0;; ++it) {
      rebuild();
      const double md = new_min_distance();
      if (md >= d_ && it >= o_.lloyd) {
        out.points.assign(pos_.begin() + std::ptrdiff_t(fixed_.size()), pos_.end());
        out.min_distance = md;
        out.lloyd_iterations = o_.lloyd;
        return true;
      }
      if (it >= o_.lloyd + o_.repair) return false;
      if (it < o_.lloyd)
        lloyd_step();
      else
        repel_step(d_ * 1.01);
    }
  }

 private:
  Point2 wrapped(Point2 q) const {
    if (!p_.torus) return q;
    return {wrap(q.x - p_.x0, p_.w) + p_.x0, wrap(q.y - p_.y0, p_.h) + p_.y0};
  }
  bool in_domain(Point2 q) const {
    return p_.torus || (q.x >= p_.x0 && q.y >= p_.y0 && q.x < p_.x0 + p_.w && q.y < p_.y0 + p_.h);
  }
  bool in_region(Point2 q) const { return in_domain(q) && (!p_.free || p_.free(q)); }
  // The orbit of q: image k is q turned k * step_ quarter turns about the centre.
  Point2 image(Point2 q, int k) const { return wrapped(rotate_quarter(q, k * step_, p_.centre)); }

  // Lloyd's samples: an even lattice over the whole domain (Voronoi cells reach into the fixed
  // regions too), symmetric under the rotations the problems use.
  void make_samples() {
    const double hs = d_ / o_.samples_per_distance;
    int nx = std::max(2, int(std::ceil(p_.w / hs))), ny = std::max(2, int(std::ceil(p_.h / hs)));
    nx += nx % 2, ny += ny % 2;
    std::vector<std::pair<int, Point2>> keyed;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const Point2 q{p_.x0 + (i + 0.5) * p_.w / nx, p_.y0 + (j + 0.5) * p_.h / ny};
        keyed.emplace_back(grid_.cell_index(q), q);
      }
    // Grouped by the point grid's cell, so that each cell's candidate points are gathered once.
    std::stable_sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [cell, q] : keyed) samples_.push_back(q), sample_cell_.push_back(cell);
  }

  void rebuild() {
    grid_.clear();
    for (std::size_t i = 0; i < pos_.size(); ++i) grid_.insert(int(i), pos_[i]);
  }

  // Relaxation dart throwing: the dart radius starts above the minimum distance and shrinks by
  // 2% after 200 consecutive failures (thesis sec. 6.4 used 0.99 after 1,000 on whole sets).
  bool throw_darts(SplitMix64& rng) {
    rebuild();
    double radius = 1.2 * d_;
    std::size_t placed = 0;
    int failures = 0;
    std::uint64_t darts = 0;
    while (placed < p_.count) {
      if (++darts > 50'000'000ull || radius < 0.2 * d_) return false;
      const Point2 q = wrapped({p_.x0 + rng.uniform() * p_.w, p_.y0 + rng.uniform() * p_.h});
      if (dart_fits(q, radius)) {
        for (int k = 0; k < g_; ++k) {
          pos_.push_back(image(q, k));
          grid_.insert(int(pos_.size() - 1), pos_.back());
        }
        placed += std::size_t(g_);
        failures = 0;
      } else if (++failures >= 200) {
        radius *= 0.98;
        failures = 0;
      }
    }
    return true;
  }

  // Hard-disk Monte Carlo (Metropolis et al. 1953): each sweep, every new point (orbit) tries a
  // random step and takes it when the step keeps it in the free region and at least the minimum
  // distance from every other point. Dart throwing alone leaves a depleted band next to fixed
  // points (they block darts from the start, while new points arrive over time) and a crowded one
  // behind it, in the same place in every tile; the sweeps bring the new points to the hard-disk
  // distribution given the fixed ones, which has no such band (points/README.md, "Why the tiles showed").
  // The step adapts towards a 40% acceptance rate.
  void relax_hard_disks(SplitMix64& rng) {
    if (o_.hard_disk_sweeps <= 0) return;
    rebuild();
    const std::size_t f0 = fixed_.size();
    double step = 0.5 * d_;
    for (int sweep = 0; sweep < o_.hard_disk_sweeps; ++sweep) {
      std::size_t tried = 0, taken = 0;
      for (std::size_t base = f0; base < pos_.size(); base += std::size_t(g_), ++tried) {
        const Point2 moved =
            wrapped({pos_[base].x + (2 * rng.uniform() - 1) * step, pos_[base].y + (2 * rng.uniform() - 1) * step});
        if (!dart_fits(moved, d_, base)) continue;
        ++taken;
        for (int k = 0; k < g_; ++k) {
          const std::size_t i = base + std::size_t(k);
          const Point2 to = image(moved, k);
          if (grid_.cell_index(to) != grid_.cell_index(pos_[i])) grid_.erase(int(i), pos_[i]), grid_.insert(int(i), to);
          pos_[i] = to;
        }
      }
      if (tried > 0) step = std::clamp(step * (0.5 + double(taken) / double(tried) / 0.8), 0.01 * d_, d_);
    }
  }

  // Whether q's orbit may be added: every image at least `radius` from every point (but the orbit
  // starting at `moving`, the one being moved) and from the other images, and in the free region
  // (tested last: it is the costly part near curved borders).
  bool dart_fits(Point2 q, double radius, std::size_t moving = std::numeric_limits<std::size_t>::max() - 4) const {
    const int rings = int(std::ceil(radius / grid_.cell()));
    const double r2 = radius * radius;
    Point2 orbit[4];
    for (int k = 0; k < g_; ++k) {
      orbit[k] = image(q, k);
      for (int m = 0; m < k; ++m) {
        const Point2 dd = grid_.delta(orbit[k], orbit[m]);
        if (dd.x * dd.x + dd.y * dd.y < r2) return false;
      }
      const bool blocked = grid_.any_near(orbit[k], rings, [&](int id) {
        if (std::size_t(id) >= moving && std::size_t(id) < moving + std::size_t(g_)) return false;
        const Point2 dd = grid_.delta(orbit[k], pos_[std::size_t(id)]);
        return dd.x * dd.x + dd.y * dd.y < r2;
      });
      if (blocked) return false;
    }
    for (int k = 0; k < g_; ++k)
      if (!in_region(orbit[k])) return false;
    return true;
  }

  // The smallest distance between a new point and any other point, capped at 2 cells.
  double new_min_distance() const {
    double best = 4 * grid_.cell() * grid_.cell();
    const std::size_t f0 = fixed_.size();
    for (std::size_t i = f0; i < pos_.size(); ++i) {
      grid_.for_near(pos_[i], 2, [&](int id) {
        if (std::size_t(id) == i) return;
        const Point2 dd = grid_.delta(pos_[i], pos_[std::size_t(id)]);
        best = std::min(best, dd.x * dd.x + dd.y * dd.y);
      });
    }
    return std::sqrt(best);
  }

  // One Jacobi step of discrete Lloyd relaxation (thesis sec. 4.2.4.3): every new point moves
  // to the centroid of the samples nearest to it; orbits move together.
  void lloyd_step() {
    const std::size_t n = pos_.size(), f0 = fixed_.size();
    sum_.assign(n, Point2{});
    cnt_.assign(n, 0);
    // The nearest point of a sample is among the 3x3 cells around its own whenever it is closer
    // than one cell (anything outside is farther); otherwise ask the grid.
    const double cell2 = grid_.cell() * grid_.cell();
    std::vector<std::pair<int, Point2>> near;
    for (std::size_t a = 0; a < samples_.size();) {
      const int cell = sample_cell_[a];
      const Point2 centre = grid_.cell_centre(cell);
      near.clear();
      grid_.for_near(centre, 1, [&](int id) {
        const Point2 dd = grid_.delta(pos_[std::size_t(id)], centre);
        near.emplace_back(id, Point2{centre.x + dd.x, centre.y + dd.y});
      });
      for (; a < samples_.size() && sample_cell_[a] == cell; ++a) {
        const Point2 s = samples_[a];
        int id = -1;
        double best = 1e300;
        for (const auto& [j, q] : near) {
          const double d2 = squared_distance(s, q);
          if (d2 < best) best = d2, id = j;
        }
        if (best > cell2) id = grid_.nearest(s, pos_);
        if (id < int(f0)) continue;
        const Point2 dd = grid_.delta(s, pos_[std::size_t(id)]);
        sum_[std::size_t(id)].x += dd.x;
        sum_[std::size_t(id)].y += dd.y;
        ++cnt_[std::size_t(id)];
      }
    }
    for (std::size_t base = f0; base < n; base += std::size_t(g_)) {
      Point2 delta{};
      for (int k = 0; k < g_; ++k) {
        const std::size_t i = base + std::size_t(k);
        if (cnt_[i] == 0) continue;
        const Point2 dk = rotate_quarter({sum_[i].x / cnt_[i], sum_[i].y / cnt_[i]}, -k * step_);
        delta.x += dk.x / g_;
        delta.y += dk.y / g_;
      }
      move_orbit(base, delta);
    }
  }

  // Pairs closer than `target` push each other apart (a new point takes half of the shortfall
  // from another new point, all of it from a fixed one).
  void repel_step(double target) {
    const std::size_t n = pos_.size(), f0 = fixed_.size();
    sum_.assign(n, Point2{});
    for (std::size_t i = f0; i < n; ++i)
      grid_.for_near(pos_[i], 2, [&](int id) {
        if (std::size_t(id) == i) return;
        const Point2 dd = grid_.delta(pos_[i], pos_[std::size_t(id)]);
        const double dist = std::sqrt(dd.x * dd.x + dd.y * dd.y);
        if (dist >= target || dist == 0) return;
        const double push = (target - dist) * (std::size_t(id) < f0 ? 1.0 : 0.5) / dist;
        sum_[i].x += push * dd.x;
        sum_[i].y += push * dd.y;
      });
    for (std::size_t base = f0; base < n; base += std::size_t(g_)) {
      Point2 delta{};
      for (int k = 0; k < g_; ++k) {
        const Point2 dk = rotate_quarter(sum_[base + std::size_t(k)], -k * step_);
        delta.x += dk.x / g_;
        delta.y += dk.y / g_;
      }
      if (delta.x != 0 || delta.y != 0) move_orbit(base, delta);
    }
  }

  // Moves the orbit starting at `base` by `delta` (its representative's displacement), shortened
  // so that no image leaves its region (thesis sec. 4.3: clipping the displacement vectors).
  void move_orbit(std::size_t base, Point2 delta) {
    for (int halvings = 0; halvings < 8; ++halvings, delta.x *= 0.5, delta.y *= 0.5) {
      const Point2 moved = wrapped({pos_[base].x + delta.x, pos_[base].y + delta.y});
      bool ok = true;
      for (int k = 0; k < g_ && ok; ++k) ok = in_region(image(moved, k));
      if (!ok) continue;
      for (int k = 0; k < g_; ++k) pos_[base + std::size_t(k)] = image(moved, k);
      return;
    }
  }

  const SamplingProblem& p_;
  const SamplingOptions& o_;
  double d_;
  PointGrid grid_;
  int g_ = 1, step_ = 4;
  std::vector<Point2> fixed_, pos_, samples_, sum_;
  std::vector<int> cnt_, sample_cell_;
};

}  // namespace

SamplingResult sample_poisson_disk(const SamplingProblem& problem, const SamplingOptions& options, std::uint64_t seed) {
  assert(options.min_distance > 0);
  const int g = problem.symmetry_order;
  if (g != 1 && g != 2 && g != 4) throw InputError("sampling symmetry order must be 1, 2 or 4");
  if (problem.count % std::size_t(g) != 0)
    throw InputError(fmt::format("{} points cannot form orbits of {} points", problem.count, g));
  SamplingResult result;
  if (problem.count == 0) return result;
  Sampler sampler(problem, options);
  SplitMix64 rng(seed);
  for (int t = 1; t <= options.tries; ++t) {
    if (sampler.run(rng, result)) {
      result.tries = t;
      return result;
    }
  }
  throw RequestError(
      "rho", fmt::format("could not place {} points at distance {:.6g} in {} tries (lower `rho` or raise `points`)",
                         problem.count, options.min_distance, options.tries));
}

}  // namespace tilekit::points
