#include "texture/texture_atlas.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "texture/mipmap.hpp"

namespace tilekit {

namespace fs = std::filesystem;

namespace {

TextureAtlas from_level0(const AtlasLookup& lookup, Image level0, int tile_px) {
  TextureAtlas a;
  a.lookup = lookup;
  a.tile_px = tile_px;
  a.levels = mip_chain(level0, MipEdge::Wrap);  // the atlas is a torus: filtering wraps around
  return a;
}

}  // namespace

TextureAtlas build_texture_atlas(const AtlasLookup& lookup, const std::vector<Image>& tiles) {
  if (tiles.size() != lookup.cells.size())
    throw InputError(fmt::format("{} tile images for a set of {} tiles", tiles.size(), lookup.cells.size()));
  const int n = tiles.empty() ? 0 : tiles[0].width;
  for (const Image& t : tiles)
    if (t.width != n || t.height != n || n < 1) throw InputError("tile images must all be square and of one size");
  Image level0(lookup.cols * n, lookup.rows * n, Rgb{0, 0, 0});
  for (int r = 0; r < lookup.rows; ++r)
    for (int c = 0; c < lookup.cols; ++c) {
      const Image& t = tiles[lookup.cells[std::size_t(r) * std::size_t(lookup.cols) + std::size_t(c)]];
      for (int y = 0; y < n; ++y) std::copy_n(t.at(0, y), std::size_t(n) * 4, level0.at(c * n, r * n + y));
    }
  return from_level0(lookup, std::move(level0), n);
}

TextureAtlas build_texture_atlas(const AtlasLookup& lookup, const std::string& tiles_dir) {
  Image level0 = atlas_from_tile_images(lookup, tiles_dir);
  TextureAtlas a = from_level0(lookup, std::move(level0), 0);
  a.tile_px = a.levels[0].width / lookup.cols;
  a.tiles_dir = tiles_dir;
  return a;
}

std::string atlas_stem(const std::string& path) {
  fs::path p(path);
  if (p.extension() == ".png" || p.extension() == ".json") p.replace_extension();
  return p.string();
}

AtlasFiles write_texture_atlas(const TextureAtlas& a, const std::string& png, const std::string& glsl_source) {
  const std::string stem = atlas_stem(png);
  AtlasFiles f;
  nlohmann::json levels = nlohmann::json::array();
  for (std::size_t k = 0; k < a.levels.size(); ++k) {
    const std::string file = k == 0 ? stem + ".png" : fmt::format("{}.mip{}.png", stem, k);
    write_png(file, a.levels[k]);
    f.levels.push_back(file);
    levels.push_back(
        {{"file", fs::path(file).filename().string()}, {"width", a.levels[k].width}, {"height", a.levels[k].height}});
  }
  nlohmann::json j = {{"tilekit", "texture atlas"},
                      {"kind", std::string(kind_name(a.lookup.kind))},
                      {"colors", a.lookup.colours},
                      {"tile_px", a.tile_px},
                      {"rows", a.lookup.rows},
                      {"cols", a.lookup.cols},
                      {"levels", levels},
                      {"tiles_dir", a.tiles_dir},
                      {"lookup", lookup_json(a.lookup)}};
  f.manifest = stem + ".json";
  f.header = stem + ".h";
  f.glsl = stem + ".glsl";
  write_file_atomic(f.header, lookup_c_header(a.lookup));
  write_file_atomic(f.glsl, glsl_source);
  write_file_atomic(f.manifest, j.dump(1) + "\n");  // last: its presence means the atlas is complete
  return f;
}

TextureAtlas read_texture_atlas(const std::string& path) {
  const std::string stem = atlas_stem(path), manifest = stem + ".json";
  std::ifstream in(manifest);
  if (!in)
    throw InputError(fmt::format(
        "{}: no atlas manifest (write the atlas with `tilekit texture atlas DIR --out {}.png`)", manifest, stem));
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text.str());
  } catch (const std::exception& e) {
    throw InputError(fmt::format("{}: not JSON ({})", manifest, e.what()));
  }
  try {
    const nlohmann::json& l = j.at("lookup");
    Tiling t(l.at("kind").get<std::string>() == "wang" ? TileKind::Wang : TileKind::Corner,
             l.at("colors").get<std::uint32_t>(), l.at("rows").get<int>(), l.at("cols").get<int>(), true);
    std::size_t i = 0;
    for (const auto& row : l.at("cells"))
      for (const auto& cell : row) {
        if (i >= t.cells.size()) throw InputError(fmt::format("{}: more cells than rows x cols", manifest));
        t.cells[i++] = cell.get<TileIndex>();
      }
    if (i != t.cells.size()) throw InputError(fmt::format("{}: fewer cells than rows x cols", manifest));
    TextureAtlas a;
    a.lookup =
        lookup_from_packing(t, l.value("source", "file"), l.value("how", manifest), l.value("closed_form", false));
    a.tile_px = j.at("tile_px").get<int>();
    a.tiles_dir = j.value("tiles_dir", "");
    const fs::path dir = fs::path(manifest).parent_path();
    for (const auto& level : j.at("levels")) {
      const std::string file = (dir / level.at("file").get<std::string>()).string();
      Image img = read_image(file);
      const int w = img.width, h = img.height;
      const int want_w = a.levels.empty() ? a.lookup.cols * a.tile_px : std::max(1, a.levels.back().width / 2);
      const int want_h = a.levels.empty() ? a.lookup.rows * a.tile_px : std::max(1, a.levels.back().height / 2);
      if (w != want_w || h != want_h)
        throw InputError(fmt::format("{}: {}x{} pixels, but level {} of this atlas is {}x{}", file, w, h,
                                     a.levels.size(), want_w, want_h));
      a.levels.push_back(std::move(img));
    }
    if (a.levels.empty() || a.levels.back().width != 1 || a.levels.back().height != 1)
      throw InputError(fmt::format("{}: the mip chain does not reach 1x1", manifest));
    return a;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: not an atlas manifest ({})", manifest, e.what()));
  }
}

}  // namespace tilekit
