#pragma once
// `tilekit aperiodic verify SET`: is a tile set periodic, finite (tiles no large square), or
// neither so far? Two independent routes:
//   - transducer (aperiodic/decide.hpp): Jeandel & Rao's method. Decides every periodic set and
//     every finite set, given time; an aperiodic set stays unknown at the k reached;
//   - torus (aperiodic/torus.hpp): the solver's tiling models (solve(), packing = false) search
//     p x q tori, 1 <= p, q <= max_period, smallest area first (a hit is a periodic witness),
//     and with max_square an n x n square (failure proves the set finite).
// route "auto" runs the transducer route and, if it ends unknown before the time limit (max_k),
// the torus route with the time left; "both" runs the two within the time limit and checks them
// against each other. `route` in the result says which one answered. Every witness is checked
// by the independent validator; the time limit covers the whole run, every route included.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "aperiodic/decide.hpp"
#include "base/run_control.hpp"
#include "solver/search_stats.hpp"
#include "tilesets/tile_grid.hpp"
#include "tilesets/tile_set.hpp"

namespace tilekit {

struct VerifyOptions {
  std::string route = "auto";  // auto | transducer | torus | both
  double time_limit = 10;      // seconds for the whole run (every route); 0: none
  int threads = 0;             // 0: all (OpenMP); torus shapes are searched in parallel
  bool progress = false;
  // transducer route (its time_limit, stop and progress are set from the fields above)
  DecideOptions decide;
  // torus route
  int max_period = 8;      // torus shapes p x q, 1 <= p, q <= max_period
  int max_square = 0;      // bounded n x n square search (0: none)
  bool transducer_filter = true;  // false: every shape goes to the solver (baseline)
};

struct VerifyResult {
  // "periodic", "finite", "unknown" (transducer route), "no-period-up-to P" (torus route, every
  // shape up to P searched) or "inconclusive" (the time limit stopped a torus search)
  std::string verdict;
  std::string route;  // the route that answered: "transducer", "torus" (or "" when none decided)
  std::optional<std::pair<int, int>> period;        // rows, cols of the witness torus
  std::vector<std::vector<std::int64_t>> witness;  // tile numbers (positions in the set)
  std::optional<Tiling> witness_tiling;             // the same, as tile indices (validated)
  bool witness_validated = false;
  std::optional<DecideResult> transducer;  // the transducer route's run, when it ran
  std::string torus_verdict;               // the torus route's own verdict, when it ran
  // torus route
  int largest_square = -1;  // largest n <= max_square with an n x n tiling (-1: not searched)
  bool square_tileable = false;
  std::uint64_t nodes = 0;
  SearchStats stats;  // the torus searches' engine statistics, summed (solver/search_stats.hpp)
  std::size_t shapes_searched = 0, shapes_incomplete = 0;
  // Shapes ruled out without search by the transducer filter (aperiodic/rows.hpp): no
  // tiling has horizontal period q for q in excluded_cols, nor vertical period p in excluded_rows.
  std::size_t shapes_excluded = 0;
  std::vector<int> excluded_cols, excluded_rows;
  std::vector<std::size_t> periodic_rows, periodic_cols;  // [q-1]: q-periodic rows/columns (0: over the limit)
  int threads = 1;
  bool interrupted = false;  // a signal stopped the run (every route; the transducer's after its checkpoint)
  int signal = 0;            // the signal caught, when interrupted
  double seconds = 0;
};

VerifyResult verify_tile_set(const TileSet& set, const VerifyOptions& opts);

// The torus route alone, until `deadline` (aperiodic/torus.cpp).
VerifyResult torus_route(const TileSet& set, const VerifyOptions& opts, const Deadline& deadline);

}  // namespace tilekit
