#include "texture/texture_atlas.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/json_input.hpp"
#include "tilesets/tile_grid.hpp"
#include "tilesets/tile_set.hpp"
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

Ktx2Texture texture_atlas_ktx2(const TextureAtlas& a) {
  Ktx2Texture t;
  t.width = a.levels.at(0).width;
  t.height = a.levels[0].height;
  t.transfer = a.transfer;
  for (const Image& l : a.levels) {
    if (l.channels != 4) throw InputError("a KTX2 atlas needs RGBA levels");
    t.levels.push_back(l.pixels);
  }
  const nlohmann::json packing = {{"kind", std::string(kind_name(a.lookup.kind))},
                                  {"colors", a.lookup.colours},
                                  {"rows", a.lookup.rows},
                                  {"cols", a.lookup.cols},
                                  {"tile_px", a.tile_px},
                                  {"source", a.lookup.source}};
  t.key_values = {{"tilekit.atlas", packing.dump()}};
  return t;
}

AtlasFiles write_texture_atlas(const TextureAtlas& a, const std::string& png, const std::string& glsl_source,
                               const std::vector<std::pair<std::string, std::string>>& shaders) {
  const std::string stem = atlas_stem(png);
  AtlasFiles f;
  // All files or none: each is staged (written beside its target) and renamed into place only
  // when every one is complete, the manifest last, so an old atlas stays whole until then.
  AtomicFileSet files;
  nlohmann::json levels = nlohmann::json::array();
  for (std::size_t k = 0; k < a.levels.size(); ++k) {
    const std::string file = k == 0 ? stem + ".png" : fmt::format("{}.mip{}.png", stem, k);
    files.stage(file, encode_png(a.levels[k]));
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
  j["color_space"] = a.transfer == Ktx2Transfer::Srgb ? "srgb" : "linear";
  f.ktx2 = stem + ".ktx2";
  files.stage(f.ktx2, encode_ktx2(texture_atlas_ktx2(a)));
  f.manifest = stem + ".json";
  f.header = stem + ".h";
  f.glsl = stem + ".glsl";
  files.stage(f.header, lookup_c_header(a.lookup));
  files.stage(f.glsl, glsl_source);
  for (const auto& [suffix, text] : shaders) {
    f.shaders.push_back(stem + suffix);
    files.stage(f.shaders.back(), text);
  }
  files.stage(f.manifest, j.dump(1) + "\n");  // last: its presence means the atlas is complete
  files.commit();
  return f;
}

TextureAtlas read_texture_atlas(const std::string& path) {
  const std::string stem = atlas_stem(path), manifest = stem + ".json";
  std::error_code ec;
  if (!fs::exists(manifest, ec))
    throw InputError(fmt::format(
        "{}: no atlas manifest (write the atlas with `tilekit texture atlas DIR` and the output file {}.png)", manifest,
        stem));
  const nlohmann::json doc = read_json_file(manifest, "atlas manifest");
  const JsonIn j(doc, manifest);
  // The lookup is a tiling file (tilesets/tile_grid.hpp, checked there) that must be a packing
  // of the complete set (lookup_from_packing runs the independent validator).
  const JsonIn l = j.at("lookup");
  const Tiling t = tiling_from_json(l);
  check_complete_set_colours(t.colours, "the lookup's colors");
  if (auto kind = j.find("kind"); kind && kind->string() != kind_name(t.kind))
    throw kind->error(fmt::format("\"{}\", but the lookup is a {} packing", kind->string(), kind_name(t.kind)));
  TextureAtlas a;
  a.lookup = lookup_from_packing(t, l.string_or("source", "file"), l.string_or("how", manifest),
                                 l.boolean_or("closed_form", false));
  // Level 0 is cols * tile_px x rows * tile_px pixels, at most kMaxImagePixels: checked in 64 bits.
  const JsonIn px = j.at("tile_px");
  const std::int64_t tile_px = px.integer(1, kMaxImagePixels);
  if (tile_px * tile_px * a.lookup.rows * a.lookup.cols > kMaxImagePixels)
    throw px.error(fmt::format("{}-pixel tiles make a {}x{} atlas of more than {} pixels", tile_px, a.lookup.rows,
                               a.lookup.cols, kMaxImagePixels));
  a.tile_px = int(tile_px);
  a.tiles_dir = j.string_or("tiles_dir", "");
  if (auto space = j.find("color_space")) {
    const std::string name = space->string(16);
    if (name != "srgb" && name != "linear") throw space->error("expected \"srgb\" or \"linear\"");
    a.transfer = name == "srgb" ? Ktx2Transfer::Srgb : Ktx2Transfer::Linear;
  }
  const fs::path dir = fs::path(manifest).parent_path();
  const JsonIn levels = j.at("levels");
  const std::size_t n = levels.array(1, 64);
  for (std::size_t k = 0; k < n; ++k) {
    const std::string file = (dir / levels[k].at("file").string(4096)).string();
    const std::int64_t want_w = a.levels.empty() ? a.lookup.cols * tile_px : std::max(1, a.levels.back().width / 2);
    const std::int64_t want_h = a.levels.empty() ? a.lookup.rows * tile_px : std::max(1, a.levels.back().height / 2);
    Image img = read_image(file);
    if (img.width != want_w || img.height != want_h)
      throw InputError(fmt::format("{}: {}x{} pixels, but level {} of this atlas is {}x{}", file, img.width,
                                   img.height, a.levels.size(), want_w, want_h));
    a.levels.push_back(std::move(img));
  }
  if (a.levels.back().width != 1 || a.levels.back().height != 1)
    throw InputError(fmt::format("{}: the mip chain does not reach 1x1", manifest));
  return a;
}

TileSetManifest read_tile_set_manifest(const std::string& dir) {
  const std::string path = (fs::path(dir) / "tiles.json").string();
  std::error_code ec;
  if (!fs::exists(path, ec))
    throw InputError(fmt::format("{}: no tiles.json (make the tiles with `tilekit texture tiles`)", path));
  const nlohmann::json doc = read_json_file(path, "texture tile-set manifest");
  const JsonIn j(doc, path);
  TileSetManifest m;
  const JsonIn kind = j.at("kind");
  const std::string k = kind.string(16);
  if (k != "corner" && k != "wang") throw kind.error("expected \"corner\" or \"wang\"");
  m.kind = k == "wang" ? TileKind::Wang : TileKind::Corner;
  m.colours = std::uint32_t(j.at("colors").integer(1, kMaxCompleteSetColours));
  // The synthesis methods make one kind each (texture/tile_synthesis.hpp): a manifest whose kind
  // and method disagree was edited, and its tiles would be laid out by the wrong packing.
  if (auto method = j.find("method")) {
    const std::string name = method->string(64);
    const bool corner = name == "corner-strips" || name == "ng-corner";  // ng-corner, cohen-wang: older tilekits
    const bool wang = name == "wang-strips" || name == "cohen-wang";
    if ((corner && m.kind != TileKind::Corner) || (wang && m.kind != TileKind::Wang))
      throw method->error(
          fmt::format("\"{}\" makes {} tiles, but kind is \"{}\"", name, corner ? "corner" : "wang", k));
  }
  if (auto tiles = j.find("tiles")) {
    const std::uint64_t want = std::uint64_t(m.colours) * m.colours * m.colours * m.colours;
    if (tiles->unsigned_integer() != want)
      throw tiles->error(fmt::format("{} tiles, but the complete {} set over {} colours has {}",
                                     tiles->unsigned_integer(), k, m.colours, want));
  }
  return m;
}

}  // namespace tilekit
