#pragma once
// What `tilekit tiled tileset|map|import` do, as a library: requests in, files and outcomes out.
//   tileset: NAME.tsx and NAME.png, the packed sheet of the complete corner or Wang set over C
//            colours (built-in pictures of atlas/render.hpp, or tile images a user drew);
//   map:     the tileset and NAME-map.tmx, W x H cells of the direct stochastic tiling (the
//            tiling of `tilekit tile --algo direct`, tiling/tiling_algorithms.hpp), validated;
//   import:  a Tiled Wang set (.tsx) read back as a Tilekit tile set (tilemap/tsx_reader.hpp).
// Every input is checked before anything is written; every file is written atomically.
#include <cstdint>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "tilesets/tile_grid.hpp"

namespace tilekit::tilemap {

struct TilesetRequest {
  TileKind kind = TileKind::Corner;
  std::uint32_t colours = 2;
  std::string tiles_dir;  // "": built-in coloured tiles; else images named by tile index
  int tile_px = 32;       // built-in tiles only (drawn tiles keep their size)
  std::string name;       // "": "corner-C" or "wang-C"
  std::string out_dir;    // created if missing

  // The Wang colours' names by colour (empty: built-in or "colour k") and their display colours
  // (empty: the pictures' palette).
  std::vector<std::string> colour_names;
  std::vector<Rgb> colour_rgb;
};

struct TilesetOutcome {
  std::string name, tsx_path, png_path, how;
  int rows = 0, cols = 0, tile_px = 0;
  std::size_t tiles = 0;
};

struct MapRequest {
  TilesetRequest tileset;
  int width = 0, height = 0;  // in tiles
  std::uint64_t seed = 1;
};

struct MapOutcome {
  TilesetOutcome tileset;
  std::string tmx_path;
  Tiling map;  // the cells written, validated
};

// The tileset name's file stem: letters, digits, '.', '-' and '_' kept, anything else '_'.
std::string file_stem(const std::string& name);

TilesetOutcome write_tiled_tileset(const TilesetRequest& req);
// InputError for a size outside tiling/tiling_algorithms.hpp's check_tiling_size.
MapOutcome write_tiled_map(const MapRequest& req);
// The map's cells alone (what write_tiled_map writes): the direct stochastic tiling of the
// complete set, validated.
Tiling direct_map(TileKind kind, std::uint32_t colours, int width, int height, std::uint64_t seed);

}  // namespace tilekit::tilemap
