// Point tile files: Poisson disk tile sets (.ptiles, points/tile_set_file.hpp) and recursive Wang
// tile sets (.rtiles, points/recursive_tiles.hpp). Byte 0 picks the format (bit 0) and whether
// the rest is the whole file or a body that gets a valid closing checksum line (bit 1), so that
// the fuzzer reaches the counts, the points and the checks on load past the checksum. What loads
// must keep its promises: every tile holds N points, the radius belongs to rho and N, and the
// independent neighbour check finds no two points closer than the set's rho says.
#include <cmath>
#include <cstdint>
#include <string>

#include "base/error.hpp"
#include "points/geometry.hpp"
#include "points/recursive_tiles.hpp"
#include "points/text_format.hpp"
#include "points/tile_set_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tilekit::points;
  if (size == 0) return 0;
  std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  if (data[0] & 2) text = text::with_checksum(std::move(text));
  try {
    if (data[0] & 1) {
      const RecursiveWangTiles t = recursive_tiles_from_text(text, "fuzz.rtiles");
      for (std::size_t type = 0; type < t.types(); ++type)
        if (t.base[type].size() != t.points || t.rank[type].size() != std::size_t(t.n) * std::size_t(t.n) * t.points)
          __builtin_trap();
    } else {
      const PoissonTileSet s = poisson_tiles_from_text(text, "fuzz.ptiles");
      for (const auto& tile : s.tiles)
        if (tile.size() != s.points) __builtin_trap();
      if (!(std::abs(s.radius - s.rho * max_poisson_radius(s.points)) <= 1e-9 * s.radius)) __builtin_trap();
      const TileSetCheck c = check_poisson_tiles(s);
      if (c.rho_within < s.rho || c.rho_across < s.rho) __builtin_trap();
    }
  } catch (const tilekit::InputError&) {
  }
  return 0;
}
