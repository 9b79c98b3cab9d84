#pragma once
// The search engine's public face (Gecode-style: models say what, the engine searches).
// One entry point, solve(), for packing and tiling problems on a torus or a bounded grid; the
// types it takes and returns are in problem.hpp.
#include <string>

#include "solver/problem.hpp"

namespace tilekit {

// Throws InputError for impossible problems/options (e.g. packing with rows*cols != tiles).
SearchResult solve(const TilingProblem& problem, const SearchOptions& options);

// The identity of a search for checkpoints: problem, mode, formulation, ordering, seed,
// restarts and shard (not threads, time limits or checkpoint settings). Throws like solve().
std::string search_fingerprint(const TilingProblem& problem, const SearchOptions& options);

}  // namespace tilekit
