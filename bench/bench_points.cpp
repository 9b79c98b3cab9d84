// Point sets: speed of window generation through the direct stochastic tiling against
// Bridson's dart throwing and a plain memory write timed in the same run, tile-set build time,
// the relative radius across tile borders of a large window, and the anisotropy of the power
// spectrum (K = 10 sets). One JSON line per case; medians of --reps runs; the core count and the
// load average with every line.
//
//   build/bench_points [--reps 5] [--points 10000000] [--bridson-points 200000] [--quick]
#include <fmt/format.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "points/analysis_radius.hpp"
#include "points/analysis_spectrum.hpp"
#include "points/generator.hpp"
#include "points/poisson_tiles.hpp"
#include "points/recursive_tiles.hpp"
#include "points/reference_sets.hpp"

using namespace tilekit;
using namespace tilekit::points;

namespace {

inline void escape(const void* p) {
  asm volatile("" : : "g"(p) : "memory");
}

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : (v[v.size() / 2 - 1] + v[v.size() / 2]) / 2;
}
std::string load() {
  std::ifstream f("/proc/loadavg");
  std::string a;
  f >> a;
  return a;
}
void emit(nlohmann::json j) {
  j["cores"] = std::thread::hardware_concurrency();
  j["load"] = load();
  fmt::print("{}\n", j.dump());
  std::fflush(stdout);
}

struct Options {
  int reps = 5;
  double points = 1e7, bridson_points = 2e5;
  bool quick = false;
};

PoissonTileSet build(PoissonTileMethod m, std::uint32_t c, std::uint32_t n, int threads) {
  PoissonTileParams p;
  p.method = m;
  p.colours = c;
  p.points = n;
  p.rho = 0.75;
  p.threads = threads;
  return build_poisson_tiles(p);
}

// Median wall seconds of `reps` runs of f.
double timed(int reps, const std::function<void()>& f) {
  std::vector<double> t;
  for (int i = 0; i < reps; ++i) {
    const double t0 = now();
    f();
    t.push_back(now() - t0);
  }
  return median(t);
}

void speed(const Options& o, const PoissonTileSet& set, const std::string& name) {
  // A square window of about o.points points at density 1 (tile side sqrt(N)).
  const double side = std::sqrt(o.points);
  const Window w{0.5, 0.25, 0.5 + side, 0.25 + side};
  const PoissonTileGenerator gen(set, HashKind::LongPeriod, 7);
  std::size_t count = 0;
  const double t1 = timed(o.reps, [&] {
    const auto xy = gen.generate(w, 1.0, 1);
    count = xy.size() / 2;
    escape(xy.data());
  });
  const double t2 = timed(o.reps, [&] { escape(gen.generate(w, 1.0, 2).data()); });
  // The same number of 8-byte points written by a plain loop into a fresh vector (memory bound).
  const double tm = timed(o.reps, [&] {
    std::vector<float> out(2 * count);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = float(i & 1023);
    escape(out.data());
  });
  // Bridson's dart throwing in the same run, on a window of o.bridson_points points.
  const double bside = std::sqrt(o.bridson_points);
  std::size_t bcount = 0;
  const double tb = timed(std::max(1, o.reps / 2), [&] {
    const auto xy = bridson_points({0, 0, bside, bside}, 2 * 0.75 * max_poisson_radius(1.0), 3);
    bcount = xy.size() / 2;
    escape(xy.data());
  });
  const double rate1 = count / t1, rate2 = count / t2, rate_mem = count / tm, rate_b = bcount / tb;
  emit({{"case", "generate_window"},
        {"tiles", name},
        {"points", count},
        {"points_per_second_1_thread", rate1},
        {"points_per_second_2_threads", rate2},
        {"memory_write_points_per_second", rate_mem},
        {"bridson_points", bcount},
        {"bridson_points_per_second", rate_b},
        {"ratio_to_bridson", rate1 / rate_b},
        {"fraction_of_memory_write", rate1 / rate_mem},
        {"reps", o.reps}});
}

void build_time(const Options& o, PoissonTileMethod m, std::uint32_t c, std::uint32_t n) {
  std::vector<double> wall1, cpu1, wall2;
  double rho = 0;
  for (int i = 0; i < std::max(1, o.reps / 2); ++i) {
    double c0 = cpu_seconds(), t0 = now();
    const auto set = build(m, c, n, 1);
    wall1.push_back(now() - t0), cpu1.push_back(cpu_seconds() - c0);
    t0 = now();
    escape(build(m, c, n, 2).tiles.data());
    wall2.push_back(now() - t0);
    rho = check_poisson_tiles(set, 2).rho_across;
  }
  emit({{"case", "build_tile_set"},
        {"method", method_name(m)},
        {"colors", c},
        {"points", n},
        {"rho", 0.75},
        {"seconds_1_thread", median(wall1)},
        {"cpu_seconds_1_thread", median(cpu1)},
        {"seconds_2_threads", median(wall2)},
        {"rho_across_checked", rho}});
}

void quality(const PoissonTileSet& set, const std::string& name, double points) {
  // A tile-aligned window (exact density) of at least `points` points.
  const int tiles = int(std::ceil(std::sqrt(points / set.points)));
  const Window w{-3, 5, -3.0 + tiles, 5.0 + tiles};
  const auto xy = PoissonTileGenerator(set, HashKind::LongPeriod, 11).generate(w, set.points, 2);
  const auto r = radius_stats(xy, w.area(), 1.0);
  emit({{"case", "radius"},
        {"tiles", name},
        {"points", r.count},
        {"rho", r.rho},
        {"rho_within", r.rho_within},
        {"rho_across", r.rho_across},
        {"mean_nn_relative", r.mean_nn_relative}});
}

