#pragma once
// The atlas lookup of a packing that may come from a results database (`atlas lookup`, `atlas
// build`, `texture atlas --db`): packing/ finds it, atlas/ lays it out. The library of either
// stays without the other: atlas/ links no database and no search.
#include <cstdint>
#include <string>

#include "atlas/lookup.hpp"

namespace tilekit::cli {

// find_lookup_packing (packing/find_packing.hpp: the database at `db_path`, "" for none, then a
// construction; NotFound naming what is available) as an AtlasLookup.
AtlasLookup lookup_with_database(TileKind kind, std::uint32_t colours, const std::string& db_path);

}  // namespace tilekit::cli
