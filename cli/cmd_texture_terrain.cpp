// tilekit texture terrain: terrain transition tiles (texture/terrain_tiles.hpp), the complete
// corner set over C terrains each from its own texture, written as a texture tile set (as
// `texture tiles` writes it, so `texture atlas` and the renderers take it), its packed sheet
// (the tiles laid out by the constructed packing: the sheet wraps seamlessly) and, with --tiled,
// a Tiled tileset (tilemap/tiled_files.hpp) whose Wang colours are the terrains.
#include <fmt/format.h>

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "atlas/atlas_image.hpp"
#include "atlas/lookup.hpp"
#include "base/error.hpp"
#include "cli/cmd_texture.hpp"
#include "cli/command.hpp"
#include "cli/run_options.hpp"
#include "image/image.hpp"
#include "texture/terrain_tiles.hpp"
#include "tilemap/tiled_files.hpp"
#include "tilemap/tiled_tileset.hpp"

namespace tilekit::cli {

namespace {

namespace fs = std::filesystem;

struct TerrainArgs {
  std::vector<std::string> terrains;
  std::string out, tiled, name, seams = "graph-cut";
  SynthesisOptions synthesis = [] {
    SynthesisOptions o;
    o.tile_px = 64;
    return o;
  }();
  RunOptions run = [] {
    RunOptions r;
    r.seed = SynthesisOptions{}.seed;
    return r;
  }();
  bool quiet = false;
};

struct TerrainSpec {
  std::string name, file;
  bool tileable = false;
};

// NAME=FILE[:tileable]: FILE a path or a fetched real texture's name (exemplar.hpp).
TerrainSpec parse_terrain(const std::string& spec) {
  const std::size_t eq = spec.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 >= spec.size())
    throw InputError(fmt::format("--terrain '{}': expected NAME=FILE[:tileable]", spec));
  TerrainSpec t{spec.substr(0, eq), spec.substr(eq + 1), false};
  const std::string suffix = ":tileable";
  if (t.file.size() > suffix.size() && t.file.compare(t.file.size() - suffix.size(), suffix.size(), suffix) == 0) {
    t.file.resize(t.file.size() - suffix.size());
    t.tileable = true;
  }
  return t;
}

std::string joined(const std::vector<std::string>& names, const char* sep) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : sep) + n;
  return s;
}

// The Tiled tileset of the set written to a.out: its Wang colours named after the terrains and
// drawn in each terrain's mean colour (that of its tile alone, all four corners k).
nlohmann::json write_tiled(const TerrainArgs& a, const TextureTileSet& s, const std::vector<std::string>& names) {
  tilemap::TilesetRequest req;
  req.kind = TileKind::Corner;
  req.colours = s.colours;
  req.tiles_dir = a.out;
  req.name = a.name.empty() ? "terrain-" + joined(names, "-") : a.name;
  req.out_dir = a.tiled;
  req.colour_names = names;
  for (std::uint32_t k = 0; k < s.colours; ++k) {
    const Image& tile = s.tiles[corner_index(CornerTile{k, k, k, k}, s.colours)];
    std::array<double, 3> sum{};
    for (int y = 0; y < tile.height; ++y)
      for (int x = 0; x < tile.width; ++x)
        for (int c = 0; c < 3; ++c) sum[std::size_t(c)] += tile.at(x, y)[c];
    const double texels = double(tile.width) * double(tile.height);
    req.colour_rgb.push_back({std::uint8_t(sum[0] / texels + 0.5), std::uint8_t(sum[1] / texels + 0.5),
                              std::uint8_t(sum[2] / texels + 0.5)});
  }
  const tilemap::TilesetOutcome t = tilemap::write_tiled_tileset(req);
  return {{"name", t.name}, {"tsx", t.tsx_path}, {"png", t.png_path}, {"rows", t.rows}, {"cols", t.cols}};
}

// What tiles.json and --json add to a texture tile set's report.
nlohmann::json terrain_report(const TerrainTileSet& r, const std::vector<TerrainTexture>& terrains,
                              const tilemap::TiledSheet& sheet, const std::string& seams) {
  nlohmann::json tj = nlohmann::json::array();
  for (std::size_t k = 0; k < terrains.size(); ++k)
    tj.push_back({{"colour", k},
                  {"name", r.names[k]},
                  {"exemplar", terrains[k].exemplar.name},
                  {"tileable", terrains[k].exemplar.wrap_w > 0},
                  {"texel_fraction", r.texel_fraction[k]},
                  {"cut_error", r.cut_error[k]}});
  return {{"terrains", tj},
          {"seams", seams},
          {"terrain_seam_step", r.seam_step},
          {"terrain_mean_step", r.terrain_step},
          {"sheet_packing", {{"rows", sheet.packing.rows}, {"cols", sheet.packing.cols}, {"how", sheet.how}}},
          {"packed_sheet", "sheet.png"}};
}

