// tilekit texture tiles|atlas|render: texture tiles from an exemplar (thesis sec. 5.3), atlases
// laid out by packings with mip chains (5.4), and renders of the infinite virtual texture on
// the CPU or through GLSL (headless EGL, Mesa llvmpipe).
#include "cli/cmd_texture.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "atlas/lookup.hpp"
#include "base/error.hpp"
#include "cli/command.hpp"
#include "cli/packing_lookup.hpp"
#include "cli/run_options.hpp"
#include "render/glsl_sampler.hpp"
#include "texture/texture_atlas.hpp"
#include "texture/tile_synthesis.hpp"

namespace tilekit::cli {

namespace {

namespace fs = std::filesystem;

HashKind hash_option(const std::string& name) {
  return parse_hash_kind(name);
}

struct TilesArgs {
  std::string exemplar, kind = "corner", out, period = "auto", perspective = "auto";
  SynthesisOptions synthesis;  // kind, threads, seed, progress and keep_period come from the fields here
  RunOptions run = [] {
    RunOptions r;
    r.seed = SynthesisOptions{}.seed;
    return r;
  }();
  bool tileable = false, quiet = false;
};

void run_tiles(const TilesArgs& a, const Context& ctx) {
  SynthesisOptions o = a.synthesis;
  o.kind = a.kind == "wang" ? TileKind::Wang : TileKind::Corner;
  o.threads = a.run.resolved_threads();
  o.seed = a.run.seed;
  o.progress = !a.quiet;
  o.keep_period = a.period == "auto";
  o.rectify = a.perspective == "auto";
  const Exemplar e = load_exemplar(a.exemplar, a.tileable);
  const TextureTileSet s = synthesize_tiles(e, o);
  write_tile_set(s, a.out, e.name);
  nlohmann::json j = tile_set_json(s);
  j["exemplar"] = e.name;
  j["tileable"] = e.wrap_w > 0;
  j["out"] = a.out;
  j["sheet"] = (fs::path(a.out) / "tileset.png").string();
  j["labels"] = (fs::path(a.out) / "labels").string();
  j["threads"] = o.threads;
  emit(ctx, j, [&] {
    fmt::print("{}: {} {} texture tiles over {} colours, {}x{} px, from {} ({}, {:.2f} s)\n", a.out, s.tiles.size(),
               a.kind, o.colours, o.tile_px, o.tile_px, e.name, s.method, s.seconds);
    fmt::print("boundary-cut error {:.1f} (first draw {:.1f}); picture of the set: {}\n", s.cut_error,
               s.cut_error_initial, j["sheet"].get<std::string>());
    if (s.perspective.applied)
      fmt::print(
          "photographed wall: rectified by its {} lines ({} of them, {:.3f} periods rms; spacing spread {:.2f})\n",
          s.perspective.axis == 0 ? "vertical" : "horizontal", s.perspective.lines, s.perspective.rms,
          s.perspective.spread);
    if (s.exemplar_scale[0] != 1 || s.exemplar_scale[1] != 1)
      fmt::print("periodic exemplar (period {:g} x {:g} px): resampled by {:.3f} x {:.3f} to whole periods per tile\n",
                 s.period.x, s.period.y, s.exemplar_scale[0], s.exemplar_scale[1]);
  });
}

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
  cmd->add_option("--kind", a->kind, "corner (Ng et al., thesis 5.3) or wang (Cohen et al. 2003)")
      ->check(CLI::IsMember({"corner", "wang"}))
      ->capture_default_str();
  cmd->add_option("--colors", a->synthesis.colours, "Colours C: the complete set has C^4 tiles")->required();
  cmd->add_option("--tile-px", a->synthesis.tile_px, "Tile size in pixels (even, 16..1024)")->capture_default_str();
  cmd->add_option("--out", a->out, "Folder for tile-NNNN.png (by tile index), tiles.json, tileset.png and labels/")
      ->required();
  add_run_options(cmd, RunOptionFlags::Threads | RunOptionFlags::Seed, a->run);
  cmd->add_option("--search", a->synthesis.search,
                  "Candidate shared samples per sample and round (0: the first random draw, no search)")
      ->capture_default_str();
  cmd->add_option("--centre-candidates", a->synthesis.centre_candidates, "Centre patches scored per tile")
      ->capture_default_str();
  cmd->add_option("--centre-cuts", a->synthesis.centre_cuts, "Of those, how many get the full graph cut")
      ->capture_default_str();
  cmd->add_flag("--thin-bands", a->synthesis.thin_bands,
                "Share fewer texels (margin 3n/64, a wide cut zone pulled to the centre): less grid repetition, "
                "but mip level 2 next to a border is no longer exact (not for a periodic exemplar)");
  cmd->add_option("--period", a->period,
                  "auto: keep a periodic exemplar's structure (resample it to whole periods per tile, samples in "
                  "phase); off: never")
      ->check(CLI::IsMember({"auto", "off"}))
      ->capture_default_str();
  cmd->add_option("--perspective", a->perspective,
                  "auto: rectify a photographed periodic exemplar whose lines converge (fit the homography that "
                  "makes them parallel and equally spaced) before keeping its period; off: never")
      ->check(CLI::IsMember({"auto", "off"}))
      ->capture_default_str();
  cmd->add_flag("--quiet", a->quiet, "No progress output on stderr");
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_tiles(*a, ctx); });
}

struct AtlasArgs {
  std::string dir, out, db, hash = "long-period", color_space = "srgb";
  std::uint64_t seed = 1;
  bool no_db = false, power_of_two = false;
};

