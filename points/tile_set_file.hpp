#pragma once
// Point tile-set files (documented in points/README.md) and their place in the results
// database (results/results_db.hpp: a `runs` row for the build and a `tilesets` row whose
// text is the file, so `tilekit db list --table tilesets`, export and merge carry them).
//
//   TILEKIT-POINT-TILES 2    (format version: 1, or 2 for sets with edge colours)
//   method corner            (corner | wang | dual)
//   colors 4
//   edge_colors 2            (version 2 only; E, 1 in version 1)
//   points 64                (per tile)
//   rho 0.75
//   radius 0.050403...       (r on the unit tile; points at least 2r (1 + 1e-3) apart)
//   lloyd 0
//   seed 1
//   tiles 4096               (C^4 E^4 corner tiles, (4C)^4 dual, C^12 edge-based)
//   tile 0                   (then `points` lines "u v", tile coordinates in [0, 1)^2, y south)
//   0.123... 0.456...
//   ...
//   end
//   fnv1a64 0123456789abcdef (FNV-1a of every byte before this line)
#include <cstdint>
#include <string>

#include "points/poisson_tiles.hpp"

namespace tilekit {
class ResultsDb;
}

namespace tilekit::points {

std::string poisson_tiles_to_text(const PoissonTileSet& set);
// InputError naming `source` and the line for anything malformed, a format version newer than 2,
// a checksum mismatch, or a set whose points are not N per tile. Writes the oldest version that
// holds the set.
PoissonTileSet poisson_tiles_from_text(const std::string& text, const std::string& source);

void write_poisson_tiles(const std::string& path, const PoissonTileSet& set);  // atomically
// A file path, or `db:ID` for a tile set stored in the database at `db_path`.
PoissonTileSet read_poisson_tiles(const std::string& path, const std::string& db_path = "");

// The name a stored set gets: poisson-METHOD-C4-N64-rho0.75-seed1.
std::string poisson_tiles_name(const PoissonTileSet& set);
// Stores the set (idempotent by name and content hash) with a run row for its build; returns the
// tilesets row id.
std::int64_t store_poisson_tiles(ResultsDb& db, const PoissonTileSet& set, const std::string& text, int threads);

}  // namespace tilekit::points