void run_terrain(const TerrainArgs& a, const Context& ctx) {
  std::vector<TerrainTexture> terrains;
  std::vector<std::string> names;
  for (const std::string& spec : a.terrains) {
    const TerrainSpec t = parse_terrain(spec);
    terrains.push_back({t.name, load_exemplar(t.file, t.tileable)});
    names.push_back(t.name);
  }
  SynthesisOptions o = a.synthesis;
  o.kind = TileKind::Corner;
  o.colours = std::uint32_t(terrains.size());
  o.threads = a.run.resolved_threads();
  o.seed = a.run.seed;
  o.progress = !a.quiet;
  check_terrain_options(terrains, o);
  // The sheet's packing (tilemap/tiled_tileset.hpp): the same layout the Tiled tileset gets.
  const tilemap::TiledSheet sheet = tilemap::sheet_layout(TileKind::Corner, o.colours);
  const AtlasLookup lookup = lookup_from_packing(sheet.packing, "construct", sheet.how, sheet.closed_form);
  const TerrainTileSet r = synthesize_terrain_tiles(terrains, o,
                                                    a.seams == "straight" ? TerrainSeams::Straight
                                                    : a.seams == "cut"    ? TerrainSeams::Cut
                                                                          : TerrainSeams::GraphCut);
  const TextureTileSet& s = r.set;
  const nlohmann::json report = terrain_report(r, terrains, sheet, a.seams);
  write_tile_set(s, a.out, joined(names, ","), [&](const std::string& dir, nlohmann::json& manifest) {
    manifest.update(report);
    write_png((fs::path(dir) / "sheet.png").string(), atlas_from_tile_images(lookup, dir));
  });
  nlohmann::json j = tile_set_json(s);
  j.update(report);
  j["out"] = a.out;
  j["packed_sheet"] = (fs::path(a.out) / "sheet.png").string();
  j["sheet"] = (fs::path(a.out) / "tileset.png").string();
  j["threads"] = o.threads;
  if (!a.tiled.empty()) j["tiled"] = write_tiled(a, s, names);
  emit(ctx, j, [&] {
    if (a.quiet) return;
    fmt::print("{}: {} terrain tiles over {} terrains ({}), {}x{} px ({:.2f} s)\n", a.out, s.tiles.size(),
               terrains.size(), joined(names, ", "), s.tile_px, s.tile_px, s.seconds);
    fmt::print("packed sheet ({}x{} tiles, wraps seamlessly): {}; picture of the set: {}\n", sheet.packing.cols,
               sheet.packing.rows, j["packed_sheet"].get<std::string>(), j["sheet"].get<std::string>());
    fmt::print("terrain seams: mean step {:.1f} per channel (the textures' own: {:.1f})\n", r.seam_step,
               r.terrain_step);
    if (j.contains("tiled"))
      fmt::print("Tiled tileset: {}, {}\n", j["tiled"]["tsx"].get<std::string>(), j["tiled"]["png"].get<std::string>());
  });
}

}  // namespace

void add_texture_terrain(CLI::App& texture, Context& ctx) {
  auto* cmd = texture.add_subcommand(
      "terrain",
      "Synthesise terrain transition tiles: the complete corner set over C terrain textures, joined along "
      "seams through the textures");
  auto a = std::make_shared<TerrainArgs>();
  cmd->add_option("--terrain", a->terrains,
                  "A terrain, NAME=FILE[:tileable] (2 to 6 of them; corner colour k is the k-th): FILE a texture "
                  "(PNG, JPEG, TIFF, TGA, PPM) or a fetched real texture by name (grass, gravel, oa-dirt, oa-rock, ...; "
                  "the oa-* and gimp-* ones are tileable); :tileable samples FILE as a torus")
      ->type_name("NAME=FILE[:tileable]")
      ->required();
  cmd->add_option("--out", a->out,
                  "Folder for tile-NNNN.png (by tile index), tiles.json, tileset.png, labels/ and sheet.png (the "
                  "packed sheet)")
      ->required();
  cmd->add_option("--tiled", a->tiled, "Folder for a Tiled tileset (NAME.tsx, NAME.png) with a corner Wang set");
  cmd->add_option("--name", a->name, "The Tiled tileset's name (default: terrain-NAME1-NAME2...)");
  cmd->add_option("--tile-px", a->synthesis.tile_px, "Tile size in pixels (even, 16..1024)")->capture_default_str();
  add_run_options(cmd, RunOptionFlags::Threads | RunOptionFlags::Seed, a->run);
  cmd->add_option("--search", a->synthesis.search,
                  "Candidate shared samples per sample and round (0: the first random draw, no search)")
      ->capture_default_str();
  cmd->add_option("--seams", a->seams,
                  "graph-cut: terrain boundaries along minimum-error cuts through the textures, refined by a graph "
                  "cut in tiles of two terrains; cut: the cuts alone; straight: on the tiles' middle lines (the "
                  "baseline)")
      ->check(CLI::IsMember({"graph-cut", "cut", "straight"}))
      ->capture_default_str();
  cmd->add_flag("--quiet", a->quiet, "No progress output on stderr and no summary on stdout");
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_terrain(*a, ctx); });
}

}  // namespace tilekit::cli
