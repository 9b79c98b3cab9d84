// tilekit points recursive | objects.
//
//   tilekit points recursive [--points 512] [--subdivision 2] [--seed S] [--out F.rtiles] [--db F | --no-db]
//       (generate from it: points generate --method recursive --tiles F.rtiles ...)
//   tilekit points objects [source options] --window x0,y0,x1,y1 --density D --objects NAME:P,...
//       [--seed S] [--out F.csv|.svg] [--texture F.png]
#include <fmt/format.h>

#include <map>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/hash.hpp"
#include "base/parallel.hpp"
#include "results/results_db.hpp"
#include "cli/cmd_points.hpp"
#include "points/object_distribution.hpp"

namespace tilekit::cli::pts {

using namespace tilekit::points;

namespace {

struct RecursiveArgs {
  std::uint32_t points = 512;
  int subdivision = 2, threads = 0;
  std::uint64_t seed = 1;
  std::string out, db;
  bool no_db = false, quiet = false;
};

struct ObjectsArgs {
  SourceArgs source;
  std::string window, objects = "tree:0.5,rock:0.3,bush:0.2", out, texture;
  double density = 0;
  std::uint64_t seed = 1;
  int px = 640, threads = 0;
  bool quiet = false;
};

void run_recursive(const RecursiveArgs& a, const Context& ctx) {
  RecursiveTileParams p;
  p.points = a.points;
  p.subdivision = a.subdivision;
  p.seed = a.seed;
  p.threads = resolve_threads(a.threads);
  p.progress = !a.quiet;
  const RecursiveWangTiles t = build_recursive_tiles(p);
  const std::string text = recursive_tiles_to_text(t);
  nlohmann::json j = {{"points", t.points},
                      {"subdivision", t.n},
                      {"types", t.types()},
                      {"relax_iterations", t.relax_iterations},
                      {"relax_residual", t.relax_residual},
                      {"seconds", t.seconds},
                      {"seed", t.seed}};
  if (!a.out.empty()) write_file_atomic(a.out, text), j["out"] = a.out;
  if (!a.no_db) {
    ResultsDb db(a.db.empty() ? ResultsDb::default_path() : a.db);
    RunRecord run;
    run.command = "points recursive";
    run.params = {{"points", t.points}, {"subdivision", t.n}, {"seed", t.seed}};
    run.status = "complete";
    run.solutions = 1;
    run.seconds = t.seconds;
    run.threads = p.threads;
    run.id = db.begin_run(run);
    db.finish_run(run);
    j["db"] = db.path();
    j["tileset_id"] = db.add_tileset(fmt::format("recursive-wang-N{}-n{}-seed{}", t.points, t.n, t.seed),
                                     TileKind::Wang, t.types(), t.colours, fmt::format("{:016x}", stable_hash64(text)),
                                     fmt::format("tilekit points recursive (run {})", run.id), text);
  }
  emit(ctx, j, [&] {
    fmt::print(
        "recursive Wang tiles: 8 tiles of {} points, {}x{} subdivision, relaxed in {} iterations "
        "(snap residual {:.2g}), {:.2f} s{}\n",
        t.points, t.n, t.n, t.relax_iterations, t.relax_residual, t.seconds, a.out.empty() ? "" : " -> " + a.out);
  });
}

void add_recursive(CLI::App* points, Context& ctx) {
  auto* cmd =
      points->add_subcommand("recursive", "Build recursive Wang tiles for progressive blue noise (Kopf et al. 2006)");
  auto a = std::make_shared<RecursiveArgs>();
  cmd->add_option("--points", a->points, "Points per tile N (default 512)")->check(CLI::Range(8, 65536));
  cmd->add_option("--subdivision", a->subdivision, "Sub-tiles per side n (default 2)")->check(CLI::Range(2, 8));
  cmd->add_option("--seed", a->seed, "Random seed (default 1)");
  cmd->add_option("--threads", a->threads, "Threads (default: all cores)");
  cmd->add_option("--out", a->out, "Write the tile set (text, points/README.md)");
  cmd->add_option("--db", a->db, "Results database (default: $TILEKIT_DB or the per-user one)");
  cmd->add_flag("--no-db", a->no_db, "Do not store the set in the results database");
  cmd->add_flag("--quiet", a->quiet, "No progress output on stderr");
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_recursive(*a, ctx); });
}

