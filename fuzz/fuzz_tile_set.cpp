// Tile-set files, text and JSON (tilesets/tile_set_io.hpp): any input is a TileSet or an
// InputError; a set that parses survives the text and JSON round trips unchanged.
#include <cstdint>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

#include "base/error.hpp"
#include "tilesets/tile_set_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tilekit;
  const std::string text(reinterpret_cast<const char*>(data), size);
  TileSet set;
  try {
    set = parse_tile_set(text, "fuzz.tiles");
  } catch (const InputError&) {
    return 0;
  }
  const TileSet again = parse_tile_set(format_tile_set_text(set), "again.tiles");
  const TileSet from_json = parse_tile_set(tile_set_to_json(set).dump(), "again.json");
  for (const TileSet* s : {&again, &from_json})
    if (s->kind() != set.kind() || s->size() != set.size() || s->source() != set.source()) std::abort();
  for (std::size_t k = 0; k < set.size(); ++k)
    if (again.file_colours(k) != set.file_colours(k) || from_json.file_colours(k) != set.file_colours(k)) std::abort();
  return 0;
}
