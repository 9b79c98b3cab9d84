#include "tilemap/tiled_files.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "atlas/atlas_image.hpp"
#include "atlas/render.hpp"
#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "tilemap/tiled_tileset.hpp"
#include "tilesets/tile_set.hpp"
#include "tilesets/validator.hpp"
#include "tiling/tiling_algorithms.hpp"

namespace tilekit::tilemap {

std::string file_stem(const std::string& name) {
  std::string s;
  for (const char ch : name) {
    const bool keep = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '.' ||
                      ch == '-' || ch == '_';
    s += keep ? ch : '_';
  }
  if (s.empty() || s.front() == '.') s.insert(0, "tileset");
  return s.substr(0, 128);
}

namespace {

constexpr int kMaxSheetSide = 8192;  // atlas/render.hpp's largest picture side

// Everything a tileset request makes, in memory, before any file is written.
struct TilesetFiles {
  TiledSheet sheet;
  std::string png, tsx;
  TilesetOutcome outcome;
};

void make_out_dir(const std::string& dir) {
  if (dir.empty()) throw RequestError("out", "`out`: a folder is needed");
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw InputError(fmt::format("{}: cannot make the output folder ({})", dir, ec ? ec.message() : "not a folder"));
}

TilesetFiles make_tileset(const TilesetRequest& req) {
  TilesetFiles f{sheet_layout(req.kind, req.colours), {}, {}, {}};
  TilesetOutcome& o = f.outcome;
  o.name = req.name.empty() ? fmt::format("{}-{}", kind_name(req.kind), req.colours) : req.name;
  const std::string stem = file_stem(o.name);
  o.tsx_path = (std::filesystem::path(req.out_dir) / (stem + ".tsx")).string();
  o.png_path = (std::filesystem::path(req.out_dir) / (stem + ".png")).string();
  o.how = f.sheet.how;
  o.rows = f.sheet.packing.rows, o.cols = f.sheet.packing.cols;
  o.tiles = f.sheet.packing.cells.size();
  if (req.tiles_dir.empty()) {
    if (req.tile_px < 2 || req.tile_px > 512)
      throw RequestError("tile_px", fmt::format("`tile_px` must be 2..512, got {}", req.tile_px));
    if (std::int64_t(f.sheet.packing.cols) * req.tile_px > kMaxSheetSide)
      throw RequestError(
          "tile_px", fmt::format("a sheet of {}x{} tiles of {} pixels is more than {} pixels wide; use `tile_px` {} "
                                 "or less",
                      o.cols, o.rows, req.tile_px, kMaxSheetSide, kMaxSheetSide / o.cols));
    o.tile_px = req.tile_px;
    f.png = atlas::to_png(atlas::draw_tiling(f.sheet.packing, {req.tile_px, false}));
  } else {
    const AtlasLookup lookup = lookup_from_packing(f.sheet.packing, "construct", f.sheet.how, f.sheet.closed_form);
    const Image img = atlas_from_tile_images(lookup, req.tiles_dir);
    o.tile_px = img.width / f.sheet.packing.cols;
    f.png = encode_png(img);
  }
  if (!req.colour_names.empty() && req.colour_names.size() != req.colours)
    throw RequestError("colour_names",
                       fmt::format("{} colour names for {} colours", req.colour_names.size(), req.colours));
  if (!req.colour_rgb.empty() && req.colour_rgb.size() != req.colours)
    throw RequestError("colour_rgb",
                       fmt::format("{} display colours for {} colours", req.colour_rgb.size(), req.colours));
  f.tsx =
      tsx_text(f.sheet, {o.name, stem + ".png", o.tile_px, req.tiles_dir.empty(), req.colour_names, req.colour_rgb});
  return f;
}

void write_tileset_files(const TilesetFiles& f) {
  write_file_atomic(f.outcome.png_path, f.png);
  write_file_atomic(f.outcome.tsx_path, f.tsx);
}

}  // namespace

TilesetOutcome write_tiled_tileset(const TilesetRequest& req) {
  const TilesetFiles f = make_tileset(req);
  make_out_dir(req.out_dir);
  write_tileset_files(f);
  return f.outcome;
}

Tiling direct_map(TileKind kind, std::uint32_t colours, int width, int height, std::uint64_t seed) {
  const TileSet set = kind == TileKind::Corner ? complete_corner_set(colours) : complete_wang_set(colours, colours);
  TilingRequest req;
  req.algo = TilingAlgo::Direct;
  req.rows = height, req.cols = width, req.seed = seed;
  Tiling map = generate_tiling(set, req);
  const ValidationReport rep = validate(map, &set);
  if (!rep.valid)
    throw std::logic_error(fmt::format("the direct tiling is not valid: {}", rep.errors.empty() ? "" : rep.errors[0]));
  return map;
}

MapOutcome write_tiled_map(const MapRequest& req) {
  check_tiling_size(req.height, req.width);
  const TilesetFiles f = make_tileset(req.tileset);
  MapOutcome o{f.outcome, {}, direct_map(req.tileset.kind, req.tileset.colours, req.width, req.height, req.seed)};
  const std::string stem = file_stem(o.tileset.name);
  o.tmx_path = (std::filesystem::path(req.tileset.out_dir) / (stem + "-map.tmx")).string();
  const std::string tmx = tmx_text(f.sheet, o.map, stem + ".tsx", o.tileset.tile_px);
  make_out_dir(req.tileset.out_dir);
  write_tileset_files(f);
  write_file_atomic(o.tmx_path, tmx);
  return o;
}

}  // namespace tilekit::tilemap
