// tilekit points analyze | spectrum | zoneplate: the analysis of thesis ch. 6.
//
//   tilekit points analyze FILE [--window x0,y0,x1,y1] [--tile-size S] [--spectrum F.png]
//                          [--plot F.png|.svg] [--zoneplate F.png] [--quiet]
//   tilekit points spectrum [source options] [--sets 10] [--set-points 16384] [--compare M,M]
//                          [--image F.png] [--plot F.png|.svg]
//   tilekit points zoneplate [source options] [--set-points 262144] --out F.png
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/parallel.hpp"
#include "base/progress.hpp"
#include "cli/cmd_points.hpp"
#include "cli/numeric_flags.hpp"
#include "points/analysis_plot.hpp"
#include "points/analysis_radius.hpp"
#include "points/point_io.hpp"
#include "points/zone_plate.hpp"

namespace tilekit::cli::pts {

using namespace tilekit::points;

namespace {

nlohmann::json summary_json(const SpectralSummary& s) {
  return {{"principal_frequency", s.principal_frequency}, {"max_anisotropy_db", s.max_anisotropy_db},
          {"mean_anisotropy_db", s.mean_anisotropy_db},   {"anisotropy_band", {s.band_lo, s.band_hi}},
          {"effective_nyquist", s.effective_nyquist},     {"oscillations", s.oscillations},
          {"peak_frequency", s.peak_frequency},           {"low_frequency_power", s.low_frequency_power}};
}

void write_plot(const std::string& path, const std::vector<PlotSeries>& series) {
  if (is_svg(path))
    write_file_atomic(path, radial_plot_svg(series));
  else
    write_image(path, radial_plot_png(series));
}

// A toroidal window of about `target` points for a source (thesis sec. 6.2.2: periodograms of
// sets of 16,384 points): whole tiles with a periodic tiling for tile methods, the unit square
// for the samplers (Bridson's on a torus).
struct SetLayout {
  Window window;
  double density = 0;
  std::int64_t period = 0;
  bool torus = false;
};
SetLayout layout_for(const Source& src, double target) {
  SetLayout l;
  if (src.tiles() || src.recursive()) {
    // Unit (base) tiles: N points per tile, or 2.5 N per base tile for recursive sets (between the
    // capacities of the base level and its subdivision).
    const double per_tile = src.tiles() ? src.tiles()->points : 2.5 * src.recursive()->points;
    l.period = std::max<std::int64_t>(1, std::llround(std::sqrt(target / per_tile)));
    l.window = {0, 0, double(l.period), double(l.period)};
    l.density = per_tile;
  } else {
    l.window = {0, 0, 1, 1};
    l.density = target;
    l.torus = true;
  }
  return l;
}

struct Estimate {
  PowerSpectrum spectrum{16, 1};
  double rho_min = std::numeric_limits<double>::infinity(), seconds = 0;
};
Estimate estimate(const Source& src, const SetLayout& l, int sets, std::uint64_t seed, int threads,
                  ProgressReporter& progress) {
  Estimate e;
  e.spectrum = PowerSpectrum(periodogram_size(l.density, l.window.width()), l.window.width());
  for (int k = 0; k < sets; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto xy = src.points(l.window, l.density, seed + std::uint64_t(k), threads, l.period, l.torus);
    e.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    e.spectrum.add(xy, l.window.x0, l.window.y0, threads);
    e.rho_min = std::min(e.rho_min, radius_stats(xy, l.window.area()).rho);
    progress.add(1);
  }
  return e;
}

struct AnalyzeArgs {
  std::string file, window, spectrum, plot, zoneplate;
  double tile_size = 0;
  int threads = 0;
  bool quiet = false;
};

struct SpectrumArgs {
  SourceArgs source;
  int sets = 10, threads = 0;
  double set_points = 16384;
  std::uint64_t seed = 1;
  std::string image, plot, compare;
  bool quiet = false;
};

struct ZoneplateArgs {
  SourceArgs source;
  double set_points = 262144;
  std::uint64_t seed = 1;
  std::string out;
  int threads = 0;
  bool quiet = false;
};

// The smallest half-open window that holds every point (x,y pairs).
Window bounding_window(const std::vector<double>& xy) {
  Window w{xy[0], xy[1], xy[0], xy[1]};
  for (std::size_t i = 0; i < xy.size(); i += 2)
    w.x0 = std::min<double>(w.x0, xy[i]), w.x1 = std::max<double>(w.x1, xy[i]),
    w.y0 = std::min<double>(w.y0, xy[i + 1]), w.y1 = std::max<double>(w.y1, xy[i + 1]);
  w.x1 = std::nextafter(w.x1, INFINITY), w.y1 = std::nextafter(w.y1, INFINITY);
  return w;
}

void run_analyze(const AnalyzeArgs& a, const Context& ctx) {
  check_extension(a.spectrum, {".png"}, "--spectrum");
  check_extension(a.plot, {".png", ".svg"}, "--plot");
  check_extension(a.zoneplate, {".png"}, "--zoneplate");
  const int threads = resolve_threads(a.threads);
  const auto xy = read_points(a.file);
  if (xy.size() < 4) throw InputError(fmt::format("{}: needs at least two points", a.file));
  const Window w = a.window.empty() ? bounding_window(xy) : parse_window(a.window);
  // Steps: radius analysis, periodogram, pictures.
  ProgressReporter progress("points analyze", 3, !a.quiet && xy.size() > 2'000'000);
  progress.set_detail("radius");
  const auto r = radius_stats(xy, w.area(), a.tile_size);
  progress.add(1);
  nlohmann::json j = {{"file", a.file},
                      {"points", r.count},
                      {"window", {w.x0, w.y0, w.x1, w.y1}},
                      {"density", r.density},
                      {"min_distance", r.min_distance},
                      {"mean_nn_distance", r.mean_nn_distance},
                      {"rho", r.rho},
                      {"mean_nn_relative", r.mean_nn_relative}};
  if (r.tiled) j["rho_within"] = r.rho_within, j["rho_across"] = r.rho_across, j["tile_size"] = a.tile_size;
  const double side = std::min(w.width(), w.height());
  PowerSpectrum ps(periodogram_size(r.density, side), side);
  progress.set_detail("periodogram");
  ps.add(xy, w.x0, w.y0, threads);
  progress.add(1);
  const auto radial = radial_stats(ps);
  j["spectrum"] = summary_json(summarize(radial, ps.density()));
  j["spectrum"]["size"] = ps.size;
  if (!a.spectrum.empty()) write_image(a.spectrum, spectrum_image(ps)), j["spectrum_image"] = a.spectrum;
  if (!a.plot.empty()) write_plot(a.plot, {{a.file, radial, principal_frequency(ps.density())}}), j["plot"] = a.plot;
  if (!a.zoneplate.empty()) {
    const auto z = zone_plate(xy, w);
    write_image(a.zoneplate, z.image);
    j["zoneplate"] = {{"out", a.zoneplate}, {"rms_inner", z.rms_inner}, {"rms_outer", z.rms_outer}};
  }
  progress.add(1);
  progress.finish();
  emit(ctx, j, [&] {
    fmt::print("{}: {} points, density {:.6g}\n  rho {:.4f}", a.file, r.count, r.density, r.rho);
    if (r.tiled) fmt::print(" (inside tiles {:.4f}, across tile borders {:.4f})", r.rho_within, r.rho_across);
    fmt::print(", mean nearest-neighbour distance {:.3f} x 2 r_max\n", r.mean_nn_relative);
    const auto& s = j["spectrum"];
    fmt::print(
        "  one periodogram ({0}x{0}): anisotropy up to {1:.1f} dB in [0.5, 2] f_p, effective Nyquist {2:.3f}, "
        "oscillations {3:.2f}\n",
        ps.size, s["max_anisotropy_db"].get<double>(), s["effective_nyquist"].get<double>(),
        s["oscillations"].get<double>());
  });
}

void add_analyze(CLI::App* points, Context& ctx) {
  auto* cmd = points->add_subcommand("analyze", "Radius and spectral analysis of a point file (thesis sec. 6.2)");
  auto a = std::make_shared<AnalyzeArgs>();
  cmd->add_option("file", a->file, "Points: .f32/.bin (float32 x,y pairs), .f64 (float64) or .csv")->required();
  cmd->add_option("--window", a->window, "x0,y0,x1,y1 the set covers (default: its bounding box)");
  cmd->add_option("--tile-size", a->tile_size, "Tile side: also measure rho inside tiles and across tile borders")
      ->check(positive_number());
  cmd->add_option("--spectrum", a->spectrum, "Periodogram picture (.png) of the largest square at the window's corner");
  cmd->add_option("--plot", a->plot, "Radially averaged power and anisotropy (.png or .svg)");
  cmd->add_option("--zoneplate", a->zoneplate, "Zone plate sampled at the points (.png, thesis sec. 6.2.3)");
  cmd->add_option("--threads", a->threads, "Threads (default: all cores)");
  cmd->add_flag("--quiet", a->quiet, "No progress output on stderr");
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_analyze(*a, ctx); });
}

