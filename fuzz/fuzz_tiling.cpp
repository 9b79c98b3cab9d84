// Tiling/packing JSON files (tilesets/tile_grid.hpp), then the independent validator on what parses.
#include <cstdint>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

#include "base/error.hpp"
#include "base/json_input.hpp"
#include "tilesets/tile_grid.hpp"
#include "tilesets/validator.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tilekit;
  const std::string text(reinterpret_cast<const char*>(data), size);
  Tiling t;
  try {
    t = tiling_from_json(parse_json_input(text, "fuzz.json"), "fuzz.json");
  } catch (const InputError&) {
    return 0;
  }
  validate(t);
  if (tiling_from_json(tiling_to_json(t), "again.json").cells != t.cells) std::abort();
  return 0;
}
