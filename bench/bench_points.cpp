// Point sets: the comparison of README.md ("The comparison") in one run. For every method:
// generation speed on one thread (and its ratio to Bridson's dart throwing and to an earlier
// corner set, timed in the same run), the power spectrum of K = 10 toroidal sets of 16,384 points
// (thesis sec. 6.2.2: max and mean anisotropy in 0.5-2 f_p, effective Nyquist frequency,
// oscillations) and the smallest relative radius of those sets; then the build time of the
// default corner set and rho across the borders of a large window. One JSON line per case;
// medians of --reps runs; the load average with each line.
//
//   build/bench_bench_points [--reps 5] [--points 1e7] [--bridson-points 2e5] [--before F.ptiles]
//                            [--plots DIR] [--quick]
//
// --before: the corner set an earlier tilekit built (`tilekit points tiles --out F`), measured
// beside today's; --plots: radial power and anisotropy plots and spectrum images (.png, .svg).
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "base/atomic_file.hpp"
#include "bench/bench_common.hpp"
#include "points/analysis_plot.hpp"
#include "points/analysis_radius.hpp"
#include "points/analysis_spectrum.hpp"
#include "points/generator.hpp"
#include "points/poisson_tiles.hpp"
#include "points/recursive_tiles.hpp"
#include "points/reference_sets.hpp"
#include "points/tile_set_file.hpp"

using namespace tilekit;
using namespace tilekit::points;
using bench::median;
using bench::seconds_of;