// How far the periodogram of a set of `points` points reaches, in multiples of the principal
// frequency: it depends on the count alone (at most 2048 x 2048 bins).
double periodogram_reach(double points) {
  return double(periodogram_size(points, 1)) / 2 / principal_frequency(points);
}

// The anisotropy band reaches 2 f_p: a set of `points` points whose periodogram does not is
// refused, with the largest count that fits.
[[noreturn]] void refuse_reach(double set_points, double points) {
  const double reach = periodogram_reach(points);
  throw InputError(fmt::format("--set-points {}: the periodogram reaches {:.2f} f_p, not the 2 f_p of the "
                               "anisotropy band (it is at most 2048 x 2048); use at most about {:.0f} points per set",
                               set_points, reach, points * reach * reach / 4 * 0.99));
}

void run_spectrum(const SpectrumArgs& a, const Context& ctx) {
  check_extension(a.image, {".png"}, "--image");
  check_extension(a.plot, {".png", ".svg"}, "--plot");
  // Before any tile set is built: a layout of whole tiles holds at least a quarter of the target
  // (layout_for rounds the period), so a quarter that is already too many is refused here.
  if (periodogram_reach(a.set_points / 4) < 2) refuse_reach(a.set_points, a.set_points);
  const int threads = resolve_threads(a.threads);
  std::vector<std::string> methods = {a.source.method};
  std::stringstream list(a.compare);
  for (std::string m; std::getline(list, m, ',');)
    if (!m.empty()) methods.push_back(m);
  std::vector<Source> sources;
  for (std::size_t i = 0; i < methods.size(); ++i) {
    SourceArgs s = a.source;
    s.method = methods[i];
    if (i > 0) s.tiles.clear();
    sources.emplace_back(s, threads, !a.quiet);
  }
  ProgressReporter progress("points spectrum", double(a.sets) * double(sources.size()), !a.quiet);
  nlohmann::json results = nlohmann::json::array();
  std::vector<PlotSeries> series;
  for (const Source& src : sources) {
    const SetLayout l = layout_for(src, a.set_points);
    const double points = l.density * l.window.width() * l.window.height();
    if (periodogram_reach(points) < 2) refuse_reach(a.set_points, points);
    const Estimate e = estimate(src, l, a.sets, a.seed, threads, progress);
    const auto radial = radial_stats(e.spectrum);
    const double density = e.spectrum.density();
    nlohmann::json j = summary_json(summarize(radial, density));
    j["method"] = src.method();
    j["source"] = src.describe();
    j["points_per_set"] = double(e.spectrum.points) / double(e.spectrum.sets);
    j["rho_min"] = e.rho_min;
    j["seconds_per_set"] = e.seconds / a.sets;
    j["size"] = e.spectrum.size;
    results.push_back(j);
    series.push_back({src.method(), radial, principal_frequency(density)});
    if (&src == &sources.front() && !a.image.empty()) write_image(a.image, spectrum_image(e.spectrum));
  }
  progress.finish();
  nlohmann::json j = results[0];
  j["sets"] = a.sets;
  if (results.size() > 1) j["compare"] = nlohmann::json(results.begin() + 1, results.end());
  if (!a.image.empty()) j["image"] = a.image;
  if (!a.plot.empty()) write_plot(a.plot, series), j["plot"] = a.plot;
  emit(ctx, j, [&] {
    for (const auto& r : results)
      fmt::print(
          "{}: K={} sets of {:.0f} points: anisotropy up to {:.2f} dB (mean {:.2f}) in [0.5, 2] f_p, "
          "effective Nyquist {:.3f}, oscillations {:.2f}, peak at {:.2f} f_p, rho >= {:.4f}\n",
          r["source"].get<std::string>(), a.sets, r["points_per_set"].get<double>(),
          r["max_anisotropy_db"].get<double>(), r["mean_anisotropy_db"].get<double>(),
          r["effective_nyquist"].get<double>(), r["oscillations"].get<double>(), r["peak_frequency"].get<double>(),
          r["rho_min"].get<double>());
  });
}

