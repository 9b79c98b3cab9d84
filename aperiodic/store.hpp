#pragma once
// Writes aperiodic-engine results to the results database (tables tilesets, conversions,
// runs, solutions): tile sets by (name, content hash), conversions with their soundness
// label, and verify runs with the periodic witness as a solution.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "aperiodic/verify.hpp"
#include "results/results_db.hpp"
#include "tilesets/tile_set.hpp"

namespace tilekit {

// FNV-1a 64 of the tile-set file text: 16 hex digits, stable across runs and machines.
std::string tile_set_content_hash(const TileSet& set);

std::int64_t store_tile_set(ResultsDb& db, const TileSet& set);
std::int64_t store_conversion(ResultsDb& db, const TileSet& source, const TileSet& result, const std::string& method,
                              const std::string& soundness, const nlohmann::json& details);
// A run "aperiodic verify" with its parameters and verdict; the witness (if any) as a solution.
std::int64_t store_verify(ResultsDb& db, const TileSet& set, const VerifyResult& r, const nlohmann::json& params);

}  // namespace tilekit
