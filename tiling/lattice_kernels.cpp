// The vectorised inner loop of the direct corner tiling (lattice_tiling.hpp), compiled for AVX2
// and for the baseline instruction set; the loader picks the one the CPU runs (GCC
// target_clones, TILEKIT_CLONES). Plain loops the compiler vectorises: 16-bit lanes throughout.
#include "tiling/lattice_hash.hpp"
#include "tiling/lattice_tiling.hpp"

namespace tilekit {

TILEKIT_CLONES void corner_row_tiles(const std::uint8_t* south, const std::uint16_t* north_code, std::size_t n,
                                     std::uint32_t colours, TileIndex* out, std::uint16_t* south_code) {
  const std::uint16_t c1 = std::uint16_t(colours), c2 = std::uint16_t(c1 * c1), c3 = std::uint16_t(c2 * c1);
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint16_t sw = south[k], se = south[k + 1];
    // thesis eq. (2.5): ((NE C + SE) C + SW) C + NW = (NE C^3 + NW) + (SE C^2 + SW C)
    out[k] = TileIndex(std::uint16_t(north_code[k] + std::uint16_t(se * c2 + sw * c1)));
    south_code[k] = std::uint16_t(se * c3 + sw);  // this row's NE C^3 + NW part, for the next row of tiles
  }
}

TILEKIT_CLONES void corner_row_code(const std::uint8_t* row, std::size_t n, std::uint32_t colours,
                                    std::uint16_t* code) {
  const std::uint16_t c3 = std::uint16_t(colours * colours * colours);
  for (std::size_t k = 0; k < n; ++k) code[k] = std::uint16_t(row[k + 1] * c3 + row[k]);
}

}  // namespace tilekit
