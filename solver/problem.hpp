#pragma once
// The engine's vocabulary: the problem a search is asked (TilingProblem), how it is asked
// (SearchOptions) and what it answers (SearchResult). solve.hpp runs them; the models, the
// parallel driver, the portfolio and the callers outside solver/ name them.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "solver/run_settings.hpp"
#include "solver/search_state.hpp"
#include "solver/search_stats.hpp"
#include "tilesets/tile_grid.hpp"
#include "tilesets/tile_set.hpp"

namespace tilekit {

enum class SearchMode { First, Count, All };

// How the engine models a search (solve.cpp's table of routes picks the model from it and the
// subspace): a tile per cell, a colour per peg (corner; window tori: a symbol per peg) or per
// edge (Wang), or CNF for cadical (with an imposed group, a lift or a window torus). Auto: the
// best measured one for the subspace.
enum class Formulation { Auto, Cell, Pegs, Edges, Sat };
// Its word: "auto", "cell", "pegs", "edges", "sat".
std::string_view formulation_name(Formulation f);
// The formulation a word names; none for another word.
std::optional<Formulation> formulation_from_name(std::string_view name);

struct TilingProblem {
  TileSet set;  // the tiles that may be placed
  int rows = 0, cols = 0;
  bool torus = true;     // false: a bounded rows x cols rectangle (no wrap-around)
  bool packing = false;  // true: every tile of the set exactly once (needs rows*cols == set.size())
};

// The default packing problem: the complete Wang or corner set over C colours on the C^2 x C^2
// torus. InputError for C outside 1..kMaxCompleteSetColours (tilesets/tile_set.hpp).
TilingProblem complete_packing_problem(TileKind kind, std::int64_t colours);

// A de Bruijn torus: every K x L window over C symbols once on the R x S torus
// (tilesets/window_torus.hpp). InputError naming the reason when the shape cannot hold them.
TilingProblem window_torus_problem(std::int64_t colours, int window_rows, int window_cols, int rows, int cols);

// Throws InputError when searching `p` needs a model larger than kMaxModelTable (the cell
// model's masks: 4 x edge labels x tiles/64 words), e.g. a corner packing over 40 colours. A
// command calls it before it touches any file; the models check again when they are built.
void check_searchable(const TilingProblem& p);

struct SearchOptions {
  // ---- what is searched ----
  SearchMode mode = SearchMode::First;
  // Search only the solutions invariant under this group (solver/impose_group.hpp SPEC, e.g.
  // "t=0,4:pi=1,2,3,0"); "" = no group. The model is then the fundamental domain
  // (solver/impose_model.hpp), formulation pegs/edges (or sat: the same subspace as CNF for
  // cadical, first mode only, no checkpoints), ordering "mrv" (default) or "static".
  std::string impose;
  unsigned impose_patterns = 4;  // partial-pattern counts under a group: bit k = size-k slot subsets
  // Colour-quotient lift SPEC (solver/colour_lift_model.hpp): search packings B + m*E of the
  // complete set; "" = none. Formulation auto (the engine), cell (tile per cell) or sat (cadical).
  std::string lift;
  bool count_orbits = true;  // Count/All on complete sets: also count orbits

  // ---- the model and the engine ----
  Formulation formulation = Formulation::Auto;
  std::string ordering = "auto";     // "static", "mrv" (most constrained first) or "auto"
  int restarts = -1;                 // First mode: Luby restarts; -1 auto (on for packings), 0 off, 1 on
  std::uint64_t restart_base = 0;    // nodes per Luby unit; 0 = auto
  std::size_t subproblems = 0;       // subproblem target for the split; 0 = auto (1024, at least 64 per shard)

  // ---- the run: threads, seed, limits, shard, checkpoints, progress, signals ----
  RunSettings run;

  // ---- reporting ----
  std::string title;                  // progress line prefix
  std::uint64_t estimate_probes = 0;  // Knuth tree-size probes before the search (progress/ETA)

  // ---- hooks ----
  // Called for every solution in All mode (and for the solution in First mode), one call at a
  // time (never concurrently), with the solution already checked by the validator.
  std::function<void(const Tiling&)> on_solution;
  std::function<void()> flush;  // called before every checkpoint (commit stored solutions)
  // Checkpoint I/O, injected because the file format lives in checkpoints/ (which depends on
  // solver/): use checkpoints/checkpoint.hpp `solve_checkpointed()`, which fills these from
  // run.checkpoint_path / run.resume_path. solve() itself rejects the paths without these hooks.
  std::function<void(const SearchState&)> save_checkpoint;
  std::optional<SearchState> resume_state;
};

struct SearchResult {
  // ---- how it ended ----
  bool complete = false;     // the search space of this run/shard was exhausted: counts are final
  bool interrupted = false;  // stopped by a signal after writing the checkpoint (CLI exit 3)
  bool timed_out = false;    // stopped by run.time_limit
  int signal = 0;            // the signal that interrupted the run

  // ---- what it found ----
  std::uint64_t solutions = 0;
  std::optional<std::uint64_t> orbits;  // solutions up to symmetry, when known
  std::uint64_t symmetry_order = 0;     // |translations x H| used for orbits (0: none)
  std::vector<Tiling> found;            // First mode: the solution, if any

  // ---- what it searched ----
  std::string formulation;        // the one actually used
  std::string ordering;           // the variable ordering actually used
  std::string fingerprint;        // what a checkpoint must match to resume this search
  std::string group;              // the imposed group's canonical spec ("" = none)
  std::uint64_t group_order = 0;  // its order (0 = none)
  int sites = 0;                  // variables of the fundamental domain under a group

  // ---- the work ----
  std::uint64_t nodes = 0;
  double seconds = 0;
  double total_seconds = 0;  // including the runs this one resumed
  int threads = 1;
  std::uint64_t subproblems = 0, shard_subproblems = 0, subproblems_done = 0;
  std::uint64_t restarts = 0;   // First mode with restarts
  double estimated_nodes = 0;   // Knuth estimate (when estimate_probes > 0; infinite beyond double's range)
  double estimated_log10_nodes = 0;  // the same as a logarithm
  std::uint64_t estimated_probes = 0;  // the probes made (fewer than asked when the time limit or a signal came)
  std::size_t checkpoints = 0;  // checkpoints written by this run
  SearchStats stats;            // this run's counters and time per phase (solver/search_stats.hpp)
};

}  // namespace tilekit
