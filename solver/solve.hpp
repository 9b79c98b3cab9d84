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

#include "solver/search_state.hpp"
#include "tilesets/tile_set.hpp"
#include "tilesets/tile_grid.hpp"

namespace tilekit {

enum class SearchMode { First, Count, All };

struct TilingProblem {
  TileSet set;  // the tiles that may be placed
  int rows = 0, cols = 0;
  bool torus = true;     // false: a bounded rows x cols rectangle (no wrap-around)
  bool packing = false;  // true: every tile of the set exactly once (needs rows*cols == set.size())
};

// The largest C for packings of the complete set: C^4 = 16.8 M tiles on a 4096 x 4096 torus
// (the largest atlas, atlas/lookup.hpp). Beyond it building the set alone took minutes and
// gigabytes before a search that could never end (issue 15); a construction of that size is
// also the largest atlas a GPU takes.
inline constexpr std::uint32_t kMaxPackingColours = 64;

// The default packing problem: the complete Wang or corner set over C colours on the C^2 x C^2
// torus. InputError for C outside 1..kMaxPackingColours.
TilingProblem complete_packing_problem(TileKind kind, std::int64_t colours);

// Throws InputError when searching `p` needs a model larger than kMaxModelTable (the cell
// model's masks: 4 x edge labels x tiles/64 words), e.g. a corner packing over 40 colours. A
// command calls it before it touches any file; the models check again when they are built.
void check_searchable(const TilingProblem& p);

struct SearchOptions {
  SearchMode mode = SearchMode::First;
  int threads = 1;
  std::uint64_t seed = 0;
  double time_limit = 0;             // seconds; 0 = none. Hitting it leaves `complete` false.
  std::string formulation = "auto";  // "cell", "pegs" (corner), "edges" (Wang) or "auto"; "sat" with lift
  int shard_index = 0, shard_count = 1;
  std::string checkpoint_path;  // write checkpoints here ("" = none)
  double checkpoint_every = 0;  // seconds between checkpoints (0 = only on signals)
  std::string resume_path;      // resume from this checkpoint ("" = fresh start)
  bool progress = false;        // progress bar / log lines on stderr
  // Called for every solution in All mode (and for the solution in First mode), one call at a
  // time (never concurrently), with the solution already checked by the validator.
  std::function<void(const Tiling&)> on_solution;

  // ---- extensions (solver owner) ----
  std::string ordering = "auto";      // "static", "mrv" (most constrained first) or "auto"
  int restarts = -1;                  // First mode: Luby restarts; -1 auto (on for packings), 0 off, 1 on
  std::uint64_t restart_base = 0;     // nodes per Luby unit; 0 = auto
  std::size_t subproblems = 0;        // subproblem target for the split; 0 = auto (1024, at least 64 per shard)
  std::uint64_t estimate_probes = 0;  // Knuth tree-size probes before the search (progress/ETA)
  bool catch_signals = false;         // SIGTERM/SIGINT/SIGUSR1 stop the search (result.interrupted)
  bool count_orbits = true;           // Count/All on complete sets: also count orbits
  std::string title;                  // progress line prefix
  std::string lift;                   // colour-quotient lift SPEC (solver/colour_lift_model.hpp, issue 11):
                                      // search packings B + m*E of the complete set; "" = none.
                                      // Formulation "auto" (the engine) or "sat" (cadical)
  // Checkpoint I/O, injected because the file format lives in checkpoints/ (which depends on
  // solver/): use checkpoints/checkpoint.hpp `solve_checkpointed()`, which fills these from
  // checkpoint_path / resume_path. solve() itself rejects the paths without these hooks.
  std::function<void(const SearchState&)> save_checkpoint;
  std::optional<SearchState> resume_state;
  std::function<void()> flush;  // called before every checkpoint (commit stored solutions)

  // ---- imposed groups (issue 11: one engine) ----
  // Search only the solutions invariant under this group (solver/impose_group.hpp SPEC, e.g.
  // "t=0,4:pi=1,2,3,0"); "" = no group. The model is then the fundamental domain
  // (solver/impose_model.hpp), formulation "pegs"/"edges" (or "sat": the same subspace as CNF
  // for cadical, first mode only, no checkpoints), ordering "mrv" (default) or "static".
  std::string impose;
  unsigned impose_patterns = 4;  // partial-pattern counts under a group: bit k = size-k slot subsets
};

struct SearchResult {
  bool complete = false;     // the search space of this run/shard was exhausted: counts are final
  bool interrupted = false;  // stopped by a signal after writing the checkpoint (CLI exit 3)
  std::uint64_t solutions = 0;
  std::optional<std::uint64_t> orbits;  // solutions up to symmetry, when known
  std::uint64_t nodes = 0;
  double seconds = 0;
  int threads = 1;
  std::string formulation;    // the one actually used
  std::vector<Tiling> found;  // First mode: the solution, if any

  // ---- extensions (solver owner) ----
  bool timed_out = false;  // stopped by time_limit
  int signal = 0;          // the signal that interrupted the run
  std::string ordering;    // the variable ordering actually used
  std::uint64_t subproblems = 0, shard_subproblems = 0, subproblems_done = 0;
  std::uint64_t restarts = 0;        // First mode with restarts
  double estimated_nodes = 0;        // Knuth estimate (when estimate_probes > 0)
  std::size_t checkpoints = 0;       // checkpoints written by this run
  double total_seconds = 0;          // including the runs this one resumed
  std::uint64_t symmetry_order = 0;  // |translations x H| used for orbits (0: none)
  std::string fingerprint;           // what a checkpoint must match to resume this search
  std::string group;                 // the imposed group's canonical spec ("" = none)
  std::uint64_t group_order = 0;     // its order (0 = none)
  int sites = 0;                     // variables of the fundamental domain under a group
};

// Throws InputError for impossible problems/options (e.g. packing with rows*cols != tiles).
SearchResult solve(const TilingProblem& problem, const SearchOptions& options);

// The identity of a search for checkpoints: problem, mode, formulation, ordering, seed,
// restarts and shard (not threads, time limits or checkpoint settings). Throws like solve().
std::string search_fingerprint(const TilingProblem& problem, const SearchOptions& options);

}  // namespace tilekit
