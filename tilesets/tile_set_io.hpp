#pragma once
// Tile-set files: text, one tile per line, `n s w e` (Wang) or `nw ne sw se`
// (corner, marked by a first line `# kind: corner`), `#` comments; or JSON
// {"kind":"wang"|"corner","tiles":[[...],...]}. Also the built-in set names.
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "tilesets/tile_set.hpp"

namespace tilekit {

// A tile equal to an earlier one of the same file.
struct RepeatedTile {
  std::string where;             // "file:line" (text) or "file: tile N" (JSON)
  std::size_t first = 0;         // 0-based position of the earlier tile in the set of distinct tiles
  std::vector<Colour> colours;   // in file order
};

// Parses text or JSON (detected by a leading '{'). `origin` names the file in errors.
// Throws InputError "origin:line: problem". A repeated tile is an InputError, unless `repeated`
// is given: then repeats are dropped (the set keeps the first of equal tiles, in order) and
// listed there (a repeated tile changes nothing about what a set tiles).
TileSet parse_tile_set(std::string_view text, const std::string& origin, std::vector<RepeatedTile>* repeated = nullptr);
TileSet read_tile_set_file(const std::string& path, std::vector<RepeatedTile>* repeated = nullptr);

std::string format_tile_set_text(const TileSet& set);
nlohmann::json tile_set_to_json(const TileSet& set);

// A built-in name (complete-wang-C, complete-wang-HxV, complete-corner-C, compact-wang-C,
// compact-wang3-C, compact-corner-C, a reference set by file stem) or a file path.
TileSet resolve_tile_set(const std::string& name_or_path, std::vector<RepeatedTile>* repeated = nullptr);

struct BuiltinInfo {
  std::string name;         // a name or a pattern such as "complete-corner-C"
  std::string description;
};
std::vector<BuiltinInfo> builtin_tile_sets();

}  // namespace tilekit
