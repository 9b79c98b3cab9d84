#pragma once
// The fundamental domain of a packing or periodic tiling under an imposed group G
// (impose_group.hpp): what the search model (impose_model.hpp) and the CNF encoding
// (impose_sat.hpp) are built from. Variables ("sites") are one representative per
// G-orbit of lattice points (corner tiles: pegs, thesis sec. 5.5 / the de Bruijn torus view) or
// of edges (Wang tiles: the horizontal and the vertical edge grid). Every other peg or edge is
// the image pi_g(value) of its representative. Constraints live on one representative cell per
// cell orbit: its four slots (site, permutation) give its tile, whose G-orbit must be in the set
// and, for a packing, used by no other representative cell ("each orbit of tiles exactly once").
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "solver/impose_group.hpp"
#include "tilesets/tile_set.hpp"
#include "tilesets/tile_grid.hpp"

namespace tilekit {

struct TilingProblem;

struct FundamentalDomain {
  struct Slot {
    int site = 0;          // representative variable
    int perm = 0;          // index into perm_tables: colour = perm_tables[perm][value]
    std::uint32_t weight;  // radix weight of this corner/edge in the tile index (thesis eq. 2.2/2.5)
  };
  TileKind kind = TileKind::Corner;
  std::uint32_t ch = 0, cv = 0;
  int rows = 0, cols = 0;
  bool packing = true;
  std::size_t group_order = 1;

  int num_sites = 0;
  std::vector<std::uint32_t> site_colours;             // domain size of each site (ch or cv)
  std::vector<std::vector<std::uint8_t>> perm_tables;  // per (element, class): colour map
  std::vector<std::array<Slot, 4>> cells;              // representative cells; slot order NE,SE,SW,NW / N,E,S,W
  std::vector<std::array<int, 2>> cell_positions;      // (row, col) of each representative cell
  std::vector<std::int32_t> orbit_of;                  // tile index -> orbit id, -1 if not usable
  int num_orbits = 0;

  // Where each peg (corner; rows*cols lattice points) or edge (Wang: h-edges then v-edges, each
  // rows*cols, the N edge and the W edge of cell (r,c)) comes from: (site, perm table).
  std::vector<std::array<int, 2>> origin;

  // Builds the model. Throws InputError for a problem the group cannot apply to (bounded grid,
  // tile set not closed under G in packing mode, a tile fixed by G, mismatched sizes).
  static FundamentalDomain build(const TilingProblem& problem, const ImposedGroup& group);

  // The full tiling from site values (one per site).
  Tiling to_tiling(const std::vector<int>& values) const;
};

// The group of a spec for a problem (the packing rules when problem.packing). Throws InputError
// for a bad spec or a group that cannot hold a solution.
ImposedGroup build_group(const TilingProblem& problem, const std::string& spec);

}  // namespace tilekit
