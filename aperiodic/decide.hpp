#pragma once
// Deciding a tile set by the transducer method of Jeandel & Rao (2015/2021, "An aperiodic set of
// 11 Wang tiles", sec. 3): build T_1, T_2, ... (aperiodic/chain.hpp) for the rows and for the
// columns of the set, alternately (the cheaper chain grows next), until
//   - some T_k is empty: the set is FINITE (no infinite strip of k rows or columns); the proof
//     is k, with a bound on the largest tileable square (aperiodic/chain.hpp);
//   - some T_k has a cycle that reads and writes the same word: the set is PERIODIC; the cycle
//     is lifted to a k x W torus of tiles (k = a vertical period), reduced to its least periods
//     and checked by the independent validator (tilesets/validator.hpp);
//   - or the time limit, the memory budget, max_k or a stop ends the run: UNKNOWN at the k
//     reached, with the time each level took.
// Corner sets are decided through their equivalent Wang set (thesis 2.9, tile for tile).
// A periodic set is always found (at k = its least vertical or horizontal period) and a set
// that does not tile is always found finite, given time; an aperiodic set stays unknown.
//
// Long runs checkpoint the chains (aperiodic/decide_checkpoint.hpp): every checkpoint_every
// seconds, when the run stops and on SIGTERM/SIGINT/SIGUSR1 (with catch_signals; then
// `interrupted`), and resume from them.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/parallel.hpp"
#include "tilesets/tile_set.hpp"
#include "tilesets/tile_grid.hpp"

namespace tilekit {

struct DecideOptions {
  double time_limit = 10;         // seconds for the whole run; 0: none
  int max_k = 0;                  // stop after building T_max_k in each direction; 0: no bound
  bool rows = true, columns = true;  // which chains to build
  bool merge = true;              // bisimulation merges (false: trimming only)
  std::size_t memory_limit = 0;   // bytes for the transducers; 0: half the physical memory
  bool progress = false;          // ProgressReporter on stderr
  const StopToken* stop = nullptr;  // an outside stop: the run ends unknown ("stopped")
  bool catch_signals = false;     // SIGTERM/SIGINT/SIGUSR1: checkpoint and end interrupted
  std::string checkpoint_path;    // "" = no checkpoints
  double checkpoint_every = 300;  // seconds between checkpoints (with checkpoint_path)
  std::string resume_path;        // continue the run this checkpoint describes
};

struct DecideLevel {
  int k = 0;
  std::string direction;  // "rows" or "columns"
  std::uint64_t product_states = 0, product_transitions = 0, components = 0;
  std::uint64_t states = 0, transitions = 0;  // of T_k after trimming and merging
  double seconds = 0;
};

struct DecideResult {
  std::string verdict = "unknown";  // "periodic", "finite" or "unknown"
  std::string direction;            // the chain that decided: "rows" or "columns"
  int k = 0;                        // periodic/finite: the deciding k; unknown: the largest k built
  int k_rows = 0, k_columns = 0;    // levels built per direction
  std::string stopped_by;           // unknown: "time-limit", "memory", "max-k", "signal", "stopped"
  // finite: no square with a larger side is tileable (nullopt: the bound exceeds 2^64, see log10)
  std::optional<std::uint64_t> square_bound;
  double square_bound_log10 = 0;
  // periodic: rows x cols torus of tile numbers (positions in the set), validated
  std::vector<std::vector<std::int64_t>> witness;
  std::optional<Tiling> witness_tiling;  // the same as tile indices (colours relabelled if they overflow)
  bool witness_validated = false;        // checked by tilesets/validator.hpp (else by a direct edge check)
  int period_rows = 0, period_cols = 0;
  int shift = 0;  // periodic: the strip of k rows (columns) stacks on itself moved this far
  std::vector<DecideLevel> levels;  // in the order they were built
  std::size_t checkpoints = 0;
  bool resumed = false, interrupted = false;
  int signal = 0;
  double seconds = 0;  // this run (total_seconds: including the runs it resumed)
  double total_seconds = 0;
};

// Throws InputError for an empty set or bad options; a checkpoint that is corrupt or belongs to
// another set or options is an InputError naming what differs.
DecideResult decide_tile_set(const TileSet& set, const DecideOptions& opts);

// The Wang tiles a set is decided on: its own, or (corner sets) the equivalent Wang set.
std::vector<WangTile> decision_tiles(const TileSet& set);

// The smallest periods of a torus of tile numbers: the least p | rows and q | cols with
// grid[r][c] == grid[(r+p) % rows][(c+q) % cols]; returns the p x q corner of it.
std::vector<std::vector<std::int64_t>> least_period(const std::vector<std::vector<std::int64_t>>& grid);

// A torus of tile numbers as a Tiling of `set` (indices by thesis eq. 2.2/2.5). InputError when
// the set's colours make indices overflow 32 bits.
Tiling numbers_to_tiling(const TileSet& set, const std::vector<std::vector<std::int64_t>>& grid);

}  // namespace tilekit
