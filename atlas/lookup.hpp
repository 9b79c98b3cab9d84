#pragma once
// Atlas lookup (thesis 5.4): a packing of the complete Wang or corner set over C colours laid
// out as a C^2 x C^2 texture atlas, with its inverse (tile -> atlas cell), exported as JSON, a
// C header or a GLSL snippet that maps the infinite virtual texture to the atlas (direct
// stochastic tiling, thesis 3.3, then the packing lookup).
#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <utility>
#include <vector>

#include "tilesets/tile_grid.hpp"

namespace tilekit {

struct AtlasLookup {
  TileKind kind = TileKind::Corner;
  std::uint32_t colours = 0;
  int rows = 0, cols = 0;
  std::vector<TileIndex> cells;                 // atlas cell (row-major) -> tile index
  std::vector<std::pair<int, int>> positions;   // tile index -> (row, col)
  std::string source;                           // "db" | "construct"
  std::string how;                              // construction name, or "solution N in FILE"
  bool closed_form = false;                     // positions have a closed form (GLSL uses it)
  std::int64_t solution_id = 0;                 // for source "db"
};

struct LookupOptions {
  std::string db_path;  // "" = no database
};

// Database hit first (a validated stored packing, re-checked by the validator), then a
// construction. Throws NotFound (exit 1) naming the available colour counts and the search
// command when neither has one, InputError for C outside 1..kMaxCompleteSetColours (tilesets/tile_set.hpp).
AtlasLookup atlas_lookup(TileKind kind, std::uint32_t colours, const LookupOptions& options);

// From a packing. Throws InputError unless it is a C^2 x C^2 torus holding every tile once and,
// with `run_validator`, the independent validator accepts it as a packing.
AtlasLookup lookup_from_packing(const Tiling& packing, std::string source, std::string how, bool closed_form,
                                bool run_validator = true);

nlohmann::json lookup_json(const AtlasLookup& a);
// The same JSON object as text, written directly (large atlases print in milliseconds).
std::string lookup_json_text(const AtlasLookup& a);
std::string lookup_c_header(const AtlasLookup& a);
// `seed` picks the permutation table of the direct stochastic tiling hash (thesis eq. 3.3).
std::string lookup_glsl(const AtlasLookup& a, std::uint64_t seed);

// The GLSL function `ivec2 tk_tile_position(int tile)` (row, col of a tile in the atlas): the closed
// form where the packing has one, else a table. Expects TK_COLORS and TK_COLS to be defined.
std::string lookup_glsl_position(const AtlasLookup& a);

// The permutation table of size 256 for the hash (thesis 3.4.1), from a seed.
std::vector<int> hash_permutation(std::uint64_t seed);

// CPU reference of the GLSL snippet: the tile that the direct stochastic tiling puts at tile
// coordinates (x, y) of the virtual texture (thesis 3.3.1 for corner tiles, 3.3.2.1 for Wang
// tiles; y grows upwards, the tile's SW corner is lattice point (x, y)).
TileIndex virtual_tile(const AtlasLookup& a, const std::vector<int>& perm, std::int64_t x, std::int64_t y);
// Atlas coordinate in [0,1)^2 (u right, v down: image rows, row 0 at the top) of the virtual
// texture coordinate (u, v) in tile units (v upwards).
std::pair<double, double> virtual_to_atlas(const AtlasLookup& a, const std::vector<int>& perm, double u, double v);

}  // namespace tilekit
