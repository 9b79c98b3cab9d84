#pragma once
// A Tiled Wang set read back as a Tilekit tile set: a tileset file (.tsx, Tiled 1.5 and later)
// with a <wangset> of type "corner" (a corner set) or "edge" (a Wang set), each <wangtile>'s
// wangid one tile (tilemap/wang_id.hpp). Tiles that share a wangid (Tiled's variants, drawn
// several times for variety) are one tile of the set. Refused with an InputError (exit 2) naming
// the file and the problem: a file that is not such XML or is larger than 64 MiB, no Wang set
// (or none of the given name), a "mixed" set, an entry unset where the type needs a colour or
// set where it needs none, a colour above the set's, no tiles.
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "tilesets/tile_set.hpp"

namespace tilekit::tilemap {

inline constexpr std::uint64_t kMaxTsxBytes = std::uint64_t(64) << 20;

struct ImportedWangSet {
  TileSet set;                            // named after the Wang set, source the file
  std::string type;                       // "corner" or "edge"
  std::vector<std::string> colour_names;  // colour k of the set is Tiled's colour k + 1
  std::vector<int> tile_ids;              // Tiled tile id of tile k of the set (its first variant)
  std::map<int, std::size_t> tile_of_id;  // every Tiled tile id with a wangid -> its tile k (variants too)
  std::size_t wang_tiles = 0;             // <wangtile> entries read (variants included)
};

// `wangset` names the Wang set to read; "" reads the file's first.
ImportedWangSet read_tiled_wang_set(const std::string& path, const std::string& wangset = "");
// The same from the file's text; `origin` names it in errors.
ImportedWangSet parse_tiled_wang_set(const std::string& text, const std::string& origin,
                                     const std::string& wangset = "");

}  // namespace tilekit::tilemap
