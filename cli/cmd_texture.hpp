#pragma once
// The `tilekit texture` commands that show a texture, render (cmd_texture_render.cpp) and preview
// (cmd_texture_preview.cpp), and what they share: where the texture comes from (an atlas for
// tiles, an exemplar for the hex and hpn baselines) and the view (cmd_texture_source.cpp). tiles
// and atlas are in cmd_texture.cpp.
#include <CLI/CLI.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "cli/command.hpp"
#include "render/cpu_renderer.hpp"
#include "render/exemplar_surface.hpp"

namespace tilekit::cli {

void add_texture_render(CLI::App& texture, Context& ctx);
void add_texture_preview(CLI::App& texture, Context& ctx);
void add_texture_analyze(CLI::App& texture, Context& ctx);  // cmd_texture_analyze.cpp
void add_texture_terrain(CLI::App& texture, Context& ctx);  // cmd_texture_terrain.cpp

struct SourceArgs {
  std::string method = "tiles", atlas, exemplar, hash = "long-period";
  std::uint64_t seed = 1;
  float cell_px = 0;
  int aniso = 16;
  std::string filter = "taps";
};
// --method, --atlas, --exemplar, --cell-px, --hash, --seed, --aniso.
void add_source_options(CLI::App* cmd, SourceArgs& a);

// The loaded atlas and exemplar surface, and the render source and options pointing at them.
struct LoadedSource {
  std::optional<TextureAtlas> atlas;
  std::optional<ExemplarSurface> exemplar;
  RenderSource source;
  RenderOptions options;
};
// InputError (exit 2) for an unknown method or hash, a method without what it samples (tiles
// without --atlas, hex or hpn without --exemplar), or an unreadable atlas or exemplar.
std::unique_ptr<LoadedSource> load_source(const SourceArgs& a);
// method, hash, seed, aniso, kind and colours (atlas), exemplar and cell_px, memory_bytes.
nlohmann::json source_json(const LoadedSource& s);

// --size WxH, --scale, --origin U,V and --tilt as a view (InputError naming the flag).
View parse_view(const std::string& size, double scale, const std::string& origin, double tilt);

}  // namespace tilekit::cli
