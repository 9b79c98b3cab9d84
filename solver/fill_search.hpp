#pragma once
// Filling a map with the engine (`tilekit fill`): one region searched by ParallelSearch over
// FillModel (first mode, Luby restarts with seeded value orders, threads, the time limit,
// signals), and the map driver that fills W x H maps of any size block by block.
//
// The driver fills blocks of B x B cells in row-major order. Each block is a FillRegion whose
// cells next to filled cells (earlier blocks, the user's fixed cells, across the torus' wrap)
// start with the domains those neighbours allow, so every fill is valid across block borders.
// A block the engine cannot fill within `dives` restarts is retried as a larger region, the
// block grown by a margin into the cells filled before it (they are filled again), the margin
// doubling up to the whole map. Memory is the map (4 bytes a cell) plus one region's search.
// Each block's seed is derived from the run's seed and the block's number, so with one thread
// the map is a function of the request: a run resumed from its checkpoint (the map so far and
// the next block, written between blocks) ends with the same map as an uninterrupted one.
//
// When no fill is found, the driver looks for a proof: a small window around the user's fixed
// cells (or the whole map) whose search is exhausted without a fill, with nothing outside it
// constrained, so no map holding those fixed cells can be filled. That window is the region an
// impossible request names.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "solver/fill_model.hpp"
#include "solver/run_settings.hpp"
#include "solver/search_stats.hpp"

namespace tilekit {

struct FillSearchResult {
  bool found = false;
  bool complete = false;  // the region's whole tree was searched (not found: it has no fill)
  bool interrupted = false, timed_out = false;
  int signal = 0;
  Tiling tiling;  // found: the region's tiles
  std::uint64_t nodes = 0, restarts = 0;
  SearchStats stats;
};

// One region, first mode with restarts (at most `max_dives`, 0 = no bound). Uses run.threads,
// run.seed, run.time_limit, run.catch_signals and run.progress (checkpoints are the driver's).
FillSearchResult fill_region(const FillRegion& region, const RunSettings& run, std::uint64_t max_dives,
                             const std::string& title = "fill");

struct FillMapRequest {
  std::shared_ptr<const FillRules> rules;
  int rows = 0, cols = 0;
  bool torus = false;
  std::vector<int> fixed;  // rows*cols: a tile, or -1 for a free cell (empty: none fixed)
  int block = 0;           // block side; 0: the whole map up to 128 x 128 cells, else 64
  std::uint64_t dives = 64;  // restarts per attempt of one block before it grows
  // Every tile of the set at least once (a sheet holding the whole set); one block only. On a
  // torus without fixed cells tile 0 is placed at (0, 0): every such sheet has a translate with
  // it there, so a refutation covers every sheet of the size.
  bool cover = false;
  FillOrder order = FillOrder::Auto;  // which cell a dive fills next (solver/fill_model.hpp)
  RunSettings run;         // threads, seed, time limit, checkpoint/resume files and interval, signals
};

struct FillWindow {
  int row = 0, col = 0, rows = 0, cols = 0;  // top-left cell and size (wraps on a torus)
};

struct FillMapOutcome {
  bool found = false;
  bool proved_impossible = false;  // `window` has no fill holding its fixed cells
  bool interrupted = false, timed_out = false;
  int signal = 0;
  FillWindow window;          // not found: the proof's window, or the region that failed
  std::vector<int> map;       // rows*cols tiles (found), or the cells filled so far
  int blocks = 0, grown = 0;  // blocks filled; attempts that grew a block into its neighbours
  std::uint64_t nodes = 0, restarts = 0;
  double seconds = 0;
  bool resumed = false;
  std::size_t checkpoints = 0;
  SearchStats stats;
};

// InputError for a size outside 1..2^15 per side, a fixed cell out of range, or a checkpoint
// that is not this request's.
FillMapOutcome fill_map(const FillMapRequest& req);

// The proof search alone: is there a fill of `window` (of a rows x cols map, wrapping on a torus)
// holding the fixed cells inside it, with nothing outside constrained? Exhaustive up to
// `node_limit` nodes: 1 no fill (proved), 0 a fill exists, -1 undecided within the limit.
int fill_window_status(const std::shared_ptr<const FillRules>& rules, const std::vector<int>& fixed, int rows, int cols, bool torus,
                       const FillWindow& window, std::uint64_t node_limit);

}  // namespace tilekit
