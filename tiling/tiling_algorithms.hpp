#pragma once
// One entry point for every tiling algorithm (the names `tilekit tile --algo` takes): checks
// that the algorithm fits the tile set (it can only produce tiles of the set) and generates the
// tiling.
//   scanline        Wang (Cohen et al. 2003; thesis 3.2.1) or corner (thesis 3.2.2)
//   direct          corner (thesis 3.3.1) or Wang with two hashes (thesis 3.3.2.1)
//   direct-edge     Wang, one hash at the tile edges (thesis 3.3.2.3)
//   direct-compact  Wang on compact-wang3-C (thesis 3.3.2.2)
//   halton          corner, Halton sequence (Schloemer & Deussen 2010, eq. 4-6)
//   controlled      corner, from a colour probability map (Schloemer & Deussen 2010, eq. 7)
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tiling/controlled_tiling.hpp"
#include "tiling/lattice_hash.hpp"
#include "tilesets/tile_set.hpp"
#include "tilesets/tile_grid.hpp"

namespace tilekit {

enum class TilingAlgo { Scanline, Direct, DirectEdge, DirectCompact, Halton, Controlled };

TilingAlgo parse_tiling_algo(const std::string& name);  // InputError for unknown names
const char* tiling_algo_name(TilingAlgo a);
std::vector<std::string> tiling_algo_names();

struct TilingRequest {
  TilingAlgo algo = TilingAlgo::Direct;
  int rows = 0, cols = 0;
  std::uint64_t seed = 1;
  HashKind hash = HashKind::LongPeriod;
  std::optional<ProbabilityMap> map;  // controlled only; default: ProbabilityMap::ramp
};

// Largest tiling the command makes: 65536 per side and 2^24 tiles in all (the validator
// keeps 32 bytes per cell).
void check_tiling_size(std::int64_t rows, std::int64_t cols);

// Throws InputError when the algorithm does not fit the set (wrong kind, or a tile it can
// produce is missing from the set) or the size is out of range.
Tiling generate_tiling(const TileSet& set, const TilingRequest& req);

}  // namespace tilekit
