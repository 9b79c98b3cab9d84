// tilekit atlas lookup|build: packings as texture atlases (thesis 5.4).
#include <fmt/format.h>

#include <iostream>

#include "atlas/atlas_image.hpp"
#include "atlas/lookup.hpp"
#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "cli/command.hpp"
#include "cli/packing_lookup.hpp"
#include "results/results_db.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit::cli {

namespace {

struct PackingArgs {
  std::string kind = "corner";
  std::uint32_t colours = 0;
  std::string db;
  bool no_db = false;
};

void add_packing_options(CLI::App* cmd, PackingArgs& a) {
  cmd->add_option("--kind", a.kind, "corner or wang")->check(CLI::IsMember({"corner", "wang"}))->capture_default_str();
  cmd->add_option("--colors", a.colours, "Number of colours C (the atlas is C^2 x C^2 tiles)")->required();
  cmd->add_option("--db", a.db, "Results database to look in first (default: the per-user one, if it exists)");
  cmd->add_flag("--no-db", a.no_db, "Do not look in any database (constructions only)");
}

AtlasLookup lookup(const PackingArgs& a) {
  const std::string db = a.no_db ? "" : a.db.empty() ? ResultsDb::default_path() : a.db;
  return lookup_with_database(a.kind == "wang" ? TileKind::Wang : TileKind::Corner, a.colours, db);
}

struct LookupArgs {
  PackingArgs packing;
  std::string format = "json", out, hash = "long-period";
  std::uint64_t seed = 1;
};

void run_lookup(const LookupArgs& a, const Context& ctx) {
  const HashKind hash = parse_hash_kind(a.hash);
  AtlasLookup l = lookup(a.packing);
  // The generated C and GLSL name the command that makes them again.
  const std::string command =
      fmt::format("tilekit atlas lookup --kind {} --colors {} --format {}", kind_name(l.kind), l.colours, a.format);
  std::string text = a.format == "json" ? lookup_json_text(l) + "\n"
                     : a.format == "c"
                         ? lookup_c_header(l, command)
                         : lookup_glsl(l, DirectTiling(l.kind, l.colours, hash, a.seed),
                                       fmt::format("{} --hash {} --seed {}", command, hash_kind_name(hash), a.seed));
  if (!a.out.empty()) {
    write_file_atomic(a.out, text);
    nlohmann::json s = {{"kind", a.packing.kind},
                        {"colors", l.colours},
                        {"rows", l.rows},
                        {"cols", l.cols},
                        {"source", l.source},
                        {"how", l.how},
                        {"closed_form", l.closed_form},
                        {"format", a.format},
                        {"out", a.out}};
    emit(ctx, s, [&] {
      fmt::print("{} packing over {} colours ({}: {}) written as {} to {}\n", a.packing.kind, l.colours, l.source,
                 l.how, a.format, a.out);
    });
    return;
  }
  if (a.format == "json" || !ctx.json) {
    std::cout << text;
    std::cout.flush();
    return;
  }
  nlohmann::json j = lookup_json(l);
  j["format"] = a.format;
  j["text"] = text;
  emit(ctx, j, [] {});
}

void add_lookup(CLI::App& atlas, Context& ctx) {
  auto* cmd = atlas.add_subcommand("lookup", "A packing as an atlas layout and its inverse: JSON, C header or GLSL");
  auto a = std::make_shared<LookupArgs>();
  add_packing_options(cmd, a->packing);
  cmd->add_option("--format", a->format, "json, c (header) or glsl (virtual texture -> atlas coordinate)")
      ->check(CLI::IsMember({"json", "c", "glsl"}))
      ->capture_default_str();
  cmd->add_option("--hash", a->hash, "Lattice hash of the direct stochastic tiling in the GLSL: perm or long-period")
      ->capture_default_str();
  cmd->add_option("--seed", a->seed, "Seed of that hash")->capture_default_str();
  cmd->add_option("--out", a->out, "Write the lookup to this file (atomically) instead of stdout");
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_lookup(*a, ctx); });
}

struct BuildArgs {
  PackingArgs packing;
  std::string tiles_dir, out;
  int tile_size = 32;
};

void run_build(const BuildArgs& a, const Context& ctx) {
  AtlasLookup l = lookup(a.packing);
  Image img = a.tiles_dir.empty() ? atlas_from_generated_tiles(l, a.tile_size) : atlas_from_tile_images(l, a.tiles_dir);
  const int size = img.width / l.cols;
  SeamReport seams = measure_seams(img, size);
  write_png(a.out, img);
  nlohmann::json j = {{"out", a.out},
                      {"kind", a.packing.kind},
                      {"colors", l.colours},
                      {"rows", l.rows},
                      {"cols", l.cols},
                      {"tile_size", size},
                      {"width", img.width},
                      {"height", img.height},
                      {"tiles", a.tiles_dir.empty() ? "generated" : a.tiles_dir},
                      {"source", l.source},
                      {"how", l.how},
                      {"seam_jump", seams.seam_jump},
                      {"interior_jump", seams.interior_jump}};
  emit(ctx, j, [&] {
    fmt::print("{}: {}x{} atlas of {} {} tiles over {} colours ({} {}x{} tiles, packing from {}: {})\n", a.out,
               img.width, img.height, l.cells.size(), a.packing.kind, l.colours, l.rows, l.cols, size, l.source, l.how);
    fmt::print("largest colour step across tile borders {} (inside tiles {})\n", seams.seam_jump, seams.interior_jump);
  });
}

void add_build(CLI::App& atlas, Context& ctx) {
  auto* cmd = atlas.add_subcommand(
      "build", "Build an atlas PNG from tile images named by tile index, or from generated colour-blend tiles");
  auto a = std::make_shared<BuildArgs>();
  add_packing_options(cmd, a->packing);
  cmd->add_option("--tiles", a->tiles_dir, "Folder of tile images named by tile index (e.g. 0.png ... 80.png)");
  cmd->add_option("--tile-size", a->tile_size, "Pixels per generated tile (without --tiles)")->capture_default_str();
  cmd->add_option("--out", a->out, "Atlas PNG to write")->required();
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_build(*a, ctx); });
}

}  // namespace

void add_atlas_commands(CLI::App& app, Context& ctx) {
  auto* atlas = app.add_subcommand("atlas", "Packings as texture atlases: lookup tables and atlas images");
  atlas->require_subcommand(1);
  add_lookup(*atlas, ctx);
  add_build(*atlas, ctx);
}

}  // namespace tilekit::cli
