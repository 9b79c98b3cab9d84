#pragma once
// Symmetries of packings of a complete tile set on a torus (thesis sec. 5.5: packings are
// counted up to symmetry). The group is T x H: torus translations T, and H = the grid
// reflections/rotations that map the rows x cols torus to itself (a transpose needs a square
// torus and, for Wang tiles, equal horizontal and vertical radices) combined with colour
// permutations (one permutation of all colours for corner tiles; independent permutations of
// the N/S and E/W colours for Wang tiles, which never meet each other).
//
// Translations are handled by normalisation: a packing's "normal form" is its translate with
// the anchor tile (index 0) at cell (0,0), which is exactly what the solver's translation
// breaking produces. The canonical form of a packing is the least normal form among its images
// under H (lexicographic on the row-major cells); counting the solutions that equal their own
// canonical form counts orbits, with no set of seen solutions.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "solver/problem.hpp"
#include "tilesets/tile_grid.hpp"

namespace tilekit {

class PackingSymmetry {
 public:
  // The group for `problem`, or nullopt when it is not a packing of a complete set on a torus,
  // or when H would have more than `max_order` elements.
  static std::optional<PackingSymmetry> for_problem(const TilingProblem& problem, std::size_t max_order = 10000);

  std::size_t order() const { return inverse_tile0_.size(); }                   // |H|
  std::uint64_t full_order() const { return order() * std::uint64_t(cells_); }  // |T x H|

  // `cells` must be in normal form. True when no image under H is smaller; `stabiliser`
  // (optional) receives the number of elements of H fixing it.
  bool is_canonical(const std::vector<TileIndex>& cells, std::uint64_t* stabiliser = nullptr) const;
  // The canonical form of any packing (normalised first), and its orbit size under T x H.
  Tiling canonical(const Tiling& t, std::uint64_t* orbit_size = nullptr) const;
  // Translate so that tile index 0 sits at (0,0).
  Tiling normal_form(const Tiling& t) const;

 private:
  // Lexicographic comparison of the normal form of image h of `cells` with `ref`:
  // <0, 0 or >0.
  int compare_image(std::size_t h, const std::vector<TileIndex>& cells, const std::vector<TileIndex>& ref) const;
  std::vector<TileIndex> image(std::size_t h, const std::vector<TileIndex>& cells) const;

  const TileIndex* tile_map(std::size_t h) const { return &tile_maps_[h * tiles_]; }
  // h = geometry * colour_maps_ + colour map: the 8 (or 4) geometric maps share cell maps.
  const std::vector<int>& cell_map(std::size_t h) const { return cell_maps_[h / colour_maps_]; }
  const std::vector<int>& inverse_cell_map(std::size_t h) const { return inverse_cells_[h / colour_maps_]; }

  int rows_ = 0, cols_ = 0, cells_ = 0;
  std::size_t tiles_ = 0, colour_maps_ = 1;
  std::vector<TileIndex> tile_maps_;             // h * tiles_ + tile -> its image (one block: fast to build)
  std::vector<TileIndex> inverse_tile0_;         // h -> the tile that h maps to tile index 0
  std::vector<std::vector<int>> cell_maps_;      // geometry -> cell -> image cell
  std::vector<std::vector<int>> inverse_cells_;  // geometry -> image cell -> cell
};

// The packing translated by (dr, dc): cell (r,c) moves to (r+dr, c+dc) mod the torus.
Tiling translate(const Tiling& t, int dr, int dc);

}  // namespace tilekit
