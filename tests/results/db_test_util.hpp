#pragma once
// Helpers shared by the results-database tests: small packings to store, file bytes.
#include <filesystem>
#include <string>

#include "results/results_db.hpp"
#include "tests/cli_runner.hpp"
#include "tilesets/tile_grid.hpp"

namespace tilekit::test {

// A distinct (not necessarily valid) 4x4 corner grid per `seed`, for storage tests.
inline Tiling numbered_grid(std::uint32_t seed) {
  Tiling t(TileKind::Corner, 2, 4, 4, true);
  for (std::size_t i = 0; i < t.cells.size(); ++i) t.cells[i] = TileIndex((seed * 7 + i * 3 + seed / 16) % 16);
  t.cells[0] = seed % 16;
  t.cells[1] = (seed / 16) % 16;
  t.cells[2] = (seed / 256) % 16;
  return t;
}

inline SolutionRecord record_of(const Tiling& t, std::string canonical = "") {
  SolutionRecord s;
  s.tiling = t;
  s.method = "test";
  s.canonical_hash = std::move(canonical);
  s.validated = false;
  return s;
}

inline bool exists(const std::string& p) { return std::filesystem::exists(p); }

}  // namespace tilekit::test
