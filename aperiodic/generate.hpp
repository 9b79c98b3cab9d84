#pragma once
// Tile sets with a known answer, for tests and benchmarks of `aperiodic verify`.
//
// torus_with_decoys(p, q, d, seed): the p*q tiles T(i,j), i < p, j < q, whose colours encode their
// position (north (i,j), south (i+1,j), west (i,j), east (i,j+1), indices mod (p,q), colour
// (i,j) = i*q + j) tile the p x q torus and so the plane periodically; d further "decoy" tiles,
// drawn at random (seeded, base/random.hpp) over the same colours and distinct from the rest,
// may add tilings of their own but cannot take that one away. So every such set is periodic,
// whatever the decoys do: test sets with a known answer for the deciders.
#include <cstdint>

#include "tilesets/tile_set.hpp"

namespace tilekit {

// InputError unless p, q >= 1 and d <= the number of tiles left over the p*q colours.
TileSet torus_with_decoys(int p, int q, int decoys, std::uint64_t seed);

}  // namespace tilekit