// K = 10 periodograms of toroidal sets of about 16,384 points (thesis sec. 6.2.2).
SpectralSummary spectrum_of(const std::function<std::vector<float>(std::uint64_t)>& make, double side, double density,
                            int sets = 10) {
  PowerSpectrum ps(periodogram_size(density, side), side);
  for (int k = 0; k < sets; ++k) ps.add(make(std::uint64_t(k) + 1), 0, 0, 2);
  return summarize(radial_stats(ps), ps.density());
}

void spectrum(const PoissonTileSet& set, const std::string& name) {
  const std::int64_t m = std::llround(std::sqrt(16384.0 / set.points));
  const auto s = spectrum_of(
      [&](std::uint64_t seed) {
        return PoissonTileGenerator(set, HashKind::LongPeriod, seed, m)
            .generate({0, 0, double(m), double(m)}, set.points);
      },
      double(m), set.points);
  emit({{"case", "spectrum"},
        {"tiles", name},
        {"sets", 10},
        {"points_per_set", m * m * set.points},
        {"max_anisotropy_db", s.max_anisotropy_db},
        {"mean_anisotropy_db", s.mean_anisotropy_db},
        {"effective_nyquist", s.effective_nyquist},
        {"oscillations", s.oscillations},
        {"peak_frequency", s.peak_frequency}});
}

void baselines_spectrum() {
  const auto b = spectrum_of(
      [](std::uint64_t seed) {
        return bridson_points({0, 0, 1, 1}, 2 * 0.75 * max_poisson_radius(16384), seed, true);
      },
      1, 16384);
  emit({{"case", "spectrum"},
        {"tiles", "bridson (toroidal, rho 0.75 asked)"},
        {"sets", 10},
        {"max_anisotropy_db", b.max_anisotropy_db},
        {"mean_anisotropy_db", b.mean_anisotropy_db},
        {"effective_nyquist", b.effective_nyquist},
        {"oscillations", b.oscillations},
        {"peak_frequency", b.peak_frequency}});
}

void recursive_case(const Options& o) {
  RecursiveTileParams p;
  p.points = 512;
  p.threads = 2;
  const double t0 = now();
  const auto t = build_recursive_tiles(p);
  const double build_s = now() - t0;
  const RecursiveGenerator gen(t, HashKind::LongPeriod, 5);
  const double side = std::sqrt(o.points / 10);
  const auto d = constant_density(1.0);
  std::size_t count = 0;
  const double tg = timed(o.reps, [&] {
    const auto xy = gen.generate({0, 0, side, side}, *d, std::sqrt(2.5 * 512), 20, 1);
    count = xy.size() / 2;
    escape(xy.data());
  });
  const auto xy = gen.generate({0, 0, side, side}, *d, std::sqrt(2.5 * 512), 20, 2);
  const auto r = radius_stats(xy, side * side, std::sqrt(2.5 * 512));
  const std::int64_t m = 4;
  const auto s = spectrum_of(
      [&](std::uint64_t seed) {
        const RecursiveGenerator g(t, HashKind::LongPeriod, seed, m);
        return g.generate({0, 0, double(m), double(m)}, *constant_density(16384.0 / (m * m)), 1.0, 20, 1);
      },
      double(m), 16384.0 / (m * m));
  emit({{"case", "recursive_wang_tiles"},
        {"points_per_tile", 512},
        {"build_seconds", build_s},
        {"relax_iterations", t.relax_iterations},
        {"points", count},
        {"points_per_second_1_thread", count / tg},
        {"rho", r.rho},
        {"rho_across", r.rho_across},
        {"mean_nn_relative", r.mean_nn_relative},
        {"max_anisotropy_db", s.max_anisotropy_db},
        {"mean_anisotropy_db", s.mean_anisotropy_db}});
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--reps" && i + 1 < argc)
      o.reps = std::max(1, std::atoi(argv[++i]));
    else if (a == "--points" && i + 1 < argc)
      o.points = std::atof(argv[++i]);
    else if (a == "--bridson-points" && i + 1 < argc)
      o.bridson_points = std::atof(argv[++i]);
    else if (a == "--quick")
      o.quick = true, o.reps = 3, o.points = 1e6, o.bridson_points = 5e4;
    else {
      fmt::print(stderr, "usage: bench_points [--reps R] [--points N] [--bridson-points N] [--quick]\n");
      return 2;
    }
  }
  const auto c4 = build(PoissonTileMethod::Corner, 4, 64, 2);
  speed(o, c4, "corner C=4 N=64 rho=0.75");
  build_time(o, PoissonTileMethod::Corner, 4, 64);
  quality(c4, "corner C=4 N=64 rho=0.75", std::max(1e6, o.quick ? 1e6 : 2e6));
  spectrum(c4, "corner C=4 N=64 rho=0.75");
  if (!o.quick) {
    const auto c4n256 = build(PoissonTileMethod::Corner, 4, 256, 2);
    spectrum(c4n256, "corner C=4 N=256 rho=0.75");
    const auto c8 = build(PoissonTileMethod::Corner, 8, 64, 2);
    spectrum(c8, "corner C=8 N=64 rho=0.75");
    const auto dual = build(PoissonTileMethod::Dual, 2, 64, 2);
    spectrum(dual, "dual C=2 N=64 rho=0.75");
    speed(o, dual, "dual C=2 N=64 rho=0.75");
    const auto wang = build(PoissonTileMethod::Wang, 2, 64, 2);
    spectrum(wang, "wang C=2 N=64 rho=0.75");
    quality(wang, "wang C=2 N=64 rho=0.75", 1e6);
  }
  baselines_spectrum();
  recursive_case(o);
  return 0;
}
