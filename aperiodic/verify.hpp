#pragma once
// `tilekit aperiodic verify SET`: is a tile set periodic? Searches, with the solver's
// tiling models (solve(), packing = false), for
//   - a periodic tiling: a p x q torus tiling for 1 <= p, q <= max_period (smallest area
//     first). A hit proves periodicity and is the witness;
//   - a tiling of the n x n square (bounded model, n = max_square): failure proves that the
//     set tiles nothing that large, hence not the plane ("cannot-tile").
// Shapes of area <= 16 go straight to the solver. For the larger ones the row/column
// transducer filter (aperiodic/rows.hpp) first rules out every shape whose
// horizontal or vertical period admits no infinite stack of periodic rows; only the
// remaining shapes go to the solver.
// Verdicts: periodic (witness), cannot-tile (largest tileable square), no-period-up-to P,
// or inconclusive when a time limit stopped a search before it was exhausted.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tilesets/tile_set.hpp"
#include "tilesets/tiling.hpp"

namespace tilekit {

struct VerifyOptions {
  int max_period = 8;      // torus shapes p x q, 1 <= p, q <= max_period
  int max_square = 0;      // bounded n x n square search (0: none)
  int threads = 0;         // 0: all (OpenMP); the torus shapes are searched in parallel
  double time_limit = 0;   // seconds for the whole verification (0: none); a hit leaves it incomplete
  bool progress = false;
  bool transducer_filter = true;  // false: every shape goes to the solver (baseline)
};

struct VerifyResult {
  std::string verdict;                   // "periodic", "cannot-tile", "no-period-up-to P", "inconclusive"
  std::optional<std::pair<int, int>> period;  // rows, cols of the witness torus
  std::vector<std::vector<std::int64_t>> witness;  // tile numbers (positions in the set)
  std::optional<Tiling> witness_tiling;  // the same, as tile indices (validated)
  int largest_square = -1;               // largest n <= max_square with an n x n tiling (-1: not searched)
  bool square_tileable = false;          // the max_square x max_square square has a tiling
  std::uint64_t nodes = 0;
  std::size_t shapes_searched = 0, shapes_incomplete = 0;
  // Shapes ruled out without search by the transducer filter (aperiodic/rows.hpp): no
  // tiling has horizontal period q for q in excluded_cols, nor vertical period p in excluded_rows.
  std::size_t shapes_excluded = 0;
  std::vector<int> excluded_cols, excluded_rows;
  std::vector<std::size_t> periodic_rows, periodic_cols;  // [q-1]: q-periodic rows/columns (0: over the limit)
  int threads = 1;
  double seconds = 0;
};

VerifyResult verify_tile_set(const TileSet& set, const VerifyOptions& opts);

}  // namespace tilekit
