// tilekit tiled tileset --kind corner|wang --colors C [--tiles DIR] [--tile-px N] [--name NAME] --out DIR
// tilekit tiled map --kind corner|wang --colors C --size WxH [--seed S] [...] --out DIR
// tilekit tiled import FILE.tsx [--wangset NAME]
// Tiled 1.8 tilesets and maps of corner and Wang sets, and Tiled Wang sets read back
// (tilemap/tiled_files.hpp, tilemap/tsx_reader.hpp).
#include <fmt/format.h>

#include <set>

#include "base/parse.hpp"
#include "cli/command.hpp"
#include "tilemap/tiled_files.hpp"
#include "tilemap/tsx_reader.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit::cli {

namespace {

struct TiledSetArgs {
  std::string kind = "corner", tiles, name, out;
  std::uint32_t colours = 2;
  int tile_px = 32;
};

struct TiledMapArgs {
  TiledSetArgs set;
  std::string size;
  std::uint64_t seed = 1;
};

struct TiledImportArgs {
  std::string file, wangset;
};

void add_tiled_set_options(CLI::App* cmd, TiledSetArgs& a) {
  cmd->add_option("--kind", a.kind, "corner (a Tiled corner set) or wang (a Tiled edge set)")
      ->check(CLI::IsMember({"corner", "wang"}))
      ->capture_default_str();
  cmd->add_option("--colors", a.colours, "Colours C: the sheet holds all C^4 tiles on a C^2 x C^2 torus")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_option("--tiles", a.tiles,
                  "Folder of tile images named by tile index (e.g. 17.png), as `atlas build --tiles` takes them; "
                  "default: built-in coloured tiles");
  cmd->add_option("--tile-px", a.tile_px, "Pixels per built-in tile")->check(CLI::Range(2, 512))->capture_default_str();
  cmd->add_option("--name", a.name,
                  "Tileset and Wang set name (default: corner-C or wang-C); files are named after it");
  cmd->add_option("--out", a.out, "Output folder (made if missing)")->required();
}

tilemap::TilesetRequest tileset_request(const TiledSetArgs& a) {
  return {a.kind == "wang" ? TileKind::Wang : TileKind::Corner, a.colours, a.tiles, a.tile_px, a.name, a.out, {}, {}};
}

nlohmann::json tileset_json(const tilemap::TilesetOutcome& o, const TiledSetArgs& a) {
  return {{"name", o.name}, {"kind", a.kind}, {"colors", a.colours}, {"tsx", o.tsx_path},    {"png", o.png_path},
          {"rows", o.rows}, {"cols", o.cols}, {"tiles", o.tiles},    {"tile_px", o.tile_px}, {"packing", o.how}};
}

void run_tileset(const TiledSetArgs& a, const Context& ctx) {
  const tilemap::TilesetOutcome o = tilemap::write_tiled_tileset(tileset_request(a));
  emit(ctx, tileset_json(o, a), [&] {
    fmt::print("{} tileset {}: {} tiles on a {}x{} sheet of {}-pixel tiles (packing: {}) -> {}, {}\n", a.kind, o.name,
               o.tiles, o.cols, o.rows, o.tile_px, o.how, o.tsx_path, o.png_path);
  });
}

void run_map(const TiledMapArgs& a, const Context& ctx) {
  const Dimensions d = parse_dimensions(a.size, 65536, std::int64_t(1) << 24, "--size WxH");
  const tilemap::MapOutcome o = tilemap::write_tiled_map({tileset_request(a.set), int(d.first), int(d.second), a.seed});
  const std::size_t distinct = std::set<TileIndex>(o.map.cells.begin(), o.map.cells.end()).size();
  nlohmann::json j = {{"tmx", o.tmx_path},          {"width", o.map.cols},
                      {"height", o.map.rows},       {"seed", a.seed},
                      {"algo", "direct"},           {"valid", true},
                      {"distinct_tiles", distinct}, {"tileset", tileset_json(o.tileset, a.set)}};
  emit(ctx, j, [&] {
    fmt::print("{}x{} map of {} (direct stochastic tiling, seed {}, {} distinct tiles, valid) -> {}, {}\n", o.map.cols,
               o.map.rows, o.tileset.name, a.seed, distinct, o.tmx_path, o.tileset.tsx_path);
  });
}

void run_import(const TiledImportArgs& a, const Context& ctx) {
  const tilemap::ImportedWangSet w = tilemap::read_tiled_wang_set(a.file, a.wangset);
  const TileSet& s = w.set;
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t k = 0; k < s.size(); ++k) list.push_back(s.file_colours(k));
  const nlohmann::json j = {{"name", s.name()},
                            {"kind", std::string(kind_name(s.kind()))},
                            {"tiled_type", w.type},
                            {"tiles", s.size()},
                            {"wang_tiles", w.wang_tiles},
                            {"colors", w.colour_names.size()},
                            {"horizontal_colors", s.horizontal_colours()},
                            {"vertical_colors", s.vertical_colours()},
                            {"colour_names", w.colour_names},
                            {"source", s.source()},
                            {"format", s.kind() == TileKind::Wang ? "n s w e" : "nw ne sw se"},
                            {"list", list},
                            {"tile_ids", w.tile_ids}};
  emit(ctx, j, [&] {
    fmt::print("{}: {} {} tiles ({} Wang tiles in Tiled, type {}), {} colours\n", s.name(), s.size(),
               kind_name(s.kind()), w.wang_tiles, w.type, w.colour_names.size());
    fmt::print("source: {}\n{}", s.source(), format_tile_set_text(s));
  });
}

}  // namespace

void add_tiled_commands(CLI::App& app, Context& ctx) {
  auto* tiled = app.add_subcommand("tiled", "Tiled map editor files: Wang-set tilesets, maps, and Wang sets read back");
  tiled->require_subcommand(1);
  auto* ts = tiled->add_subcommand("tileset",
                                   "Write NAME.tsx and NAME.png: a packed sheet (it tiles seamlessly) "
                                   "with a Tiled Wang set whose wangids match every tile");
  auto sa = std::make_shared<TiledSetArgs>();
  add_tiled_set_options(ts, *sa);
  add_json_flag(ts, ctx);
  ts->callback([sa, &ctx] { run_tileset(*sa, ctx); });
  auto* map = tiled->add_subcommand("map", "Write NAME-map.tmx (W x H, the direct stochastic tiling) and its tileset");
  auto ma = std::make_shared<TiledMapArgs>();
  add_tiled_set_options(map, ma->set);
  map->add_option("--size", ma->size, "Width x height in tiles, e.g. 64x48")->required();
  map->add_option("--seed", ma->seed, "Seed of the direct stochastic tiling (as `tile --seed`)")->capture_default_str();
  add_json_flag(map, ctx);
  map->callback([ma, &ctx] { run_map(*ma, ctx); });
  auto* im = tiled->add_subcommand("import", "Read a Tiled Wang set (.tsx, type corner or edge) as a tile set");
  auto ia = std::make_shared<TiledImportArgs>();
  im->add_option("FILE", ia->file, "Tiled tileset file (.tsx) with a Wang set")->required();
  im->add_option("--wangset", ia->wangset, "Name of the Wang set to read (default: the first)");
  add_json_flag(im, ctx);
  im->callback([ia, &ctx] { run_import(*ia, ctx); });
}

}  // namespace tilekit::cli
