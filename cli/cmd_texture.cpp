// tilekit texture tiles|atlas|render: texture tiles from an exemplar (thesis sec. 5.3), atlases
// laid out by packings with mip chains (5.4), and renders of the infinite virtual texture on
// the CPU or through GLSL (headless EGL, Mesa llvmpipe).
#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <regex>

#include "atlas/lookup.hpp"
#include "base/error.hpp"
#include "base/parallel.hpp"
#include "cli/command.hpp"
#include "results/results_db.hpp"
#include "texture/gl_renderer.hpp"
#include "texture/glsl_sampler.hpp"
#include "texture/texture_atlas.hpp"
#include "texture/tile_synthesis.hpp"

namespace tilekit::cli {

namespace {

namespace fs = std::filesystem;

int threads_or_default(int threads) {
  return threads == 0 ? default_thread_count() : checked_thread_count(threads);
}

HashKind hash_option(const std::string& name) {
  return parse_hash_kind(name);
}

struct TilesArgs {
  std::string exemplar, kind = "corner", out, period = "auto";
  SynthesisOptions o;
  int threads = 0;
  bool tileable = false, quiet = false;
};

void add_tiles(CLI::App& texture, Context& ctx) {
  auto* cmd =
      texture.add_subcommand("tiles", "Synthesise the complete corner or Wang texture tile set from an exemplar");
  auto a = std::make_shared<TilesArgs>();
  cmd->add_option("--exemplar", a->exemplar,
                  "Example texture (PNG, JPEG, TGA, PPM), or a fetched real texture by name: brick, grass, gravel, "
                  "gimp-stone33, gimp-walnut, oa-dirt, oa-brick, oa-rock")
      ->required();
  cmd->add_flag("--tileable", a->tileable,
                "The exemplar repeats seamlessly (a pattern or game texture): sample it as a torus "
                "(the fetched gimp-* and oa-* textures are)");
  cmd->add_option("--kind", a->kind, "corner or wang")->check(CLI::IsMember({"corner", "wang"}))->capture_default_str();
  cmd->add_option("--colors", a->o.colours, "Colours C: the complete set has C^4 tiles")->required();
  cmd->add_option("--tile-px", a->o.tile_px, "Tile size in pixels (even, 16..1024)")->capture_default_str();
  cmd->add_option("--out", a->out, "Folder for tile-NNNN.png (by tile index), tiles.json, tileset.png and labels/")
      ->required();
  cmd->add_option("--seed", a->o.seed, "Seed: the same seed gives the same tiles on any thread count")
      ->capture_default_str();
  cmd->add_option("--threads", a->threads, "Threads (default: every core)");
  cmd->add_option("--search", a->o.search,
                  "Candidate shared samples per sample and round (0: the first random draw, no search)")
      ->capture_default_str();
  cmd->add_option("--centre-candidates", a->o.centre_candidates, "Centre patches scored per tile")
      ->capture_default_str();
  cmd->add_option("--centre-cuts", a->o.centre_cuts, "Of those, how many get the full graph cut")
      ->capture_default_str();
  cmd->add_option("--period", a->period,
                  "auto: keep a periodic exemplar's structure (resample it to whole periods per tile, samples in "
                  "phase); off: never")
      ->check(CLI::IsMember({"auto", "off"}))
      ->capture_default_str();
  cmd->add_flag("--quiet", a->quiet, "No progress output on stderr");
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] {
    SynthesisOptions o = a->o;
    o.kind = a->kind == "wang" ? TileKind::Wang : TileKind::Corner;
    o.threads = threads_or_default(a->threads);
    o.progress = !a->quiet;
    o.keep_period = a->period == "auto";
    const Exemplar e = load_exemplar(a->exemplar, a->tileable);
    const TextureTileSet s = synthesize_tiles(e, o);
    write_tile_set(s, a->out, e.name);
    nlohmann::json j = tile_set_json(s);
    j["exemplar"] = e.name;
    j["tileable"] = e.wrap_w > 0;
    j["out"] = a->out;
    j["sheet"] = (fs::path(a->out) / "tileset.png").string();
    j["labels"] = (fs::path(a->out) / "labels").string();
    j["threads"] = o.threads;
    emit(ctx, j, [&] {
      fmt::print("{}: {} {} texture tiles over {} colours, {}x{} px, from {} ({}, {:.2f} s)\n", a->out, s.tiles.size(),
                 a->kind, o.colours, o.tile_px, o.tile_px, e.name, s.method, s.seconds);
      fmt::print("boundary-cut error {:.1f} (first draw {:.1f}); picture of the set: {}\n", s.cut_error,
                 s.cut_error_initial, j["sheet"].get<std::string>());
      if (s.exemplar_scale[0] != 1 || s.exemplar_scale[1] != 1)
        fmt::print(
            "periodic exemplar (period {:g} x {:g} px): resampled by {:.3f} x {:.3f} to whole periods per tile\n",
            s.period.x, s.period.y, s.exemplar_scale[0], s.exemplar_scale[1]);
    });
  });
}

