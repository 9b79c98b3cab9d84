// tilekit points tiles | generate (and the group; analyze/spectrum/zoneplate in
// cmd_points_analyze.cpp, recursive/objects in cmd_points_recursive.cpp).
//
//   tilekit points tiles --method corner|wang|dual --colors C [--edge-colors E] --points N --rho R [--lloyd L]
//                        [--out F.ptiles] [--picture F.png|F.svg] [--db F | --no-db] [--no-check]
//   tilekit points generate [source options] --window x0,y0,x1,y1 --density D [--seed S]
//                        [--period M] [--out F.f32|.bin|.csv|.png|.svg] [--analyze]
#include "cli/cmd_points.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/progress.hpp"
#include "base/resources.hpp"
#include "base/signals.hpp"
#include "cli/numeric_flags.hpp"
#include "cli/run_options.hpp"
#include "points/analysis_plot.hpp"
#include "points/analysis_radius.hpp"
#include "points/generation_plan.hpp"
#include "points/point_io.hpp"
#include "points/tile_set_file.hpp"
#include "results/results_db.hpp"
#include "tilesets/tile_set.hpp"
#include "tiling/lattice_hash.hpp"

namespace tilekit::cli::pts {

using namespace tilekit::points;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

nlohmann::json radius_json(const RadiusStats& r) {
  nlohmann::json j = {{"count", r.count},
                      {"density", r.density},
                      {"min_distance", r.min_distance},
                      {"mean_nn_distance", r.mean_nn_distance},
                      {"rho", r.rho},
                      {"mean_nn_relative", r.mean_nn_relative}};
  if (r.tiled) j["rho_within"] = r.rho_within, j["rho_across"] = r.rho_across;
  return j;
}

// Run options: threads and seed (default 1).
RunOptions seeded_run() {
  RunOptions r;
  r.seed = 1;
  return r;
}

struct TilesArgs {
  std::string method = "corner", out, picture, db;
  std::uint32_t colors = 4, edge_colors = 1, points = 0;  // points 0: the method's default
  double rho = 0.75;
  int lloyd = 0;
  RunOptions run = seeded_run();
  bool no_db = false, no_check = false, quiet = false;
};

struct GenerateArgs {
  SourceArgs source;
  std::string window, out, density_expr, density_image;
  bool invert = false;
  double density = 0;
  RunOptions run = seeded_run();  // the seed of the tiling's hash tables (or the sampler)
  std::int64_t period = 0;
  int px = 800;
  bool analyze = false, quiet = false;
};

nlohmann::json tiles_json(const PoissonTileSet& set, int threads) {
  return {{"method", method_name(set.method)},
          {"colors", set.colours},
          {"edge_colors", set.edge_colours},
          {"points", set.points},
          {"rho", set.rho},
          {"radius", set.radius},
          {"tiles", set.tiles.size()},
          {"lattice_colors", set.lattice_colours()},
          {"corner_regions", set.corner_regions},
          {"edge_regions", set.edge_regions},
          {"interiors", set.interiors},
          {"seconds", set.seconds},
          {"threads", threads},
          {"seed", set.seed}};
}

// The independent neighbour check of a built set; a set that fails it is an internal error.
nlohmann::json check_tiles(const PoissonTileSet& set, int threads) {
  const auto c = check_poisson_tiles(set, threads);
  if (c.rho_across < set.rho || c.rho_within < set.rho || c.points_off_count)
    throw std::runtime_error("the built tile set failed its independent check");
  return {{"rho_within", c.rho_within},
          {"rho_across", c.rho_across},
          {"exhaustive", c.exhaustive},
          {"pairs_checked", c.pairs_checked},
          {"tiles_not_n_points", c.points_off_count}};
}

// --picture: 8 x 8 tiles of a tiling with the tile grid.
void write_tiles_picture(const PoissonTileSet& set, const std::string& path) {
  const PoissonTileGenerator gen(set, HashKind::LongPeriod, 1);
  const Window w{0, 0, 8, 8};
  const auto xy = gen.generate(w, set.points);
  if (is_svg(path))
    write_file_atomic(path, points_svg(xy, w, 640, 2, 1));
  else
    write_image(path, points_image(xy, w, 640, 2, 1));
}

void print_tiles(const PoissonTileSet& set, const nlohmann::json& j) {
  fmt::print(
      "{} Poisson disk tiles: C={} E={} N={} rho={}: {} tiles ({} corner, {} edge regions, {} interiors) in {:.2f} s\n",
      method_name(set.method), set.colours, set.edge_colours, set.points, set.rho, set.tiles.size(), set.corner_regions,
      set.edge_regions, set.interiors, set.seconds);
  if (j.contains("check"))
    fmt::print("  check: rho {:.4f} inside tiles, {:.4f} across borders ({} {})\n",
               j["check"]["rho_within"].get<double>(), j["check"]["rho_across"].get<double>(),
               j["check"]["pairs_checked"].get<std::uint64_t>(),
               j["check"]["exhaustive"].get<bool>() ? "neighbour pairs, all" : "random tilings");
  if (j.contains("out")) fmt::print("  -> {}\n", j["out"].get<std::string>());
  if (j.contains("tileset_id"))
    fmt::print("  stored as tile set {} in {}\n", j["tileset_id"].get<std::int64_t>(), j["db"].get<std::string>());
}

void run_tiles(const TilesArgs& a, const Context& ctx) {
  check_extension(a.picture, {".png", ".svg"}, "--picture");
  PoissonTileParams p;
  p.method = parse_poisson_tile_method(a.method);
  p.colours = a.colors;
  p.edge_colours = a.edge_colors;
  p.points = a.points;
  p.rho = a.rho;
  p.lloyd = a.lloyd;
  p.seed = a.run.seed;
  p.threads = a.run.resolved_threads();
  p.progress = !a.quiet;
  check_poisson_tile_params(p);
  const PoissonTileSet set = build_poisson_tiles(p);  // a signal ends it: exit 3, nothing written
  nlohmann::json j = tiles_json(set, p.threads);
  if (!a.no_check) j["check"] = check_tiles(set, p.threads);
  throw_if_interrupted();
  const std::string text = poisson_tiles_to_text(set);
  if (!a.out.empty()) write_file_atomic(a.out, text), j["out"] = a.out;
  if (!a.picture.empty()) write_tiles_picture(set, a.picture), j["picture"] = a.picture;
  if (!a.no_db) {
    ResultsDb db(a.db.empty() ? ResultsDb::default_path() : a.db);
    j["db"] = db.path();
    j["tileset_id"] = store_poisson_tiles(db, set, text, p.threads);
  }
  emit(ctx, j, [&] { print_tiles(set, j); });
}

// The points of `w` from a tile set straight into the point file a.out, a row of tiles at a time;
// returns how many. The file appears whole, or not at all (a full disk, an error, a signal).
std::uint64_t stream_points(const PoissonTileSet& set, const Window& w, const GenerationPlan& plan,
                            const GenerateArgs& a, int threads, ProgressReporter& progress) {
  const PoissonTileGenerator gen(set, parse_hash_kind(a.source.hash), a.run.seed, a.period);
  const double side = gen.tile_size(a.density);
  // A batch of rows of tiles in memory at once: 4 per thread, 16 bytes a point, twice.
  const double row_points = (std::floor(w.x1 / side) - std::floor(w.x0 / side) + 1) * double(set.points);
  require_memory(row_points * 16 * 2 * 4 * std::max(threads, 1), "a row of tiles of the window");
  PointFileWriter out(a.out, plan.largest_coordinate, 1 / std::sqrt(a.density));
  gen.generate_rows(
      w, a.density, [&](const std::vector<double>& row) { out.append(row.data(), row.size() / 2); }, threads,
      &progress);
  out.commit();
  return out.points();
}

// The made points into a.out (unless streamed there already): a point file or a picture.
void write_generated(const GenerateArgs& a, const Window& w, const std::vector<double>& xy) {
  if (is_point_file_path(a.out))
    write_points(a.out, xy);
  else if (is_svg(a.out))
    write_file_atomic(a.out, points_svg(xy, w, a.px, 1.5, 0));
  else
    write_image(a.out, points_image(xy, w, a.px, 1.5, 0));
}

std::unique_ptr<DensityFunction> density_function(const GenerateArgs& a, const Window& w) {
  if (!a.density_expr.empty() && !a.density_image.empty())
    throw InputError("give --density-expr or --density-image, not both");
  if (!a.density_expr.empty()) return expression_density(a.density_expr);
  if (!a.density_image.empty()) return image_density(a.density_image, w, a.density, a.invert);
  return nullptr;
}

void print_generated(const Source& src, const GenerateArgs& a, const Window& w, const nlohmann::json& j) {
  const std::uint64_t count = j["points"].get<std::uint64_t>();
  const double seconds = j["seconds"].get<double>();
  fmt::print("{}: {} points in [{}, {}) x [{}, {}) at density {} in {:.3f} s ({:.1f} M points/s){}\n", src.describe(),
             count, w.x0, w.x1, w.y0, w.y1, a.density, seconds, count / std::max(seconds, 1e-9) / 1e6,
             a.out.empty() ? "" : " -> " + a.out);
  if (j.contains("radius"))
    fmt::print("  rho {:.4f} (across tile borders {:.4f}), mean nearest-neighbour distance {:.3f} x 2 r_max\n",
               j["radius"]["rho"].get<double>(), j["radius"].value("rho_across", 0.0),
               j["radius"]["mean_nn_relative"].get<double>());
}

void run_generate(const GenerateArgs& a, const Context& ctx) {
  const Window w = parse_window(a.window);
  if (!a.out.empty() && !is_point_file_path(a.out)) check_extension(a.out, {".png", ".svg"}, "--out");
  const int threads = a.run.resolved_threads();
  if (!(a.density > 0) || !std::isfinite(a.density))
    throw InputError(fmt::format("--density must be positive, got {}", a.density));
  const std::unique_ptr<DensityFunction> fn = density_function(a, w);
  const bool tile_set = a.source.method == "corner" || a.source.method == "wang" || a.source.method == "dual";
  const GenerationPlan plan = plan_generation({w, a.density, tile_set, a.out, a.analyze}, fn.get());
  const Source src(a.source, threads, !a.quiet);
  const double tile = src.tile_size(a.density);
  ProgressReporter progress("points generate", 0, !a.quiet && plan.expected_points > 5e7);
  const auto start = std::chrono::steady_clock::now();
  std::vector<double> xy;
  std::uint64_t count = 0;
  if (plan.stream) {
    count = stream_points(*src.tiles(), w, plan, a, threads, progress);
  } else {
    xy = src.points(w, a.density, a.run.seed, threads, a.period, a.period > 0, fn.get(), &progress);
    count = xy.size() / 2;
  }
  const double seconds = seconds_since(start);
  progress.finish();
  if (!plan.stream) throw_if_interrupted();  // a signal during an unpolled source: nothing is written
  nlohmann::json j = {{"method", src.method()}, {"source", src.describe()},
                      {"points", count},        {"window", {w.x0, w.y0, w.x1, w.y1}},
                      {"density", a.density},   {"seed", a.run.seed},
                      {"seconds", seconds},     {"points_per_second", seconds > 0 ? double(count) / seconds : 0},
                      {"threads", threads}};
  if (tile > 0) j["tile_size"] = tile;
  if (plan.stream) j["streamed"] = true;  // written row by row: `seconds` includes the writing
  if (fn) j["density_function"] = fn->describe();
  if (a.analyze && count >= 2) j["radius"] = radius_json(radius_stats(xy, w.area(), tile));
  if (!a.out.empty()) {
    if (!plan.stream) write_generated(a, w, xy);
    j["out"] = a.out;
  }
  emit(ctx, j, [&] { print_generated(src, a, w, j); });
}

}  // namespace

