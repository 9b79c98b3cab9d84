#pragma once
// Pictures of tile sets, tilings and packings, drawn the way the thesis figures are: a Wang
// tile as four triangles meeting at its centre, one per edge colour; a corner tile as a light
// square with a coloured quarter disc at each corner (so the four tiles around a lattice point
// show one full disc). Colours 0-4 are red, yellow, green, cyan and blue, then further distinct
// colours. One Picture feeds both writers: SVG (vector) and PNG (4x4 supersampled, encoded by image/).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "tilesets/tile.hpp"
#include "tilesets/tile_set.hpp"
#include "tilesets/tile_grid.hpp"

namespace tilekit::atlas {

// The colour drawn for colour number `c`: 0 red, 1 yellow, 2 green, 3 cyan, 4 blue, then
// magenta, orange, purple, brown, pink, olive, grey, then hues spaced by the golden angle.
Rgb palette_colour(std::uint32_t c);
std::string hex(Rgb c);  // "#rrggbb"

inline constexpr Rgb kCornerBackground{232, 232, 232};
inline constexpr Rgb kBorder{64, 64, 64};
inline constexpr Rgb kPaper{255, 255, 255};

// One tile in a slot of the picture's grid. Wang: colours n, e, s, w. Corner: ne, se, sw, nw.
struct PlacedTile {
  int row = 0, col = 0;
  TileKind kind = TileKind::Corner;
  std::array<std::uint32_t, 4> colours{};
};

struct RenderOptions {
  int tile_px = 0;       // pixels per tile side; 0 chooses from the grid size
  bool borders = false;  // draw each tile's outline
};

// A grid of slots (`rows` x `cols`), `tile_px` wide, `gap` pixels apart, holding tiles.
struct Picture {
  int rows = 0, cols = 0, tile_px = 32, gap = 0;
  bool borders = false;
  std::vector<PlacedTile> tiles;
  int width() const { return cols * tile_px + (cols + 1) * gap; }
  int height() const { return rows * tile_px + (rows + 1) * gap; }
};

// A tile set laid out in index order, about square, tiles apart.
Picture draw_tile_set(const TileSet& set, const RenderOptions& opt = {});
// A tiling or packing, tiles edge to edge.
Picture draw_tiling(const Tiling& tiling, const RenderOptions& opt = {});
// Throws the InputError draw_tiling would for a rows x cols tiling that is too large to draw.
void check_tiling_picture(int rows, int cols, const RenderOptions& opt = {});

std::string to_svg(const Picture& p);
std::string to_png(const Picture& p);  // the encoded PNG file
// RGB pixels of the rendered picture, row-major (what to_png encodes).
std::vector<Rgb> rasterise(const Picture& p);

// True for paths ending in .svg or .png.
bool is_picture_path(const std::string& path);
// Writes to_svg or to_png by the extension, atomically; InputError for other extensions.
void write_picture(const Picture& p, const std::string& path);

}  // namespace tilekit::atlas