void add_atlas(CLI::App& texture, Context& ctx) {
  auto* cmd = texture.add_subcommand(
      "atlas", "Lay a texture tile set out as the packing from `atlas lookup`: atlas PNG, mip chain, lookup, GLSL");
  static std::string dir, out, db, hash = "long-period";
  static std::uint64_t seed = 1;
  static bool no_db = false;
  cmd->add_option("DIR", dir, "Folder written by `tilekit texture tiles`")->required();
  cmd->add_option("--out", out, "Atlas PNG; atlas.mipK.png, atlas.json, atlas.h and atlas.glsl go beside it")
      ->required();
  cmd->add_option("--db", db, "Results database to look for a stored packing in (default: the per-user one)");
  cmd->add_flag("--no-db", no_db, "Constructions only, no database");
  cmd->add_option("--hash", hash, "Lattice hash of the tiling in atlas.glsl: perm or long-period")
      ->capture_default_str();
  cmd->add_option("--seed", seed, "Seed of that hash")->capture_default_str();
  add_json_flag(cmd, ctx);
  cmd->callback([&ctx] {
    const std::string manifest = (fs::path(dir) / "tiles.json").string();
    std::ifstream in(manifest);
    if (!in) throw InputError(fmt::format("{}: no tiles.json (make the tiles with `tilekit texture tiles`)", manifest));
    nlohmann::json m;
    try {
      m = nlohmann::json::parse(in);
    } catch (const std::exception& e) {
      throw InputError(fmt::format("{}: not JSON ({})", manifest, e.what()));
    }
    const TileKind kind = m.value("kind", "corner") == "wang" ? TileKind::Wang : TileKind::Corner;
    LookupOptions lo;
    if (!no_db) lo.db_path = db.empty() ? ResultsDb::default_path() : db;
    const AtlasLookup lookup = atlas_lookup(kind, m.value("colors", 0u), lo);
    const TextureAtlas atlas = build_texture_atlas(lookup, dir);
    const RenderOptions ro{hash_option(hash), seed, 1, false};
    const AtlasFiles f = write_texture_atlas(atlas, out, glsl_sampler_file(atlas, ro));
    nlohmann::json j = {{"out", f.levels[0]},
                        {"levels", f.levels},
                        {"manifest", f.manifest},
                        {"header", f.header},
                        {"glsl", f.glsl},
                        {"kind", std::string(kind_name(kind))},
                        {"colors", lookup.colours},
                        {"rows", lookup.rows},
                        {"cols", lookup.cols},
                        {"tile_px", atlas.tile_px},
                        {"width", atlas.levels[0].width},
                        {"height", atlas.levels[0].height},
                        {"source", lookup.source},
                        {"how", lookup.how}};
    emit(ctx, j, [&] {
      fmt::print("{}: {}x{} atlas of {} {}-pixel tiles laid out by the {} packing ({}: {}), {} mip levels\n",
                 f.levels[0], atlas.levels[0].width, atlas.levels[0].height, lookup.cells.size(), atlas.tile_px,
                 kind_name(kind), lookup.source, lookup.how, f.levels.size());
      fmt::print("manifest {}, C lookup {}, GLSL sampler {}\n", f.manifest, f.header, f.glsl);
    });
  });
}

View parse_view(const std::string& size, double scale, const std::string& origin, double tilt) {
  View v;
  std::smatch m;
  static const std::regex wh(R"((\d{1,5})x(\d{1,5}))"), uv(R"((-?[0-9.eE+-]+),(-?[0-9.eE+-]+))");
  if (!std::regex_match(size, m, wh))
    throw InputError(fmt::format("--size must be WxH (e.g. 1024x768), got '{}'", size));
  v.width = std::stoi(m[1]);
  v.height = std::stoi(m[2]);
  if (!origin.empty()) {
    if (!std::regex_match(origin, m, uv))
      throw InputError(fmt::format("--origin must be U,V in texels, got '{}'", origin));
    try {
      v.origin_u = std::stod(m[1]);
      v.origin_v = std::stod(m[2]);
    } catch (const std::exception&) {
      throw InputError(fmt::format("--origin must be U,V in texels, got '{}'", origin));
    }
  }
  v.scale = scale;
  v.tilt = tilt;
  return v;
}

struct Difference {
  int max = 0;
  double mean = 0;
};
Difference difference(const Image& a, const Image& b) {
  Difference d;
  double sum = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const int v = std::abs(int(a.pixels[i]) - int(b.pixels[i]));
    d.max = std::max(d.max, v);
    sum += v;
  }
  d.mean = a.pixels.empty() ? 0 : sum / double(a.pixels.size());
  return d;
}

