#pragma once
// A packing laid out as a Tiled tileset (thesis 5.5: every tile of the complete set exactly once
// on a torus), so that the sheet itself tiles seamlessly, and its .tsx text: one Wang set whose
// tiles carry the Wang ids of tilemap/wang_id.hpp, and the map (.tmx) that uses it.
#include <cstdint>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "tilesets/tile_grid.hpp"

namespace tilekit::tilemap {

// The most colours a sheet is made for: a C^2 x C^2 sheet of tiles of at least 2 pixels
// stays within the 8192-pixel side of a picture (atlas/render.hpp) up to C = 64.
inline constexpr std::uint32_t kMaxSheetColours = 64;

struct TiledSheet {
  Tiling packing;   // the sheet: cell (r, c) is Tiled tile id r * cols + c
  std::string how;  // the construction (tilesets/constructions.hpp)
  bool closed_form = false;
  std::vector<std::uint32_t> tile_id;  // tile index (thesis eq. 2.2 / 2.5) -> Tiled tile id
};

// The constructed packing of the complete corner or Wang set over `colours` colours, checked by
// the independent validator. InputError for C outside 1..kMaxSheetColours or a window kind.
TiledSheet sheet_layout(TileKind kind, std::uint32_t colours);

struct TsxFile {
  std::string name;   // the tileset's and the Wang set's name (any text; escaped)
  std::string image;  // the sheet PNG, relative to the .tsx
  int tile_px = 32;
  bool builtin_colours = true;  // colours named after atlas/render.hpp's palette ("red", ...)
  // Names of the Wang colours by colour (terrains: "grass", "sand"); empty: as builtin_colours says.
  std::vector<std::string> colour_names;
  // The Wang colours' display colours by colour (a terrain's mean colour); empty: the pictures' palette.
  std::vector<Rgb> colour_rgb;
};

// Tiled 1.8's tileset file: the image, then a Wang set of type "corner" or "edge" with one
// <wangcolor> per colour (its tile: the one tile of that colour alone) and one <wangtile> per tile.
std::string tsx_text(const TiledSheet& sheet, const TsxFile& file);

// An orthogonal map of `map`'s cells (any tiles of the sheet's set), one CSV layer, using the
// tileset `tsx` (relative to the .tmx) with first gid 1. InputError for a tile of another set.
std::string tmx_text(const TiledSheet& sheet, const Tiling& map, const std::string& tsx, int tile_px);

}  // namespace tilekit::tilemap