namespace {

inline void escape(const void* p) {
  asm volatile("" : : "g"(p) : "memory");
}

void emit(nlohmann::json j) {
  j["cores"] = std::thread::hardware_concurrency();
  j["load"] = bench::loadavg();
  fmt::print("{}\n", j.dump());
  std::fflush(stdout);
}

struct Options {
  int reps = 5, sets = 10;
  double points = 1e7, bridson_points = 2e5;
  std::string before, plots;
  bool quick = false;
};

PoissonTileSet build(PoissonTileMethod m, std::uint32_t c, std::uint32_t n = 0, int threads = 2) {
  PoissonTileParams p;
  p.method = m;
  p.colours = c;
  p.points = n;  // 0: the method's default
  p.threads = threads;
  return build_poisson_tiles(p);
}

// A method under comparison: the points of a window at a density (`period` > 0: a torus of that
// many tiles; the samplers make toroidal sets of their own), and its layout for spectra.
struct Method {
  std::string name, key;  // key: file names of its pictures
  // xy of the window at the density with the seed; period > 0: a toroidal tiling of that many
  // (base) tiles of side 1 per side; torus: a toroidal sampler set.
  std::function<std::vector<double>(const Window&, double, std::uint64_t, std::int64_t, bool)> make;
  double per_tile = 0;       // points per (base) tile; 0: not tiled (the unit square at 16,384 points)
  bool timed_small = false;  // timed on the Bridson-sized window
};

// K toroidal sets of about 16,384 points (thesis sec. 6.2.2), as `tilekit points spectrum` lays
// them out: whole tiles of a periodic tiling, or the unit torus for the samplers.
struct Quality {
  RadialStats radial;
  SpectralSummary summary;
  double rho_min = 1e300;
  PowerSpectrum spectrum{16, 1};
};
Quality quality(const Method& m, int sets) {
  const double target = 16384;
  std::int64_t period = 0;
  double side = 1, density = target;
  if (m.per_tile > 0) {
    period = std::max<std::int64_t>(1, std::llround(std::sqrt(target / m.per_tile)));
    side = double(period);
    density = m.per_tile;
  }
  Quality q;
  q.spectrum = PowerSpectrum(periodogram_size(density, side), side);
  for (int k = 0; k < sets; ++k) {
    const auto xy = m.make({0, 0, side, side}, density, std::uint64_t(k) + 1, period, period == 0);
    q.spectrum.add(xy, 0, 0, 2);
    q.rho_min = std::min(q.rho_min, radius_stats(xy, side * side).rho);
  }
  q.radial = radial_stats(q.spectrum);
  q.summary = summarize(q.radial, q.spectrum.density());
  return q;
}

// Points per second of one one-thread generation of a square window of `count` points at
// density 1 (a fresh output buffer, as `points generate` makes one).
double rate_once(const Method& m, double count) {
  const double side = std::sqrt(count);
  const Window w{0.5, 0.25, 0.5 + side, 0.25 + side};
  std::size_t n = 0;
  const double t = seconds_of([&] {
    const auto xy = m.make(w, 1.0, 7, 0, false);
    n = xy.size() / 2;
    escape(xy.data());
  });
  return double(n) / t;
}

// Median speed of every method after one untimed warm-up call each, the repetitions interleaved
// (rep 1 of every method, then rep 2, ...) so that a change of the machine's load during the run
// falls on every method alike.
std::vector<double> speeds(const std::vector<Method>& list, const Options& o) {
  std::vector<std::vector<double>> rates(list.size());
  for (const Method& m : list) rate_once(m, m.timed_small ? o.bridson_points : o.points);  // warm-up, untimed
  for (int rep = 0; rep < o.reps; ++rep)
    for (std::size_t i = 0; i < list.size(); ++i) {
      const Method& m = list[i];
      if (m.key == "bridson" && rep >= std::max(1, o.reps / 2)) continue;  // slow: half the reps
      rates[i].push_back(rate_once(m, m.timed_small ? o.bridson_points : o.points));
    }
  std::vector<double> out;
  for (auto& r : rates) out.push_back(median(r));
  return out;
}

Method tile_method(std::string name, std::string key, std::shared_ptr<const PoissonTileSet> set) {
  Method m;
  m.name = std::move(name);
  m.key = std::move(key);
  m.per_tile = set->points;
  // One generator per (seed, period), made on first use: an application makes its generator
  // once and then asks it for windows, so the timed calls are the generation alone.
  auto made = std::make_shared<std::map<std::pair<std::uint64_t, std::int64_t>, PoissonTileGenerator>>();
  m.make = [set, made](const Window& w, double density, std::uint64_t seed, std::int64_t period, bool) {
    auto it = made->find({seed, period});
    if (it == made->end())
      it = made->emplace(std::pair(seed, period), PoissonTileGenerator(*set, HashKind::LongPeriod, seed, period)).first;
    return it->second.generate(w, density, 1);
  };
  return m;
}

std::vector<Method> methods(const Options& o) {
  std::vector<Method> out;
  if (!o.before.empty())
    out.push_back(tile_method("corner, before (" + std::filesystem::path(o.before).filename().string() + ")",
                              "corner-before", std::make_shared<PoissonTileSet>(read_poisson_tiles(o.before))));
  out.push_back(tile_method("corner C=4 N=1024 (default)", "corner",
                            std::make_shared<PoissonTileSet>(build(PoissonTileMethod::Corner, 4))));
  out.push_back(tile_method("corner C=4 N=64", "corner-n64",
                            std::make_shared<PoissonTileSet>(build(PoissonTileMethod::Corner, 4, 64))));
  if (!o.quick) {
    out.push_back(
        tile_method("dual (Li) C=2 N=64", "dual", std::make_shared<PoissonTileSet>(build(PoissonTileMethod::Dual, 2))));
    out.push_back(tile_method("wang (edge-based) C=2 N=64", "wang",
                              std::make_shared<PoissonTileSet>(build(PoissonTileMethod::Wang, 2))));
    RecursiveTileParams rp;
    rp.points = 512;
    rp.threads = 2;
    auto rec = std::make_shared<RecursiveWangTiles>(build_recursive_tiles(rp));
    Method r;
    r.name = "recursive Wang (Kopf) N=512";
    r.key = "recursive";
    r.per_tile = 1024;  // 16,384 points on 4 x 4 base tiles of side 1
    r.make = [rec](const Window& w, double density, std::uint64_t seed, std::int64_t period, bool) {
      // Constant density; base tiles of side sqrt(2.5 N / density) as `points generate` uses, or
      // of side 1 in a periodic tiling.
      const double base = period > 0 ? 1.0 : std::sqrt(2.5 * rec->points / density);
      return RecursiveGenerator(*rec, HashKind::LongPeriod, seed, period)
          .generate(w, *constant_density(density), base, 20, 1);
    };
    out.push_back(r);
  }
  Method b;
  b.name = "Bridson (toroidal, rho 0.75 asked)";
  b.key = "bridson";
  b.timed_small = true;
  b.make = [](const Window& w, double density, std::uint64_t seed, std::int64_t, bool torus) {
    return bridson_points(w, 2 * 0.75 * max_poisson_radius(density), seed, torus);
  };
  out.push_back(b);
  Method wn;
  wn.name = "white noise";
  wn.key = "white";
  wn.make = [](const Window& w, double density, std::uint64_t seed, std::int64_t, bool) {
    return white_noise_points(w, std::uint64_t(std::llround(density * w.area())), seed);
  };
  out.push_back(wn);
  return out;
}

void write_plot(const std::string& dir, const std::string& stem, const std::vector<PlotSeries>& series) {
  write_png(dir + "/" + stem + ".png", radial_plot_png(series));
  write_file_atomic(dir + "/" + stem + ".svg", radial_plot_svg(series));
}

void compare(const Options& o) {
  const auto list = methods(o);
  const std::vector<double> rates = speeds(list, o);
  double bridson_rate = 0, before_rate = 0;
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (list[i].key == "bridson") bridson_rate = rates[i];
    if (list[i].key == "corner-before") before_rate = rates[i];
  }
  std::vector<PlotSeries> tiled, references;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Method& m = list[i];
    const double rate = rates[i];
    const Quality q = quality(m, o.sets);
    nlohmann::json j = {{"case", "compare"},
                        {"method", m.name},
                        {"sets", o.sets},
                        {"points_per_set", double(q.spectrum.points) / double(q.spectrum.sets)},
                        {"max_anisotropy_db", q.summary.max_anisotropy_db},
                        {"mean_anisotropy_db", q.summary.mean_anisotropy_db},
                        {"rho_min", q.rho_min},
                        {"effective_nyquist", q.summary.effective_nyquist},
                        {"oscillations", q.summary.oscillations},
                        {"peak_frequency", q.summary.peak_frequency},
                        {"points_per_second_1_thread", rate},
                        {"ratio_to_bridson", rate / bridson_rate},
                        {"reps", o.reps}};
    if (before_rate > 0) j["ratio_to_corner_before"] = rate / before_rate;
    emit(j);
    const PlotSeries s{m.key, q.radial, q.summary.principal_frequency};
    if (m.per_tile > 0) tiled.push_back(s);
    if (m.key == "corner" || m.per_tile == 0) references.push_back(s);
    if (!o.plots.empty()) write_png(o.plots + "/points-spectrum-" + m.key + ".png", spectrum_image(q.spectrum));
  }
  if (!o.plots.empty()) {
    write_plot(o.plots, "points-compare-tiles", tiled);
    write_plot(o.plots, "points-compare-references", references);
  }
}

