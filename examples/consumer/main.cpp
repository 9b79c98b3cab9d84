// Tilekit as a library: the packing of the complete corner set over C colours laid out as an
// atlas (what `tilekit atlas lookup --kind corner --colors C --no-db` prints), a window of the
// direct stochastic tiling (thesis sec. 3.3.1; `tilekit tile --set complete-corner-C --algo direct
// --size 8x4 --seed 1` writes the same tiling) and the atlas cell of each of its tiles, which is
// what a renderer looks up per tile. Usage: consumer [C] (default 3).
#include <cstdint>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "atlas/lookup.hpp"
#include "tiling/direct_tiling.hpp"

int main(int argc, char** argv) {
  const auto colours = std::uint32_t(argc > 1 ? std::stoul(argv[1]) : 3);
  const tilekit::AtlasLookup atlas = tilekit::atlas_lookup(tilekit::TileKind::Corner, colours);
  const tilekit::Tiling window = tilekit::DirectCornerTiling(colours, tilekit::HashKind::LongPeriod, 1).generate(4, 8);
  std::cout << tilekit::lookup_json_text(atlas) << "\n" << tilekit::tiling_to_json(window).dump() << "\n";
  for (int r = 0; r < window.rows; ++r, std::cout << "\n")
    for (int c = 0; c < window.cols; ++c)
      std::cout << (c ? " " : "") << atlas.positions[window.at(r, c)].first << ","
                << atlas.positions[window.at(r, c)].second;
}