void add_spectrum(CLI::App* points, Context& ctx) {
  auto* cmd = points->add_subcommand(
      "spectrum", "Power spectrum estimate of a method: K periodograms averaged (thesis sec. 6.2.2; Bartlett)");
  auto a = std::make_shared<SpectrumArgs>();
  add_source_options(cmd, a->source);
  cmd->add_option("--sets", a->sets, "Periodograms averaged, K (default 10)")->check(CLI::Range(1, 1000));
  cmd->add_option("--set-points", a->set_points, "Points per set, about (default 16384)")->check(CLI::Range(16.0, 1e7));
  cmd->add_option("--seed", a->seed, "Seed of the first set (set k uses seed + k) (default 1)");
  cmd->add_option("--compare", a->compare,
                  "Other methods estimated the same way, comma-separated (e.g. bridson,white)");
  cmd->add_option("--image", a->image, "The power spectrum as a picture (.png)");
  cmd->add_option("--plot", a->plot, "Radially averaged power and anisotropy of every method (.png or .svg)");
  cmd->add_option("--threads", a->threads, "Threads (default: all cores)");
  cmd->add_flag("--quiet", a->quiet, "No progress output on stderr");
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_spectrum(*a, ctx); });
}

void run_zoneplate(const ZoneplateArgs& a, const Context& ctx) {
  check_extension(a.out, {".png"}, "--out");
  const int threads = resolve_threads(a.threads);
  const Source src(a.source, threads, !a.quiet);
  const SetLayout l = layout_for(src, a.set_points);
  const auto xy = src.points(l.window, l.density, a.seed, threads, 0, false);
  const auto z = zone_plate(xy, l.window);
  write_image(a.out, z.image);
  nlohmann::json j = {{"method", src.method()},   {"source", src.describe()}, {"points", xy.size() / 2},
                      {"rms_inner", z.rms_inner}, {"rms_outer", z.rms_outer}, {"out", a.out}};
  emit(ctx, j, [&] {
    fmt::print("{}: zone plate from {} points -> {} (RMS error {:.3f} inside radius 12, {:.3f} beyond 24)\n",
               src.describe(), xy.size() / 2, a.out, z.rms_inner, z.rms_outer);
  });
}

void add_zoneplate(CLI::App* points, Context& ctx) {
  auto* cmd = points->add_subcommand("zoneplate", "The zone plate sampled with a method's points (thesis sec. 6.2.3)");
  auto a = std::make_shared<ZoneplateArgs>();
  add_source_options(cmd, a->source);
  cmd->add_option("--set-points", a->set_points, "Points, about (default 262144: one per pixel)")
      ->check(CLI::Range(16.0, 1e8));
  cmd->add_option("--seed", a->seed, "Seed (default 1)");
  cmd->add_option("--out", a->out, "The reconstructed zone plate (.png)")->required();
  cmd->add_option("--threads", a->threads, "Threads (default: all cores)");
  cmd->add_flag("--quiet", a->quiet, "No progress output on stderr");
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_zoneplate(*a, ctx); });
}

}  // namespace

void add_analysis_commands(CLI::App* points, Context& ctx) {
  add_analyze(points, ctx);
  add_spectrum(points, ctx);
  add_zoneplate(points, ctx);
}

}  // namespace tilekit::cli::pts
