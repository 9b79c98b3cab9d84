#pragma once
// What `tilekit fill` does, as a library: a tile set with adjacency rules and a map size in, a
// filled map out (solver/fill_search.hpp: a model of the one engine), checked by a validator
// that shares no code with the search, written as a picture, a Tiled map and JSON.
//
// The tile set is one of
//   - a Tilekit tile set (a name such as complete-corner-3 or compact-wang-3, or a tile-set file;
//     tilesets/tile_set_io.hpp): Wang tiles meet where edges match, corner tiles where the two
//     shared corners match; any subset of a complete set (incomplete sets are fine);
//   - a Tiled tileset (.tsx) with a Wang set of type corner or edge (tilemap/tsx_reader.hpp);
//   - a WFC simple tiled model (.xml, tilemap/wfc_tileset.hpp), optionally one of its subsets;
//   - "blob-47", the 8-neighbour blob set (tilemap/blob_set.hpp).
// Fixed cells come from a cells file: one line per map row, one token per cell, "." a free cell,
// else the tile's number in the fill set or, for a WFC set, its name ("corner" is "corner 0",
// "corner 1" is written "corner:1"); blank lines and lines starting with '#' are skipped.
// Or from a map painted in Tiled (a .tmx, tilemap/tmx_reader.hpp; its size is the map's): empty
// cells are free, a painted cell's gid is its tileset's tile, matched to the fill set by its
// wangid (Tilekit and Tiled sets: a sheet Tilekit wrote or the user's own Wang set) or by tile id
// (WFC sets: the sheet `--tiled` writes). The filled map is then written as a .tmx over the painted
// map's own tilesets (painted cells keep their gids).
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "solver/fill_search.hpp"

namespace tilekit::tilemap {

struct FillJobRequest {
  std::string set;      // a tile set name or file, a .tsx or a WFC .xml
  std::string subset;   // WFC only: a subset of the XML ("" every tile)
  std::string wangset;  // .tsx only: the Wang set's name ("" the first)
  int width = 0, height = 0;  // 0x0 with a painted .tmx: the map's size
  bool torus = false;
  std::string cells;                                  // fixed cells file or painted .tmx ("" none)
  std::vector<std::pair<std::string, double>> weights;  // tile (number or WFC name) -> weight
  int block = 0;
  std::uint64_t dives = 64;
  bool cover = false;  // every tile at least once (FillMapRequest::cover)
  FillOrder order = FillOrder::Auto;  // the fill model's cell order
  bool sat = false;    // search with cadical (solver/fill_sat.hpp) instead of the fill model
  std::string out_cnf;  // "" or: write the request's CNF here and search nothing
  RunSettings run;
  std::string out_png, out_json, out_tiled;  // "" = not written; out_tiled a folder
  int tile_px = 16;                          // pictures of Tilekit/Tiled sets (WFC tiles keep theirs)
};

struct FillJobOutcome {
  FillMapOutcome fill;
  std::string source;  // "tileset", "tiled" or "wfc"
  std::vector<std::string> names;
  std::vector<double> weights;
  std::vector<std::uint64_t> counts;  // found: cells per tile
  bool valid = false;                 // found and passed the independent validator
  std::size_t fixed = 0;              // fixed cells
  int rows = 0, cols = 0;             // the map's size
  std::string png, json, tmx, tsx;
  std::string cnf;  // the CNF written (no search made)
  std::uint64_t cnf_variables = 0, cnf_clauses = 0;
};

FillJobOutcome run_fill(const FillJobRequest& req);

// The independent check of a WFC fill: every pair of neighbouring cells (wrapping on a torus) is
// one of `pairs` (tilemap/wfc_tileset.hpp's list, not the search's bitsets). Returns the first
// violation as text, or "".
std::string check_pair_fill(const std::vector<int>& map, int rows, int cols, bool torus,
                            const std::vector<std::array<int, 3>>& pairs, int tiles);

}  // namespace tilekit::tilemap
