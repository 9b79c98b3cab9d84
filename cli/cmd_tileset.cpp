// tilekit tileset list | show SET
#include <fmt/format.h>

#include "atlas/render.hpp"
#include "cli/command.hpp"
#include "base/error.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit::cli {

namespace {

nlohmann::json describe(const TileSet& s) {
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t k = 0; k < s.size(); ++k) list.push_back(s.file_colours(k));
  return {{"name", s.name()},
          {"kind", std::string(kind_name(s.kind()))},
          {"tiles", s.size()},
          {"colors", s.colours()},
          {"horizontal_colors", s.horizontal_colours()},
          {"vertical_colors", s.vertical_colours()},
          {"source", s.source()},
          {"format", s.kind() == TileKind::Wang ? "n s w e" : "nw ne sw se"},
          {"list", list}};
}

}  // namespace

void add_tileset_commands(CLI::App& app, Context& ctx) {
  auto* ts = app.add_subcommand("tileset", "List and show built-in and file tile sets");
  ts->require_subcommand(1);

  auto* list = ts->add_subcommand("list", "List the built-in tile sets and name patterns");
  add_json_flag(list, ctx);
  list->callback([&ctx] {
    auto sets = builtin_tile_sets();
    nlohmann::json arr = nlohmann::json::array();
    for (auto& b : sets) arr.push_back({{"name", b.name}, {"description", b.description}});
    emit(ctx, {{"tilesets", arr}}, [&] {
      for (auto& b : sets) fmt::print("{:<28} {}\n", b.name, b.description);
    });
  });

  auto* show = ts->add_subcommand("show", "Show a tile set: kind, size, colours and tiles");
  static std::string set_name, out;
  static bool borders = false;
  static int tile_px = 0;
  show->add_option("SET", set_name, "Built-in name (see `tileset list`) or tile-set file")->required();
  show->add_option("--out", out, "Draw the set: F.svg or F.png (Wang tiles as triangles, corner tiles as discs)");
  show->add_flag("--borders", borders, "Draw tile borders");
  show->add_option("--tile-size", tile_px, "Pixels per tile (default: chosen from the set size)")
      ->check(CLI::Range(1, 512));
  add_json_flag(show, ctx);
  show->callback([&ctx] {
    if (!out.empty() && !atlas::is_picture_path(out))
      throw InputError(fmt::format("{}: unknown picture format (expected a .svg or .png file name)", out));
    TileSet s = resolve_tile_set(set_name);
    nlohmann::json j = describe(s);
    if (!out.empty()) {
      atlas::write_picture(atlas::draw_tile_set(s, {tile_px, borders}), out);
      j["out"] = out;
    }
    emit(ctx, j, [&] {
      fmt::print("{}: {} {} tiles, {} colours (horizontal {}, vertical {})\n", s.name(), s.size(),
                 kind_name(s.kind()), s.colours(), s.horizontal_colours(), s.vertical_colours());
      if (!s.source().empty()) fmt::print("source: {}\n", s.source());
      fmt::print("{}", format_tile_set_text(s));
      if (!out.empty()) fmt::print("wrote {}\n", out);
    });
  });
}

}  // namespace tilekit::cli
