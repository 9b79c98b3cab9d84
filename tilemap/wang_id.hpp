#pragma once
// Tiled's Wang ids (Tiled 1.5 and later, the format of Tiled 1.8): every tile of a Wang set
// carries eight colour numbers in the order top, top-right, right, bottom-right, bottom,
// bottom-left, left, top-left; 0 means "unset" and the set's colours count from 1. A Tiled
// "corner" set uses the four corner entries, an "edge" set the four edge entries, a "mixed" set
// both. Tilekit's corner tiles are Tiled's corner sets and its Wang tiles Tiled's edge sets, with
// colour k of Tilekit written as k + 1.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "tilesets/tile.hpp"

namespace tilekit::tilemap {

// Entries in Tiled's order.
enum WangSlot { kTop, kTopRight, kRight, kBottomRight, kBottom, kBottomLeft, kLeft, kTopLeft };
using WangId = std::array<std::uint32_t, 8>;

// The most colours a Tiled Wang set holds (a Wang id entry is one byte, 0 unset).
inline constexpr std::uint32_t kMaxTiledColours = 255;

// "corner" for corner tiles, "edge" for Wang tiles; InputError for window sets.
std::string_view wang_type_name(TileKind kind);

// The Wang id of tile `index` (thesis eq. 2.3 / 2.6) of the complete set over `colours`.
WangId wang_id_of(TileKind kind, std::uint32_t colours, TileIndex index);
WangId wang_id_of(const WangTile& t);
WangId wang_id_of(const CornerTile& t);

// Back to a tile of a set over `colours` colours. Throws InputError naming `where` for an entry
// that is unset (0) where the kind needs a colour, set where it needs none (a mixed tile), or
// above `colours`.
CornerTile corner_tile_of(const WangId& id, std::uint32_t colours, const std::string& where);
WangTile wang_tile_of(const WangId& id, std::uint32_t colours, const std::string& where);

// "0,1,0,2,0,1,0,1" and back; parse_wang_id throws InputError naming `where` unless the text
// is eight comma-separated numbers 0..255 (Tiled before 1.5 wrote one hexadecimal number: refused).
std::string format_wang_id(const WangId& id);
WangId parse_wang_id(std::string_view text, const std::string& where);

}  // namespace tilekit::tilemap
