#pragma once
// Search under an imposed automorphism group: the entry point the CLI and the portfolio use.
// Same SearchOptions/SearchResult as solve() (solve.hpp); every solution passes the independent
// validator (tilesets/validator.hpp) and is checked to be invariant under the group.
//
// Modes: First runs options.threads independent restarting searches with different seeds
// (first found wins); Count and All enumerate the fundamental domain exhaustively on one thread
// (a count is the number of G-invariant solutions and does not depend on the thread count).
#include <atomic>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "solver/impose_group.hpp"
#include "solver/solve.hpp"

namespace tilekit {

struct SymmetricControl {
  const std::atomic<bool>* stop = nullptr;  // external first-found-wins flag (portfolio)
  std::uint64_t luby_unit = 0;              // nodes per Luby unit; 0 = automatic
  bool most_constrained = true;             // MCF branching (else scanline order)
  bool restarts = true;                     // First mode: Luby restarts (else one DFS)
  int pattern_sizes = 1 << 2;               // partial-pattern counts (SymmetricSearchConfig)
  bool sat = false;                         // First mode: CNF + cadical instead of the DFS
};

struct SymmetricResult {
  SearchResult result;
  nlohmann::json group;        // ImposedGroup::to_json()
  std::uint64_t restarts = 0;
  int sites = 0;               // variables of the fundamental domain
};

SymmetricResult solve_symmetric(const TilingProblem& problem, const ImposedGroup& group, const SearchOptions& options,
                                const SymmetricControl& control = {});

// Convenience: the complete packing problem of `kind` over C colours with a spec string.
// Throws InputError for a bad spec or group.
SymmetricResult solve_symmetric(TileKind kind, std::uint32_t colours, const std::string& spec,
                                const SearchOptions& options, const SymmetricControl& control = {});

// The group of a spec for a problem (packing rules when problem.packing).
ImposedGroup build_group(const TilingProblem& problem, const std::string& spec);

}  // namespace tilekit
