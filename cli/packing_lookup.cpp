// lookup_with_database: packing/'s find_lookup_packing laid out by atlas/ (packing_lookup.hpp).
#include "cli/packing_lookup.hpp"

#include "packing/find_packing.hpp"

namespace tilekit::cli {

AtlasLookup lookup_with_database(TileKind kind, std::uint32_t colours, const std::string& db_path) {
  FoundPacking f = find_lookup_packing(kind, colours, db_path);
  // find_lookup_packing validated it (a stored packing and a construction alike).
  AtlasLookup a = lookup_from_packing(f.tiling, std::move(f.source), std::move(f.how), f.closed_form, false);
  a.solution_id = f.solution_id;
  return a;
}

}  // namespace tilekit::cli