void add_tiles_command(CLI::App* points, Context& ctx) {
  auto* cmd = points->add_subcommand("tiles", "Build a Poisson disk tile set (thesis ch. 4) and check it");
  auto a = std::make_shared<TilesArgs>();
  cmd->add_option("--method", a->method, "corner (thesis 4.5, default) | wang (edge-based, 4.3) | dual (Li et al.)");
  cmd->add_option("--colors", a->colors, "Colours C (default 4)")->check(CLI::Range(1u, kMaxCompleteSetColours));
  cmd->add_option("--edge-colors", a->edge_colors,
                  "corner: edge colours E hashed per lattice edge, C^4 E^4 tiles (thesis sec. 6.11; default 1)")
      ->check(CLI::Range(1, 16));
  cmd->add_option("--points", a->points, "Points per tile N (default 1024 for corner, 64 for wang and dual)")
      ->check(CLI::Range(1, 65536));
  cmd->add_option("--rho", a->rho, "Relative radius: no two points closer than 2 rho r_max(N) (default 0.75)");
  cmd->add_option("--lloyd", a->lloyd, "Lloyd iterations at least per region (default 0: only until rho is met)")
      ->check(CLI::Range(0, 10000));
  add_run_options(cmd, RunOptionFlags::Threads | RunOptionFlags::Seed, a->run);
  cmd->add_option("--out", a->out, "Write the tile set (text, points/README.md)");
  cmd->add_option("--picture", a->picture, "Draw 8 x 8 tiles of a tiling with the tile grid (.png or .svg)");
  cmd->add_option("--db", a->db, "Results database (default: $TILEKIT_DB or the per-user one)");
  cmd->add_flag("--no-db", a->no_db, "Do not store the set in the results database");
  cmd->add_flag("--no-check", a->no_check, "Skip the independent neighbour check");
  cmd->add_flag("--quiet", a->quiet, "No progress output on stderr");
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_tiles(*a, ctx); });
}

