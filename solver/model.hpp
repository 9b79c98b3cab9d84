#pragma once
// What the engine needs from a model (Gecode: a model says variables, constraints and
// branching; the engine searches). Models are value types: every worker thread copies the
// prototype. Implementations: CellModel (tile per cell, any set), LatticeModel (pegs for
// corner tiles, edges for Wang tiles); a model over a fundamental domain under an imposed
// automorphism plugs in the same way.
//
//   int  branch(std::vector<int>& values)  // chooses the next variable and writes its
//                                           // candidate values in search order; -1 when all
//                                           // variables are assigned (a leaf = a solution);
//                                           // must be a function of the current assignment
//                                           // (and the value seed) only, so that a decision
//                                           // path replays to the same node.
//   bool assign(int var, int value)         // applies it; false when propagation fails
//                                           // (the engine still calls unassign)
//   void unassign(int var, int value)       // undoes the latest assign
//   void set_value_seed(std::uint64_t seed) // seeded value order (0 = natural order); only
//                                           // called at the root
//   Tiling tiling() const                   // at a leaf: the solution
//   std::uint64_t multiplicity() const      // solutions one leaf stands for (translations
//                                           // broken by the model)
#include <concepts>
#include <cstdint>
#include <vector>

#include "base/random.hpp"  // mix_seed
#include "tilesets/tile_grid.hpp"

namespace tilekit {

// The largest table a model builds (mask words, tile-index tables): 2^26 entries, at most 512 MiB.
// A larger one means colours or tiles far beyond anything searchable; it is refused up front
// (InputError) instead of ending in std::bad_alloc.
inline constexpr std::uint64_t kMaxModelTable = std::uint64_t(1) << 26;

template <class M>
concept SearchModel = std::copy_constructible<M> && requires(M m, const M cm, std::vector<int>& v, int x) {
  { m.branch(v) } -> std::convertible_to<int>;
  { m.assign(x, x) } -> std::convertible_to<bool>;
  m.unassign(x, x);
  m.set_value_seed(std::uint64_t{});
  { cm.tiling() } -> std::convertible_to<Tiling>;
  { cm.multiplicity() } -> std::convertible_to<std::uint64_t>;
};

}  // namespace tilekit
