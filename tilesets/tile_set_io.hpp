#pragma once
// Tile-set files (DESIGN.md): text, one tile per line, `n s w e` (Wang) or `nw ne sw se`
// (corner, marked by a first line `# kind: corner`), `#` comments; or JSON
// {"kind":"wang"|"corner","tiles":[[...],...]}. Also the built-in set names.
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "tilesets/tile_set.hpp"

namespace tilekit {

// Parses text or JSON (detected by a leading '{'). `origin` names the file in errors.
// Throws InputError "origin:line: problem".
TileSet parse_tile_set(std::string_view text, const std::string& origin);
TileSet read_tile_set_file(const std::string& path);

std::string format_tile_set_text(const TileSet& set);
nlohmann::json tile_set_to_json(const TileSet& set);

// A built-in name (complete-wang-C, complete-wang-HxV, complete-corner-C, compact-wang-C,
// compact-wang3-C, compact-corner-C, a reference set by file stem) or a file path.
TileSet resolve_tile_set(const std::string& name_or_path);

struct BuiltinInfo {
  std::string name;         // a name or a pattern such as "complete-corner-C"
  std::string description;
};
std::vector<BuiltinInfo> builtin_tile_sets();

}  // namespace tilekit
