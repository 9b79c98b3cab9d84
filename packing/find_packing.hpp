#pragma once
// One way to find a packing of the complete Wang or corner set over C colours, used by
// `tilekit pack`, `tilekit atlas lookup` and `texture atlas --db`: a validated packing from the
// results database, else a construction (closed forms, products, stored data:
// tilesets/constructions.hpp), else a search (the caller's, e.g. pack's checkpointed portfolio).
// Every answer is a packing the independent validator accepts (a stored one is re-checked;
// constructions are checked when `validate_construction`, otherwise the caller checks every tile
// once).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "tilesets/tile_grid.hpp"

namespace tilekit {

class ResultsDb;

struct FoundPacking {
  Tiling tiling;
  std::string source;            // "db", "construct" or "search"
  std::string how;               // construction name, "solution N in FILE", or the search's own words
  bool closed_form = false;      // constructions whose tile positions have a formula
  std::int64_t solution_id = 0;  // source "db"
};

struct PackingSources {
  ResultsDb* db = nullptr;            // look here first (nullptr: no database)
  bool construct = true;              // then the constructions
  bool validate_construction = true;  // run the validator on a construction (proven; the atlas
                                      // lookup skips it to answer in milliseconds)
  // Then this search (empty: none); nullopt when it found nothing.
  std::function<std::optional<FoundPacking>()> search;
};

// nullopt when no source has one. Throws InputError for C outside 1..255.
std::optional<FoundPacking> find_packing(TileKind kind, std::uint32_t colours, const PackingSources& sources);

// What `atlas lookup` (and `texture atlas --db`) ask for: find_packing without a search, the
// database at `db_path` first (opened read-only, never created; "" or a missing file: none),
// every answer validated. Throws NotFound (exit 1) naming the colour counts available and the
// search command that would store one, InputError for C outside 1..kMaxCompleteSetColours.
FoundPacking find_lookup_packing(TileKind kind, std::uint32_t colours, const std::string& db_path);

}  // namespace tilekit