void run_atlas(const AtlasArgs& a, const Context& ctx) {
  const TileSetManifest m = read_tile_set_manifest(a.dir);
  const TileKind kind = m.kind;
  // The constructed (or reference) packing unless a database is named, so that the atlas of a tile
  // set depends on nothing but the set: never on what the user's own database holds.
  const AtlasLookup lookup =
      a.db.empty() || a.no_db ? atlas_lookup(kind, m.colours) : lookup_with_database(kind, m.colours, a.db);
  TextureAtlas atlas = build_texture_atlas(lookup, a.dir);
  if (a.power_of_two) atlas = resample_to_power_of_two(atlas);
  atlas.transfer = a.color_space == "linear" ? Ktx2Transfer::Linear : Ktx2Transfer::Srgb;
  const RenderOptions ro{hash_option(a.hash), a.seed, 1, false};
  std::vector<std::pair<std::string, std::string>> shaders;
  for (const ShaderLanguage l : {ShaderLanguage::GlslVulkan, ShaderLanguage::Hlsl, ShaderLanguage::Wgsl})
    shaders.emplace_back(shader_language_extension(l), glsl_sampler_file(atlas, ro, l));
  const AtlasFiles f = write_texture_atlas(atlas, a.out, glsl_sampler_file(atlas, ro), shaders);
  nlohmann::json j = {{"out", f.levels[0]},
                      {"levels", f.levels},
                      {"ktx2", f.ktx2},
                      {"color_space", a.color_space},
                      {"manifest", f.manifest},
                      {"header", f.header},
                      {"glsl", f.glsl},
                      {"shaders", f.shaders},
                      {"kind", std::string(kind_name(kind))},
                      {"colors", lookup.colours},
                      {"rows", lookup.rows},
                      {"cols", lookup.cols},
                      {"tile_px", atlas.tile_px},
                      {"texels_per_tile", atlas_texels_per_tile(atlas)},
                      {"memory_bytes", RenderSource{RenderMethod::Tiles, &atlas, nullptr}.memory_bytes()},
                      {"width", atlas.levels[0].width},
                      {"height", atlas.levels[0].height},
                      {"source", lookup.source},
                      {"how", lookup.how}};
  emit(ctx, j, [&] {
    fmt::print(
        "{}: {}x{} atlas of {} {}-pixel tiles laid out by the {} packing ({}: {}), {} mip levels, {:.2f} MiB{}\n",
        f.levels[0], atlas.levels[0].width, atlas.levels[0].height, lookup.cells.size(), atlas.tile_px, kind_name(kind),
        lookup.source, lookup.how, f.levels.size(), j["memory_bytes"].get<double>() / (1 << 20),
        a.power_of_two ? fmt::format(" (resampled: {:.2f} texels a tile)", atlas_texels_per_tile(atlas)) : "");
    fmt::print(
        "KTX2 {} ({}, every level), manifest {}, C lookup {}, samplers {} (GLSL ES), {} (Vulkan GLSL), {} "
        "(HLSL), {} (WGSL)\n",
        f.ktx2, a.color_space, f.manifest, f.header, f.glsl, f.shaders[0], f.shaders[1], f.shaders[2]);
  });
}

void add_atlas(CLI::App& texture, Context& ctx) {
  auto* cmd = texture.add_subcommand(
      "atlas", "Lay a texture tile set out as the packing from `atlas lookup`: atlas PNG, mip chain, lookup, GLSL");
  auto a = std::make_shared<AtlasArgs>();
  cmd->add_option("DIR", a->dir, "Folder written by `tilekit texture tiles`")->required();
  cmd->add_option("--out", a->out,
                  "Atlas PNG; atlas.mipK.png, atlas.ktx2, atlas.json, atlas.h and the samplers atlas.glsl, "
                  "atlas.vk.glsl, atlas.hlsl and atlas.wgsl go beside it")
      ->required();
  cmd->add_option("--color-space", a->color_space,
                  "srgb: colour (atlas.ktx2 is RGBA8 sRGB); linear: data such as normals or roughness (RGBA8 UNORM)")
      ->check(CLI::IsMember({"srgb", "linear"}))
      ->capture_default_str();
  cmd->add_option("--db", a->db,
                  "Results database to look for a stored packing in first (default: none, the constructed or "
                  "reference packing)");
  cmd->add_flag("--no-db", a->no_db, "Constructions only, no database (the default; kept for scripts)");
  cmd->add_flag("--power-of-two", a->power_of_two,
                "Resample level 0 to the nearest power of two per axis (area-weighted, wrapping: C = 3, 5, 6, 7 "
                "make 9, 25, 36, 49 tiles a side) and make the mips again; tiles then span fractional texels");
  cmd->add_option("--hash", a->hash, "Lattice hash of the tiling in atlas.glsl: perm or long-period")
      ->capture_default_str();
  cmd->add_option("--seed", a->seed, "Seed of that hash")->capture_default_str();
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_atlas(*a, ctx); });
}

}  // namespace

void add_texture_commands(CLI::App& app, Context& ctx) {
  auto* texture = app.add_subcommand("texture", "Texture tiles from an exemplar, atlases from packings, renders");
  texture->require_subcommand(1);
  add_tiles(*texture, ctx);
  add_atlas(*texture, ctx);
  add_texture_render(*texture, ctx);
  add_texture_preview(*texture, ctx);
  add_texture_analyze(*texture, ctx);
}

}  // namespace tilekit::cli