void add_generate_command(CLI::App* points, Context& ctx) {
  auto* cmd = points->add_subcommand(
      "generate",
      "All points of a window at a density: tiles through the direct stochastic tiling, or a reference set");
  auto a = std::make_shared<GenerateArgs>();
  add_source_options(cmd, a->source);
  cmd->add_option("--window", a->window, "x0,y0,x1,y1 (half-open; y grows south)")->required();
  cmd->add_option("--density", a->density,
                  "Points per unit area (with --density-expr: the scale of the base tiles; with --density-image: "
                  "the density of black)")
      ->required();
  cmd->add_option("--density-expr", a->density_expr,
                  "recursive: density as an expression in x, y, e.g. '2000 * exp(-20 * ((x-0.5)^2 + (y-0.5)^2))'")
      ->check(non_empty_text());
  cmd->add_option("--density-image", a->density_image,
                  "recursive: density from a grey image over the window (dark = dense)")
      ->check(non_empty_text());
  cmd->add_flag("--invert", a->invert, "--density-image: light = dense");
  add_run_options(cmd, RunOptionFlags::Threads | RunOptionFlags::Seed, a->run);
  cmd->add_option("--period", a->period, "Repeat the tiling every M tiles (a toroidal set)")
      ->check(CLI::Range(1, 1 << 30));
  cmd->add_option("--out", a->out,
                  "Points: .f32/.bin (float32 x,y pairs), .f64 (float64), .csv (a tile set's points stream to the file "
                  "row by row: the disk bounds the window, not the memory); or a picture: .png, .svg");
  cmd->add_option("--px", a->px, "Picture size in pixels (default 800)")->check(CLI::Range(16, 8192));
  cmd->add_flag("--analyze", a->analyze, "Add the radius analysis (overall and across tile borders)");
  cmd->add_flag("--quiet", a->quiet, "No progress output on stderr");
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_generate(*a, ctx); });
}

}  // namespace tilekit::cli::pts

namespace tilekit::cli {

void add_points_commands(CLI::App& app, Context& ctx) {
  auto* points = app.add_subcommand(
      "points", "Poisson disk tiles, recursive Wang tiles, blue-noise analysis (thesis ch. 4, 6, 7.6)");
  points->require_subcommand(1);
  pts::add_tiles_command(points, ctx);
  pts::add_generate_command(points, ctx);
  pts::add_analysis_commands(points, ctx);
  pts::add_recursive_commands(points, ctx);
}

}  // namespace tilekit::cli
