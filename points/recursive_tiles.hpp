#pragma once
// Recursive Wang tiles for real-time blue noise (Kopf, Cohen-Or, Deussen and Lischinski 2006),
// over the 8 compact Wang tiles with N + S = E + W (mod 2) that the direct stochastic tiling
// places (thesis sec. 3.3.2.2; the 2K^2 = 8 tiles of the paper).
//
// Construction (the paper's sec. 4-5):
//  1. progressive toroidal source tiles: relaxation dart throwing whose acceptance order is the
//     rank (McCool and Fiume 1992) - one per edge colour and direction, one per tile;
//  2. each tile starts from its own source and merges in the sources of its N, E, S, W edge
//     colours along seams: min-cost paths over the Voronoi edges of the union, cost
//     (1 - d / d_max)^10 (d: distance between the two points an edge separates), by Dijkstra
//     (Boost.Graph) on a raster Voronoi diagram;
//  3. a progressive ranking: the source ranks interleaved, then greedily fixed so that point i
//     is at least 0.5 / sqrt(i) from the points ranked before it (the paper's Fig. 5);
//  4. a subdivision rule per tile: n x n sub-tiles whose border colours follow one n-colour
//     sequence per edge colour (shared by all tiles, so subdivisions of neighbours match) and
//     whose interior is filled by scanline (the compact C^3 set leaves E free and S = E + W - N);
//  5. relaxation: every base point moves a tenth of the way to its nearest point of the tile's
//     subdivision set, all tiles at once, until the base points lie on subdivision points
//     (Fig. 8); they are then snapped exactly;
//  6. the subdivision set's ranking: the N base points first, then dart throwing with a
//     shrinking radius over the other points (Fig. 8).
//
// Generation is progressive by construction: every point has a birth level and a rank, and the
// set for a density function d is every point whose rank is below d at the point times its
// tile's area (the base points of a level having been emitted one level up); a sub-tile is
// visited when the density somewhere in its parent exceeds what the parent's subdivision set can
// give. So for d <= d' everywhere the points for d are a subset of those for d'.
#include <cstdint>
#include <string>
#include <vector>

#include "points/density.hpp"
#include "points/generator.hpp"
#include "points/geometry.hpp"
#include "tiling/lattice_hash.hpp"

namespace tilekit::points {

struct RecursiveTileParams {
  std::uint32_t points = 512;  // N per tile
  int subdivision = 2;         // n: a tile splits into n x n sub-tiles
  std::uint64_t seed = 1;
  int threads = 1;
  bool progress = false;
};

struct RecursiveWangTiles {
  std::uint32_t colours = 2;  // of the compact set: C^3 = 8 tiles
  std::uint32_t points = 0;
  int n = 2;
  std::uint64_t seed = 0;
  std::vector<std::uint32_t> wang;               // tile type -> Wang tile index (thesis eq. 2.2)
  std::vector<std::vector<Point2>> base;         // per type, N points in rank order, tile coordinates
  std::vector<std::vector<std::uint32_t>> rule;  // per type, n^2 sub-tile types, row-major
  std::vector<std::vector<std::uint32_t>> rank;  // per type, rank of sub-tile j's point i at [j N + i]
  // Construction statistics.
  int relax_iterations = 0;
  double relax_residual = 0;  // largest distance a base point moved when snapped
  double seconds = 0;

  std::size_t types() const { return base.size(); }
  // The type of the compact Wang tile with these edge colours, or -1.
  int type_of(std::uint32_t wang_index) const;
};

RecursiveWangTiles build_recursive_tiles(const RecursiveTileParams& p);

// Files (points/README.md): "TILEKIT-RECURSIVE-TILES 1", header lines, per type its Wang index,
// rule, base points and subdivision ranks, "end", then an FNV-1a checksum line.
std::string recursive_tiles_to_text(const RecursiveWangTiles& t);
RecursiveWangTiles recursive_tiles_from_text(const std::string& text, const std::string& source);
void write_recursive_tiles(const std::string& path, const RecursiveWangTiles& t);
RecursiveWangTiles read_recursive_tiles(const std::string& path);

class RecursiveGenerator {
 public:
  // `period` > 0: the base tiling repeats every `period` tiles (toroidal sets for spectra).
  RecursiveGenerator(const RecursiveWangTiles& tiles, HashKind hash, std::uint64_t seed, std::int64_t period = 0);

  // Every point of the window for `density` (points per unit area), base tiles of side
  // `base_size`, at most `max_levels` subdivisions below the base tiles. Interleaved (x, y).
  std::vector<double> generate(const Window& w, const DensityFunction& density, double base_size, int max_levels = 20,
                              int threads = 1) const;

  // The compact Wang tile type of base tile (tx, ty).
  std::uint32_t base_type(std::int64_t tx, std::int64_t ty) const;

 private:
  void visit(std::uint32_t type, double x0, double y0, double size, int level, const Window& w,
             const DensityFunction& d, int max_levels, std::vector<double>& out) const;

  const RecursiveWangTiles& t_;
  ColourHash hash_;
  std::int64_t period_;
};

}  // namespace tilekit::points
