#pragma once
// Poisson disk tile sets (thesis ch. 4): a point set per tile such that every tiling the
// direct stochastic tiling algorithms make is one Poisson disk distribution, no two points
// closer than 2r, across tile borders included.
//
// Three constructions share one geometry (thesis Fig. 4.3(b)): around every lattice point a
// corner region (a square of half-side c = (1 + sqrt 2) r, so that edge regions meeting at a
// corner are 2r apart), along every edge an edge region 2r wide between two corner regions,
// and the interior of each tile. Points are made region by region with the constrained
// sampler (points/sampler.hpp), each region with the regions it touches fixed:
//
//  - corner-based (thesis sec. 4.5): C corner regions, one per lattice colour; C^2 E horizontal
//    and C^2 E vertical edge regions, one per pair of end colours and edge colour; C^4 E^4
//    interiors. Every lattice point has one of C colours and every lattice edge one of E edge
//    colours (E = 1 is the thesis' set; E > 1 follows its sec. 6.11: "more variation in edge
//    tiles will produce a better power spectrum"). The tiles are the complete corner set over C
//    colours (thesis eq. 2.5) times the complete Wang set over E colours (eq. 2.2).
//  - edge-based (thesis sec. 4.3, Lagae and Dutre 2005): C edge regions per direction, one per
//    Wang edge colour; C^4 corner regions, one per colour combination of the four edges at a
//    lattice point; C^12 interiors, one per combination of a tile's 4 edges and the 8 further
//    edges at its corners (the corner problem, thesis sec. 2.6).
//  - dual (Li, Lo, Leung and Fu, planar variant): the corner-based construction with rotatable
//    parts. A lattice point carries a colour and one of 4 orientations (4C lattice states);
//    corner regions are octagons of side 2r (C of them, turned by the orientation), edge
//    regions are shared up to a half turn (8C^2 + 2C of them) and interiors up to quarter turns
//    (64C^4 + 4C^2 + 2C); self-symmetric ones hold symmetric point sets. The tiles are the
//    complete corner set over 4C lattice states.
//
// Every tile holds exactly N points: an interior gets N minus the points its corner and edge
// regions put inside the tile (thesis sec. 4.5: "brings the number of points inside the tile
// to N").
#include <cstdint>
#include <string>
#include <vector>

#include "points/geometry.hpp"

namespace tilekit {
class ProgressReporter;
}

namespace tilekit::points {

enum class PoissonTileMethod { Corner, Wang, Dual };

const char* method_name(PoissonTileMethod m);
// "corner", "wang" or "dual"; InputError otherwise.
PoissonTileMethod parse_poisson_tile_method(const std::string& name);

struct PoissonTileParams {
  PoissonTileMethod method = PoissonTileMethod::Corner;
  std::uint32_t colours = 4;       // C
  std::uint32_t edge_colours = 1;  // E, corner method only
  std::uint32_t points = 0;        // N, points per tile; 0: default_tile_points(method)
  double rho = 0.75;               // relative radius (thesis eq. 4.3): no two points closer than 2 rho r_max(N)
  int lloyd = 0;                   // Lloyd iterations at least per region (0: only until rho is met)
  std::uint64_t seed = 1;
  int threads = 1;
  bool progress = false;  // ProgressReporter on stderr
};

// The points of every tile, in tile coordinates [0, 1)^2 (x east, y south, the tile's NW corner
// at the origin). Tile indices: corner and dual sets as complete corner sets over
// lattice_colours() (thesis eq. 2.5: ((NE L + SE) L + SW) L + NW), plus L^4 times the Wang index
// of the edge colours (eq. 2.2: ((N E + E) E + S) E + W) when E > 1 (edged_tile_index());
// edge-based sets by wang_pd_tile_index().
struct PoissonTileSet {
  PoissonTileMethod method = PoissonTileMethod::Corner;
  std::uint32_t colours = 0, points = 0;
  std::uint32_t edge_colours = 1;  // E
  double rho = 0;                  // asked for
  double radius = 0;               // r = rho r_max(N) on the unit tile; points are at least 2r (1 + kMargin) apart
  int lloyd = 0;
  std::uint64_t seed = 0;
  std::vector<std::vector<Point2>> tiles;
  // Distinct regions the construction sampled (corner, edge, interior) and its time.
  std::uint64_t corner_regions = 0, edge_regions = 0, interiors = 0;
  double seconds = 0;

  // Colours (states) per lattice point of the direct stochastic tiling that places the tiles.
  std::uint32_t lattice_colours() const { return method == PoissonTileMethod::Dual ? 4 * colours : colours; }
  // The smallest distance the construction guarantees between any two points of a tiling.
  double guaranteed_distance() const;
};

// The index of the corner tile with lattice colours (NW, NE, SW, SE) over L colours and edge
// colours (N, E, S, W) over E colours (the tile order above).
std::uint64_t edged_tile_index(std::uint32_t nw, std::uint32_t ne, std::uint32_t sw, std::uint32_t se, std::uint32_t l,
                               std::uint32_t n, std::uint32_t e, std::uint32_t s, std::uint32_t w, std::uint32_t ec);

// Relative safety margin on the distance: the construction keeps points 2r (1 + kMargin) apart
// so that float32 point files (24-bit mantissa) of windows up to ~10^4 points across keep 2r.
inline constexpr double kMargin = 1e-3;

// N when none is asked for: 1024 for corner sets, 64 for the others. A corner set's C corner
// regions, C^2 E edge regions and C^4 E^4 interiors recur across a tiling, so their share of a
// set's power at the tile lattice's harmonics grows with the tiles per set: about 16,384 / (N V)
// for a region type of V variants. With N = 64 and C = 4 the corner regions alone put +4 dB peaks
// into a 16,384-point spectrum; with N = 1024 all three stay near the -10 dB background
// (points/README.md, "Why the tiles showed").
std::uint32_t default_tile_points(PoissonTileMethod m);

// Throws InputError for parameters no tile set can meet (C < 1, N too small for the regions
// to fit, rho outside (0, 1), tile sets over 2^20 tiles, edge colours with another method).
void check_poisson_tile_params(const PoissonTileParams& p);

PoissonTileSet build_poisson_tiles(const PoissonTileParams& p);

// Edge-based tiles: the 12 Wang edge colours a tile's points depend on, in this order: its own
// N, E, S, W (thesis eq. 2.2), then at each corner the two edges that leave the tile there:
// NW corner north-going and west-going, NE north and east, SE south and east, SW south and west.
// Index = mixed radix in base C, first colour most significant.
std::uint64_t wang_pd_tile_index(const std::uint32_t colours12[12], std::uint32_t c);

// The independent check: every pair of tiles that can be neighbours (sharing an edge or a corner)
// placed side by side, all distances across the shared border measured directly. Returns the
// smallest distance found across tile borders (and within tiles), relative to r_max(N) as a
// relative radius. Exhaustive for corner and dual sets up to 2^25 neighbour pairs, else
// 64 random tilings of 8x8 tiles.
struct TileSetCheck {
  double rho_within = 0, rho_across = 0;  // relative radius inside single tiles and across borders
  std::uint64_t pairs_checked = 0;        // neighbour configurations (or random tilings) checked
  bool exhaustive = false;
  std::uint64_t points_off_count = 0;  // tiles whose point count is not N
};
TileSetCheck check_poisson_tiles(const PoissonTileSet& set, int threads = 1);

}  // namespace tilekit::points