void build_time(const Options& o) {
  std::vector<double> wall1, cpu1, wall2;
  double rho = 0;
  for (int i = 0; i < std::max(1, o.reps / 2); ++i) {
    const double c0 = bench::cpu_seconds();
    std::optional<PoissonTileSet> set;
    wall1.push_back(seconds_of([&] { set = build(PoissonTileMethod::Corner, 4, 0, 1); }));
    cpu1.push_back(bench::cpu_seconds() - c0);
    wall2.push_back(seconds_of([&] { escape(build(PoissonTileMethod::Corner, 4, 0, 2).tiles.data()); }));
    rho = check_poisson_tiles(*set, 2).rho_across;
  }
  emit({{"case", "build_tile_set"},
        {"tiles", "corner C=4 N=1024 rho=0.75"},
        {"seconds_1_thread", median(wall1)},
        {"cpu_seconds_1_thread", median(cpu1)},
        {"seconds_2_threads", median(wall2)},
        {"rho_across_checked", rho}});
}

void radius_across(const Options& o) {
  // A tile-aligned window (exact density) of at least 2e6 points (1e6 with --quick).
  const PoissonTileSet set = build(PoissonTileMethod::Corner, 4);
  const int tiles = int(std::ceil(std::sqrt((o.quick ? 1e6 : 2e6) / set.points)));
  const Window w{-3, 5, -3.0 + tiles, 5.0 + tiles};
  const auto xy = PoissonTileGenerator(set, HashKind::LongPeriod, 11).generate(w, set.points, 2);
  const auto r = radius_stats(xy, w.area(), 1.0);
  emit({{"case", "radius"},
        {"tiles", "corner C=4 N=1024 rho=0.75"},
        {"points", r.count},
        {"rho", r.rho},
        {"rho_within", r.rho_within},
        {"rho_across", r.rho_across},
        {"mean_nn_relative", r.mean_nn_relative}});
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
    else if (a == "--before" && i + 1 < argc)
      o.before = argv[++i];
    else if (a == "--plots" && i + 1 < argc)
      o.plots = argv[++i];
    else if (a == "--quick")
      o.quick = true, o.reps = 3, o.points = 1e6, o.bridson_points = 5e4;
    else {
      fmt::print(stderr,
                 "usage: bench_points [--reps R] [--points N] [--bridson-points N] [--before F.ptiles] [--plots DIR] "
                 "[--quick]\n");
      return 2;
    }
  }
  compare(o);
  build_time(o);
  radius_across(o);
  return 0;
}
