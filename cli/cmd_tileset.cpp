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

struct ShowArgs {
  std::string set_name, out;
  bool borders = false;
  int tile_px = 0;
};

void run_show(const ShowArgs& a, const Context& ctx) {
  if (!a.out.empty() && !atlas::is_picture_path(a.out))
    throw InputError(fmt::format("{}: unknown picture format (expected a .svg or .png file name)", a.out));
  TileSet s = resolve_tile_set(a.set_name);
  nlohmann::json j = describe(s);
  if (!a.out.empty()) {
    atlas::write_picture(atlas::draw_tile_set(s, {a.tile_px, a.borders}), a.out);
    j["out"] = a.out;
  }
  emit(ctx, j, [&] {
    fmt::print("{}: {} {} tiles, {} colours (horizontal {}, vertical {})\n", s.name(), s.size(), kind_name(s.kind()),
               s.colours(), s.horizontal_colours(), s.vertical_colours());
    if (!s.source().empty()) fmt::print("source: {}\n", s.source());
    fmt::print("{}", format_tile_set_text(s));
    if (!a.out.empty()) fmt::print("wrote {}\n", a.out);
  });
}

void add_show(CLI::App& ts, Context& ctx) {
  auto* cmd = ts.add_subcommand("show", "Show a tile set: kind, size, colours and tiles");
  auto a = std::make_shared<ShowArgs>();
  cmd->add_option("SET", a->set_name, "Built-in name (see `tileset list`) or tile-set file")->required();
  cmd->add_option("--out", a->out, "Draw the set: F.svg or F.png (Wang tiles as triangles, corner tiles as discs)");
  cmd->add_flag("--borders", a->borders, "Draw tile borders");
  cmd->add_option("--tile-size", a->tile_px, "Pixels per tile (default: chosen from the set size)")
      ->check(CLI::Range(1, 512));
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_show(*a, ctx); });
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
  add_show(*ts, ctx);
}

}  // namespace tilekit::cli
