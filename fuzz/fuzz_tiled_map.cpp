// Maps painted in Tiled (.tmx) as `fill --cells MAP.tmx` reads them (tilemap/tmx_reader.hpp): any
// input is a PaintedMap or an InputError. Tilesets are named relative to a folder that does not
// exist, so every external tileset is refused by name; a map that parses has width x height gids,
// none with Tiled's flip bits, and its tilesets in increasing firstgid order.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "base/error.hpp"
#include "tilemap/tmx_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tilekit;
  const std::string text(reinterpret_cast<const char*>(data), size);
  tilemap::PaintedMap m;
  try {
    m = tilemap::parse_painted_map(text, "/nonexistent-tilekit-fuzz/fuzz.tmx");
  } catch (const InputError&) {
    return 0;
  }
  if (m.width < 1 || m.height < 1 || m.gids.size() != std::size_t(m.width) * std::size_t(m.height)) std::abort();
  for (std::uint32_t g : m.gids)
    if (g & 0xF0000000u) std::abort();
  for (std::size_t k = 1; k < m.tilesets.size(); ++k)
    if (m.tilesets[k - 1].firstgid > m.tilesets[k].firstgid) std::abort();
  for (std::uint32_t g : m.gids)
    if (g != 0 && tilemap::tileset_of_gid(m, g) >= int(m.tilesets.size())) std::abort();
  return 0;
}
