#pragma once
// A map painted in Tiled (.tmx, Tiled 1.x) read as the fixed cells of a fill: the first tile
// layer's gids (0: an empty cell, to fill) and the tilesets they index. Tilesets are external
// files (`<tileset firstgid source>`, resolved next to the map); their text is read here so
// that the caller can map each gid to a tile of its own set (tilemap/fill_job.hpp).
// Refused with an InputError (exit 2) naming the file and the problem: not a Tiled map or larger
// than 64 MiB, an infinite map or one that is not orthogonal, no tile layer, a layer of another
// size than the map, data in base64 or compressed (save the map with Tile Layer Format CSV or
// XML), a gid with flip bits, an embedded tileset, a tileset file that cannot be read.
#include <cstdint>
#include <string>
#include <vector>

namespace tilekit::tilemap {

struct TmxTilesetRef {
  std::uint32_t firstgid = 1;
  std::string source;  // as the map names it (relative to the map)
  std::string path;    // the file: source resolved against the map's folder
  std::string text;    // the .tsx text
  int tilecount = 0;   // the tileset's tilecount attribute
  std::string name;    // its name attribute
};

struct PaintedMap {
  std::string path;
  int width = 0, height = 0;            // cells
  int tile_width = 0, tile_height = 0;  // pixels
  std::vector<std::uint32_t> gids;      // row by row; 0 empty
  std::vector<TmxTilesetRef> tilesets;  // by firstgid, increasing
  std::string layer;                    // the name of the layer read
};

PaintedMap read_painted_map(const std::string& path);
// The same from the map's text; `path` names it in errors and is the folder tilesets are read from.
PaintedMap parse_painted_map(const std::string& text, const std::string& path);

// The tileset a gid falls in (the last with firstgid <= gid), or -1 when gid is 0 or below every
// firstgid.
int tileset_of_gid(const PaintedMap& m, std::uint32_t gid);

}  // namespace tilekit::tilemap
