#pragma once
// Terrain transition tiles: the complete corner set over C terrains (C^4 tiles; corner colour k is
// terrain k, each from its own texture), every tile joining the terrains of its four corners along
// minimum-error seams through the textures' content, never an alpha fade. Made from the corner
// texture tiles of corner_texture_tiles.cpp (Ng et al.; thesis sec. 5.3), one set per terrain:
//
//   1. Terrain k's set S_k is the complete corner set over the same C colours synthesised from
//      terrain k's texture alone. In S_k a texel within `margin` of a border depends only on that
//      border's two corner colours (TileGeometry), so S_k's tiles all join seamlessly.
//   2. Tile t takes every texel from S_label[t], where the label is a terrain among t's corner
//      colours: the terrain of the nearest corner, with the boundaries between two terrains moved
//      to minimum-error cuts (seam_cut.hpp, Efros & Freeman 2001) between the two terrains' tiles,
//      paying the step the cut shows across it and along it where it moves (as end cuts do).
//   3. Near a border the label depends only on that border's two colours: the cut across a border
//      whose corners differ is computed once per ordered colour pair and direction, on the 2 margin
//      rows either side of the border (from the tile whose opposite borders both carry that pair),
//      and every tile with that border continues it inwards. So the two tiles of a border agree
//      texel for texel within `margin` of it, in label and in content: tiles join seamlessly, and
//      a corner of colour k looks the same in every tile around it (S_k's corner square).
//
// Inside a tile whose four corners make two halves (a a / b b), one cut runs from border to border;
// otherwise each of the four half-lines from a border's middle to the tile's centre is a cut
// confined to its quarter of the tile (the triangle between the centre and that border), which
// it leaves only at the centre, so the four always meet there. In a tile of two terrains a graph
// cut (graph_cut.hpp, Kwatra et al. 2003) then moves the boundary freely within n/8 of the cuts and
// at least `margin` from every border, where a row-by-row path cannot go (round a stone).
#include <string>
#include <vector>

#include "texture/exemplar.hpp"
#include "texture/tile_synthesis.hpp"

namespace tilekit {

struct TerrainTexture {
  std::string name;  // the terrain's name ("grass"): Tiled's Wang colour name
  Exemplar exemplar;
};

inline constexpr std::uint32_t kMinTerrains = 2, kMaxTerrains = 6;

struct TerrainTileSet {
  TextureTileSet set;  // method "terrain-corner"; colours = terrains; sources as in TextureTileSet
  std::vector<std::string> names;
  std::vector<double> cut_error;       // per terrain: its own set's boundary-cut error (tile_synthesis.hpp)
  std::vector<double> texel_fraction;  // per terrain: the fraction of all texels it shows
  double seam_step = 0;                // mean step per channel between 4-neighbours of two terrains in a tile
  double terrain_step = 0;             // mean step per channel between 4-neighbours inside the terrains' tiles
};

// InputError (exit 2) for fewer than kMinTerrains or more than kMaxTerrains terrains, two with one
// name, a name that is empty or holds a character other than letters, digits, '-', '_' and '.',
// a kind other than corner, or options one terrain's texture cannot serve
// (check_synthesis_options).
void check_terrain_options(const std::vector<TerrainTexture>& terrains, const SynthesisOptions& o);

// How the boundary between two terrains runs inside a tile: on the tile's middle lines (the
// baseline), along minimum-error cuts (seam_cut.hpp), or those cuts refined, in tiles of two
// terrains, by a graph cut (graph_cut.hpp) in a band of n/8 around them, free to leave the
// row-by-row path and go round a stone.
enum class TerrainSeams { Straight, Cut, GraphCut };

// o.colours is set to the number of terrains; o.kind must be corner. Terrain k's set is seeded by
// derive_seed(o.seed, k), so the result is the same bytes on any thread count.
TerrainTileSet synthesize_terrain_tiles(const std::vector<TerrainTexture>& terrains, SynthesisOptions o,
                                        TerrainSeams seams = TerrainSeams::GraphCut);

}  // namespace tilekit
