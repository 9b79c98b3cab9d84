#pragma once
// A tiling or packing: a grid of tile indices (row-major, row 0 at the top/north, column 0 at
// the left/west; a torus wraps row/column n-1 to 0), and its JSON file format
// {"kind","colors","rows","cols","torus","cells":[[i,...],...]}.
#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "tilesets/tile.hpp"

namespace tilekit {

class JsonIn;  // base/json_input.hpp

// Limits of a tiling file: sides up to 2^20 and 2^28 cells (1 GiB of tile indices); the
// largest packing Tilekit makes is 4096x4096 (the atlas of C=64).
inline constexpr std::int64_t kMaxTilingSide = std::int64_t(1) << 20;
inline constexpr std::int64_t kMaxTilingCells = std::int64_t(1) << 28;

struct Tiling {
  TileKind kind = TileKind::Corner;
  std::uint32_t colours = 0;           // C (the radix of N/S edges for Wang sets)
  std::uint32_t vertical_colours = 0;  // Wang only: radix of E/W edges; 0 means == colours
  int rows = 0, cols = 0;
  bool torus = false;
  std::vector<TileIndex> cells;        // rows*cols tile indices (thesis eq. 2.2 / 2.5)

  Tiling() = default;
  Tiling(TileKind k, std::uint32_t c, int r, int cl, bool t)
      : kind(k), colours(c), rows(r), cols(cl), torus(t), cells(std::size_t(r) * std::size_t(cl), 0) {}

  std::uint32_t ch() const { return colours; }
  std::uint32_t cv() const { return vertical_colours ? vertical_colours : colours; }
  TileIndex& at(int r, int c) { return cells[std::size_t(r) * std::size_t(cols) + std::size_t(c)]; }
  TileIndex at(int r, int c) const { return cells[std::size_t(r) * std::size_t(cols) + std::size_t(c)]; }
};

nlohmann::json tiling_to_json(const Tiling& t);
// Throws InputError naming `origin`, the JSON path and the problem. Reads "cells", or for a
// corner torus the compact "pegs" form below.
Tiling tiling_from_json(const nlohmann::json& j, const std::string& origin);
Tiling tiling_from_json(const JsonIn& j);  // a tiling inside a larger document (an export row)

// Pegs <-> corner tiles on a rows x cols torus: cell (r,c) holds the tile with nw = P(r,c),
// ne = P(r,c+1), sw = P(r+1,c), se = P(r+1,c+1) (indices wrap). A corner packing is thus a
// (C^2,C^2;2,2)_C de Bruijn torus of pegs: every 2x2 window of pegs occurs exactly once.
Tiling corner_torus_from_pegs(const std::vector<Colour>& pegs, int rows, int cols, std::uint32_t colours);
std::vector<Colour> pegs_of_corner_torus(const Tiling& t);  // the nw corner of every cell
// The compact file form of a corner torus: "pegs" holds one string per row with one digit per
// peg (0-9, a-z, A-Z, so at most 62 colours) instead of "cells" (a C=16 packing: 64 KiB instead
// of 400 KiB). Throws InputError unless `t` is a corner torus whose cells are its pegs' windows.
nlohmann::json tiling_to_peg_json(const Tiling& t);
Tiling read_tiling_file(const std::string& path);

}  // namespace tilekit