void add_render(CLI::App& texture, Context& ctx) {
  auto* cmd =
      texture.add_subcommand("render", "Render a window of the infinite virtual texture (CPU, or GLSL with --glsl)");
  static std::string atlas_path, size = "1024x1024", origin, out, hash = "long-period";
  static double scale = 1, tilt = 0;
  static std::uint64_t seed = 1;
  static int threads = 0;
  static bool glsl = false, compare = false, quiet = false;
  cmd->add_option("--atlas", atlas_path, "Atlas PNG (or its .json) written by `tilekit texture atlas`")->required();
  cmd->add_option("--size", size, "Window in pixels, WxH")->capture_default_str();
  cmd->add_option("--scale", scale, "Texels of the virtual texture per pixel (at the bottom, when tilted)")
      ->capture_default_str();
  cmd->add_option("--origin", origin, "Texel of the virtual texture at the window's top-left, U,V (default 0,0)");
  cmd->add_option("--tilt", tilt, "Perspective: rows at the top are (1+T)^2 times farther (0: flat)")
      ->capture_default_str();
  cmd->add_option("--hash", hash, "Lattice hash of the direct stochastic tiling: perm or long-period")
      ->capture_default_str();
  cmd->add_option("--seed", seed, "Seed of that hash")->capture_default_str();
  cmd->add_option("--threads", threads,
                  "CPU renderer threads, and llvmpipe's unless LP_NUM_THREADS is set (default: every core)");
  cmd->add_option("--out", out, "Image to write (PNG)")->required();
  cmd->add_flag("--glsl", glsl, "Render with the GLSL sampler through EGL (surfaceless Mesa, llvmpipe)");
  cmd->add_flag("--compare", compare, "Render both ways, write the GLSL image, report the largest difference");
  cmd->add_flag("--quiet", quiet, "No progress output on stderr");
  add_json_flag(cmd, ctx);
  cmd->callback([&ctx] {
    const TextureAtlas atlas = read_texture_atlas(atlas_path);
    const View view = parse_view(size, scale, origin, tilt);
    RenderOptions o{hash_option(hash), seed, threads_or_default(threads), !quiet};
    view_rows(view, atlas.tile_px);  // bad views are exit 2 before anything runs
    if ((glsl || compare) && !std::getenv("LP_NUM_THREADS"))
      setenv("LP_NUM_THREADS", std::to_string(o.threads).c_str(), 1);  // llvmpipe reads it when the context is made
    nlohmann::json j = {{"out", out},
                        {"width", view.width},
                        {"height", view.height},
                        {"scale", view.scale},
                        {"tilt", view.tilt},
                        {"hash", hash},
                        {"seed", seed},
                        {"threads", o.threads},
                        {"kind", std::string(kind_name(atlas.lookup.kind))},
                        {"colors", atlas.lookup.colours}};
    Image img;
    auto timed = [](auto&& f) {
      const auto t0 = std::chrono::steady_clock::now();
      f();
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    };
    Image cpu;
    if (!glsl || compare) {
      const double s = timed([&] { cpu = render_cpu(atlas, view, o); });
      j["cpu_seconds"] = s;
      j["cpu_mpixels_per_second"] = double(view.width) * view.height / s / 1e6;
      img = cpu;
    }
    if (glsl || compare) {
      try {
        GlRenderer r(atlas, view, o);
        const double s = r.draw(1);
        img = r.read();
        j["gl_renderer"] = r.renderer();
        j["glsl_seconds"] = s;
      } catch (const GlUnavailable& e) {
        std::cerr << "tilekit: texture render --glsl skipped: " << e.what() << std::endl;
        throw Exit{2};
      }
      if (compare) {
        const Difference d = difference(cpu, img);
        j["max_difference"] = d.max;
        j["mean_difference"] = d.mean;
      }
    }
    j["renderer"] = glsl || compare ? "glsl" : "cpu";
    write_png(out, img);
    emit(ctx, j, [&] {
      fmt::print("{}: {}x{} window of the virtual texture (scale {}, tilt {}), {} renderer{}\n", out, view.width,
                 view.height, view.scale, view.tilt, j["renderer"].get<std::string>(),
                 j.contains("gl_renderer") ? " on " + j["gl_renderer"].get<std::string>() : "");
      if (j.contains("cpu_seconds"))
        fmt::print("CPU reference: {:.3f} s, {:.1f} Mpixel/s on {} threads\n", j["cpu_seconds"].get<double>(),
                   j["cpu_mpixels_per_second"].get<double>(), o.threads);
      if (compare)
        fmt::print("GLSL vs CPU: largest difference {}/255, mean {:.4f}/255\n", j["max_difference"].get<int>(),
                   j["mean_difference"].get<double>());
    });
  });
}

}  // namespace

void add_texture_commands(CLI::App& app, Context& ctx) {
  auto* texture = app.add_subcommand("texture", "Texture tiles from an exemplar, atlases from packings, renders");
  texture->require_subcommand(1);
  add_tiles(*texture, ctx);
  add_atlas(*texture, ctx);
  add_render(*texture, ctx);
  add_texture_analyze_command(*texture, ctx);
}

}  // namespace tilekit::cli
