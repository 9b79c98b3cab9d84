#pragma once
// The search engine's public face (Gecode-style: models say what, the engine searches).
// One entry point, solve(), for packing and tiling problems on a torus or a bounded grid.
// INTERFACE CONTRACT shared by the CLI, the results database and the aperiodic engine;
// the solver owner may extend it (new fields with defaults) but not change what is here.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tilesets/tile_set.hpp"
#include "tilesets/tiling.hpp"

namespace tilekit {

enum class SearchMode { First, Count, All };

struct TilingProblem {
  TileSet set;          // the tiles that may be placed
  int rows = 0, cols = 0;
  bool torus = true;    // false: a bounded rows x cols rectangle (no wrap-around)
  bool packing = false; // true: every tile of the set exactly once (needs rows*cols == set.size())
};

// The default packing problem: the complete Wang or corner set over C colours on the C^2 x C^2 torus.
TilingProblem complete_packing_problem(TileKind kind, std::uint32_t colours);

struct SearchOptions {
  SearchMode mode = SearchMode::First;
  int threads = 1;
  std::uint64_t seed = 0;
  double time_limit = 0;             // seconds; 0 = none. Hitting it leaves `complete` false.
  std::string formulation = "auto";  // "cell", "pegs" (corner), "edges" (Wang) or "auto"
  int shard_index = 0, shard_count = 1;
  std::string checkpoint_path;       // write checkpoints here ("" = none)
  double checkpoint_every = 0;       // seconds between checkpoints (0 = only on signals)
  std::string resume_path;           // resume from this checkpoint ("" = fresh start)
  bool progress = false;             // progress bar / log lines on stderr
  // Called for every solution in All mode (and for the solution in First mode), one call at a
  // time (never concurrently), with the solution already checked by the validator.
  std::function<void(const Tiling&)> on_solution;
};

struct SearchResult {
  bool complete = false;     // the search space of this run/shard was exhausted: counts are final
  bool interrupted = false;  // stopped by a signal after writing the checkpoint (CLI exit 3)
  std::uint64_t solutions = 0;
  std::optional<std::uint64_t> orbits;  // solutions up to symmetry, when known
  std::uint64_t nodes = 0;
  double seconds = 0;
  int threads = 1;
  std::string formulation;   // the one actually used
  std::vector<Tiling> found; // First mode: the solution, if any
};

// Throws InputError for impossible problems/options (e.g. packing with rows*cols != tiles).
SearchResult solve(const TilingProblem& problem, const SearchOptions& options);

}  // namespace tilekit