void run_objects(const ObjectsArgs& a, const Context& ctx) {
  const Window w = parse_window(a.window);
  check_extension(a.out, {".csv", ".svg"}, "--out");
  check_extension(a.texture, {".png"}, "--texture");
  auto classes = parse_object_classes(a.objects);
  const int threads = resolve_threads(a.threads);
  const Source src(a.source, threads, !a.quiet);
  if (!src.tiles()) throw InputError("--method must be corner, wang or dual for objects (a Poisson disk tile set)");
  const PoissonTileGenerator gen(*src.tiles(), parse_hash_kind(a.source.hash), a.seed);
  const ObjectDistribution pod(gen, a.density, classes, a.seed);
  const auto placed = pod.scatter(w);
  std::vector<std::uint64_t> count(classes.size(), 0);
  for (const auto& o : placed) ++count[o.object];
  nlohmann::json objects = nlohmann::json::object();
  double chi2 = 0;
  for (std::size_t k = 0; k < classes.size(); ++k) {
    const double expected = classes[k].probability * double(placed.size());
    objects[classes[k].name] = {{"count", count[k]}, {"expected", expected}};
    if (expected > 0) chi2 += (double(count[k]) - expected) * (double(count[k]) - expected) / expected;
  }
  nlohmann::json j = {{"source", src.describe()},
                      {"points", placed.size()},
                      {"objects", objects},
                      {"chi_square", chi2},
                      {"degrees_of_freedom", classes.size() - 1},
                      {"disk_radius", pod.radius()}};
  if (!a.out.empty()) {
    std::string text;
    if (a.out.ends_with(".csv")) {
      text = "x,y,object\n";
      for (const auto& o : placed) text += fmt::format("{},{},{}\n", o.x, o.y, classes[o.object].name);
    } else {
      static constexpr const char* kFill[] = {"#2e7d32", "#795548", "#fbc02d", "#1e88e5", "#d81b60", "#00897b"};
      const double scale = a.px / std::max(w.width(), w.height());
      text = fmt::format("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{:.0f}\" height=\"{:.0f}\">\n",
                         w.width() * scale, w.height() * scale);
      for (const auto& o : placed)
        text += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{:.2f}\" fill=\"{}\"/>\n", (o.x - w.x0) * scale,
                            (o.y - w.y0) * scale, pod.radius() * scale, kFill[o.object % std::size(kFill)]);
      text += "</svg>\n";
    }
    write_file_atomic(a.out, text);
    j["out"] = a.out;
  }
  if (!a.texture.empty()) write_image(a.texture, pod.texture(w, a.px)), j["texture"] = a.texture;
  emit(ctx, j, [&] {
    fmt::print("{} objects in [{}, {}) x [{}, {}):", placed.size(), w.x0, w.x1, w.y0, w.y1);
    for (std::size_t k = 0; k < classes.size(); ++k) fmt::print(" {} {}", classes[k].name, count[k]);
    fmt::print(" (chi-square {:.2f}, {} degrees of freedom){}\n", chi2, classes.size() - 1,
               a.out.empty() ? "" : " -> " + a.out);
  });
}

void add_objects(CLI::App* points, Context& ctx) {
  auto* cmd = points->add_subcommand(
      "objects", "Objects scattered by the procedural object distribution function (thesis sec. 7.6)");
  auto a = std::make_shared<ObjectsArgs>();
  add_source_options(cmd, a->source);
  cmd->add_option("--window", a->window, "x0,y0,x1,y1")->required();
  cmd->add_option("--density", a->density, "Objects per unit area (the scale s)")->required();
  cmd->add_option("--objects", a->objects,
                  "Classes and probabilities, NAME:P,... (default tree:0.5,rock:0.3,bush:0.2)");
  cmd->add_option("--seed", a->seed, "Seed of the tiling and of the object hash (default 1)");
  cmd->add_option("--out", a->out, "Objects as CSV (x,y,object) or an SVG picture");
  cmd->add_option("--texture", a->texture, "The procedural texture: disks coloured by class (.png)");
  cmd->add_option("--px", a->px, "Texture size in pixels (default 640)")->check(CLI::Range(16, 8192));
  cmd->add_option("--threads", a->threads, "Threads (default: all cores)");
  cmd->add_flag("--quiet", a->quiet, "No progress output on stderr");
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_objects(*a, ctx); });
}

}  // namespace

void add_recursive_commands(CLI::App* points, Context& ctx) {
  add_recursive(points, ctx);
  add_objects(points, ctx);
}

}  // namespace tilekit::cli::pts
