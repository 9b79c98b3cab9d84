#pragma once
// Tile packings without search (issue "closed-form packings"). INTERFACE CONTRACT used by
// `tilekit pack --method construct|auto` and the atlas lookup; the owner may extend it.
//   - Wang, any C: outer product of two Eulerian circuits (thesis 5.5.1-5.5.2, Wei 2004).
//   - corner, odd C: de Bruijn sequence shifted by triangular numbers (DESIGN.md).
//   - corner, C = a*b with gcd(a,b) = 1: product of an a- and a b-packing (DESIGN.md).
//   - corner C = 2 (and 4 once found): packings found by the solver, stored as data.
#include <cstdint>
#include <optional>
#include <string>

#include "tilesets/tiling.hpp"

namespace tilekit {

struct ConstructedPacking {
  Tiling tiling;      // C^2 x C^2 torus packing of the complete set
  std::string how;    // e.g. "euler-product", "debruijn-triangular", "product 3x4", "stored"
};

// nullopt when no construction is known for this kind and C.
std::optional<ConstructedPacking> construct_packing(TileKind kind, std::uint32_t colours);

}  // namespace tilekit
