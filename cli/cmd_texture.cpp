// tilekit texture tiles|atlas|render: texture tiles from an exemplar (thesis sec. 5.3), atlases
// laid out by packings with mip chains (5.4), and renders of the infinite virtual texture on
// the CPU or through GLSL (headless EGL, Mesa llvmpipe).
#include "cli/cmd_texture.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>

#include "atlas/lookup.hpp"
#include "base/error.hpp"
#include "base/parallel.hpp"
#include "cli/command.hpp"
#include "results/results_db.hpp"
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

void add_tiles(CLI::App& texture, Context& ctx) {
  auto* cmd =
      texture.add_subcommand("tiles", "Synthesise the complete corner or Wang texture tile set from an exemplar");
  static std::string exemplar, kind = "corner", out;
  static SynthesisOptions o;
  static int threads = 0;
  static bool quiet = false;
  cmd->add_option("--exemplar", exemplar,
                  "Example texture (PNG or JPEG), or a fetched real texture by name: brick, grass, gravel")
      ->required();
  cmd->add_option("--kind", kind, "corner (Ng et al., thesis 5.3) or wang (Cohen et al. 2003)")
      ->check(CLI::IsMember({"corner", "wang"}))
      ->capture_default_str();
  cmd->add_option("--colors", o.colours, "Colours C: the complete set has C^4 tiles")->required();
  cmd->add_option("--tile-px", o.tile_px, "Tile size in pixels (even, 16..1024)")->capture_default_str();
  cmd->add_option("--out", out, "Folder for tile-NNNN.png (by tile index), tiles.json and tileset.png")->required();
  cmd->add_option("--seed", o.seed, "Seed: the same seed gives the same tiles on any thread count")
      ->capture_default_str();
  cmd->add_option("--threads", threads, "Threads (default: every core)");
  cmd->add_option("--search", o.search, "Candidate samples per colour and round (0: the first random draw, no search)")
      ->capture_default_str();
  cmd->add_flag("--quiet", quiet, "No progress output on stderr");
  add_json_flag(cmd, ctx);
  cmd->callback([&ctx] {
    o.kind = kind == "wang" ? TileKind::Wang : TileKind::Corner;
    o.threads = threads_or_default(threads);
    o.progress = !quiet;
    const Exemplar e = load_exemplar(exemplar);
    const TextureTileSet s = synthesize_tiles(e, o);
    write_tile_set(s, out, e.name);
    nlohmann::json j = tile_set_json(s);
    j["exemplar"] = e.name;
    j["out"] = out;
    j["sheet"] = (fs::path(out) / "tileset.png").string();
    j["threads"] = o.threads;
    emit(ctx, j, [&] {
      fmt::print("{}: {} {} texture tiles over {} colours, {}x{} px, from {} ({}, {:.2f} s)\n", out, s.tiles.size(),
                 kind, o.colours, o.tile_px, o.tile_px, e.name, s.method, s.seconds);
      fmt::print("boundary-cut error {:.1f} (first draw {:.1f}); picture of the set: {}\n", s.cut_error,
                 s.cut_error_initial, j["sheet"].get<std::string>());
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

}  // namespace

void add_texture_commands(CLI::App& app, Context& ctx) {
  auto* texture = app.add_subcommand("texture", "Texture tiles from an exemplar, atlases from packings, renders");
  texture->require_subcommand(1);
  add_tiles(*texture, ctx);
  add_atlas(*texture, ctx);
  add_texture_render(*texture, ctx);
  add_texture_preview(*texture, ctx);
}

}  // namespace tilekit::cli
