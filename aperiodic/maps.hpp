#pragma once
// Carrying tilings across the ch. 8 conversions: a patch of the source (a grid of tile
// numbers) maps to a patch of the result and, for sound constructions, back. These maps
// are the constructions' geometry made explicit (thesis Figs. 8.7-8.9, 8.12); the
// round-trip tests check them with the independent validator.
#include <cstdint>
#include <vector>

#include "aperiodic/convert.hpp"
#include "tilesets/tile_set.hpp"
#include "tilesets/tile_grid.hpp"

namespace tilekit {

// A rectangular patch of tile numbers (positions in a tile list); -1 = no tile.
struct Patch {
  int rows = 0, cols = 0;
  std::vector<std::int64_t> cells;
  Patch() = default;
  Patch(int r, int c) : rows(r), cols(c), cells(std::size_t(r) * std::size_t(c), -1) {}
  std::int64_t& at(int r, int c) { return cells[std::size_t(r) * std::size_t(cols) + std::size_t(c)]; }
  std::int64_t at(int r, int c) const { return cells[std::size_t(r) * std::size_t(cols) + std::size_t(c)]; }
  std::size_t holes() const;
};

// Source patch -> result patch. Shapes: diagonal (R-1)x(K-1), horizontal Rx(K-1),
// vertical (R-1)xK, rotation n x n (source n x n with n odd; the corner patch is the
// square inscribed in the turned lattice), subdivision 2R x 2K, to-wang R x K.
// Cells whose 2x2 peg window is not a tile of the result stay -1 (cannot happen for a
// valid source patch). InputError on a patch with holes or a bad shape.
Patch map_forward(const TileSet& source, const Conversion& conv, const Patch& patch);

// Result patch -> source patch, for conjugate (and lifting) constructions. Shapes are the
// inverse of map_forward; rotation recovers the diamond of source cells whose white tile
// lies in the patch (other cells -1); translations lift each row (column) by dynamic
// programming over the transducer. InputError when the method has no inverse or a row
// does not lift.
Patch map_backward(const TileSet& source, const Conversion& conv, const Patch& patch);

// The patch as a bounded tiling of `set` (tile indices, thesis eq. 2.2/2.5) for the
// independent validator. InputError if the patch has holes.
Tiling patch_to_tiling(const TileSet& set, const Patch& patch);

}  // namespace tilekit
