#include "texture/texture_atlas.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/json_input.hpp"
#include "texture/mipmap.hpp"
#include "tilesets/tile_grid.hpp"
#include "tilesets/tile_set.hpp"

namespace tilekit {

namespace fs = std::filesystem;

namespace {

TextureAtlas from_level0(const AtlasLookup& lookup, Image level0, int tile_px, ColourSpace space) {
  if (level0.is_float() && space == ColourSpace::Srgb)
    throw InputError("float tiles hold linear data (OpenEXR): their atlas is linear or normal, not sRGB colour");
  TextureAtlas a;
  a.lookup = lookup;
  a.tile_px = tile_px;
  a.colour_space = space;
  a.levels = mip_chain(level0, MipEdge::Wrap, space);  // the atlas is a torus: filtering wraps around
  return a;
}

// 2^round(log2 n): the power of two nearest n on a log scale.
int nearest_power_of_two(std::int64_t n) {
  int k = 0;
  while ((std::int64_t(1) << (k + 1)) <= n) ++k;  // 2^k <= n < 2^(k+1)
  const double low = double(std::int64_t(1) << k);
  return n * n >= std::int64_t(low * low * 2) ? int(low * 2) : int(low);  // n >= 2^k sqrt 2: up
}

// Area-weighted resampling of one axis on a torus: output texel i covers input [i s, (i + 1) s),
// s = in / out, each input texel weighted by its overlap.
Image resample_axis(const Image& in, int out_size, bool along_x) {
  const int n = along_x ? in.width : in.height, other = along_x ? in.height : in.width;
  Image out(along_x ? out_size : in.width, along_x ? in.height : out_size,
            std::vector<std::uint8_t>(std::size_t(along_x ? out_size : in.width) *
                                      std::size_t(along_x ? in.height : out_size) * 4));
  const double s = double(n) / out_size;
  for (int i = 0; i < out_size; ++i) {
    const double a = i * s, b = (i + 1) * s;
    std::vector<std::pair<int, double>> taps;
    for (int k = int(std::floor(a)); double(k) < b; ++k)
      taps.emplace_back(((k % n) + n) % n, (std::min(b, double(k + 1)) - std::max(a, double(k))) / s);
    for (int j = 0; j < other; ++j) {
      double sum[4] = {0, 0, 0, 0};
      for (const auto& [k, w] : taps) {
        const std::uint8_t* p = along_x ? in.at(k, j) : in.at(j, k);
        for (int c = 0; c < 4; ++c) sum[c] += w * p[c];
      }
      std::uint8_t* q = along_x ? out.at(i, j) : out.at(j, i);
      for (int c = 0; c < 4; ++c) q[c] = std::uint8_t(std::clamp(std::lround(sum[c]), 0l, 255l));
    }
  }
  return out;
}

}  // namespace

TextureAtlas resample_to_power_of_two(const TextureAtlas& a) {
  const Image& l0 = a.levels.at(0);
  const int w = nearest_power_of_two(l0.width), h = nearest_power_of_two(l0.height);
  if (w == l0.width && h == l0.height) return a;
  // resample_axis averages 8-bit values as stored (for sRGB colour, in the sRGB encoding).
  if (l0.depth != 8)
    throw InputError(fmt::format("a power-of-two atlas is made from 8-bit tiles only; these are {}",
                                 l0.is_float() ? "float" : "16-bit"));
  TextureAtlas r = a;
  r.levels = mip_chain(resample_axis(resample_axis(l0, w, true), h, false), MipEdge::Wrap, a.colour_space);
  return r;
}

TextureAtlas build_texture_atlas(const AtlasLookup& lookup, const std::vector<Image>& tiles, ColourSpace space) {
  if (tiles.size() != lookup.cells.size())
    throw InputError(fmt::format("{} tile images for a set of {} tiles", tiles.size(), lookup.cells.size()));
  const int n = tiles.empty() ? 0 : tiles[0].width;
  for (const Image& t : tiles)
    if (t.width != n || t.height != n || n < 1) throw InputError("tile images must all be square and of one size");
  const int depth = tiles.empty() ? 8 : tiles[0].depth;
  for (const Image& t : tiles)
    if (t.depth != depth || t.channels != 4) throw InputError("tile images must all be RGBA of one depth");
  Image level0 = Image(lookup.cols * n, lookup.rows * n, Rgb{0, 0, 0}).to_depth(depth);
  const std::size_t row_bytes = std::size_t(n) * std::size_t(level0.texel_bytes());
  for (int r = 0; r < lookup.rows; ++r)
    for (int c = 0; c < lookup.cols; ++c) {
      const Image& t = tiles[lookup.cells[std::size_t(r) * std::size_t(lookup.cols) + std::size_t(c)]];
      for (int y = 0; y < n; ++y) std::copy_n(t.at(0, y), row_bytes, level0.at(c * n, r * n + y));
    }
  return from_level0(lookup, std::move(level0), n, space);
}

TextureAtlas build_texture_atlas(const AtlasLookup& lookup, const std::string& tiles_dir, ColourSpace space) {
  Image level0 = atlas_from_tile_images(lookup, tiles_dir);
  TextureAtlas a = from_level0(lookup, std::move(level0), 0, space);
  a.tile_px = a.levels[0].width / lookup.cols;
  a.tiles_dir = tiles_dir;
  return a;
}

std::string atlas_stem(const std::string& path) {
  fs::path p(path);
  if (p.extension() == ".png" || p.extension() == ".json" || p.extension() == ".exr") p.replace_extension();
  return p.string();
}

Ktx2Texture texture_atlas_ktx2(const TextureAtlas& a) {
  Ktx2Texture t;
  t.width = a.levels.at(0).width;
  t.height = a.levels[0].height;
  // sRGB colour is RGBA8 sRGB (Vulkan has no 16-bit sRGB format: 16-bit colour levels are
  // rounded to 8 bits here); data and normals are RGBA8 or RGBA16 UNORM at the atlas's depth, or
  // RGBA32 SFLOAT for float.
  t.transfer = a.colour_space == ColourSpace::Srgb ? Ktx2Transfer::Srgb : Ktx2Transfer::Linear;
  const int depth = t.transfer == Ktx2Transfer::Srgb ? 8 : a.levels[0].depth;
  t.bytes_per_channel = depth / 8;
  for (const Image& l : a.levels) {
    if (l.channels != 4) throw InputError("a KTX2 atlas needs RGBA levels");
    t.levels.push_back(l.depth == depth ? l.pixels : l.to_depth(depth).pixels);
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
    const char* ext = image_extension(a.levels[k]);  // float levels as OpenEXR
    const std::string file = k == 0 ? stem + ext : fmt::format("{}.mip{}{}", stem, k, ext);
    files.stage(file, encode_image(a.levels[k]));
    f.levels.push_back(file);
    levels.push_back(
        {{"file", fs::path(file).filename().string()}, {"width", a.levels[k].width}, {"height", a.levels[k].height}});
  }
  nlohmann::json j = {{"tilekit", "texture atlas"},
                      {"kind", std::string(kind_name(a.lookup.kind))},
                      {"colors", a.lookup.colours},
                      {"tile_px", a.tile_px},
                      {"colour_space", std::string(colour_space_name(a.colour_space))},
                      {"bits", a.levels.empty() ? 8 : a.levels[0].depth},
                      {"format", !a.levels.empty() && a.levels[0].is_float() ? "exr float" : "png unorm"},
                      {"rows", a.lookup.rows},
                      {"cols", a.lookup.cols},
                      {"levels", levels},
                      {"tiles_dir", a.tiles_dir},
                      {"lookup", lookup_json(a.lookup)}};
  // level 0 resampled to a power of two (resample_to_power_of_two): its size, texels a tile
  j["power_of_two"] = a.levels[0].width != a.lookup.cols * a.tile_px || a.levels[0].height != a.lookup.rows * a.tile_px;
  j["texels_per_tile"] = atlas_texels_per_tile(a);
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
  if (auto space = j.find("colour_space"))
    if (!parse_colour_space(space->string(16), a.colour_space))
      throw space->error("expected \"srgb\", \"linear\" or \"normal\"");
  const fs::path dir = fs::path(manifest).parent_path();
  const bool power_of_two = j.boolean_or("power_of_two", false);
  const JsonIn levels = j.at("levels");
  const std::size_t n = levels.array(1, 64);
  for (std::size_t k = 0; k < n; ++k) {
    const std::string file = (dir / levels[k].at("file").string(4096)).string();
    const std::int64_t w0 = a.lookup.cols * tile_px, h0 = a.lookup.rows * tile_px;
    const std::int64_t want_w =
        a.levels.empty() ? (power_of_two ? nearest_power_of_two(w0) : w0) : std::max(1, a.levels.back().width / 2);
    const std::int64_t want_h =
        a.levels.empty() ? (power_of_two ? nearest_power_of_two(h0) : h0) : std::max(1, a.levels.back().height / 2);
    Image img = read_image(file, 4, true);
    if (!a.levels.empty() && img.depth != a.levels[0].depth) img = img.to_depth(a.levels[0].depth);
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
  if (auto space = j.find("colour_space"))
    if (!parse_colour_space(space->string(16), m.colour_space))
      throw space->error("expected \"srgb\", \"linear\" or \"normal\"");
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
