#include "aperiodic/generate.hpp"

#include <fmt/format.h>

#include <set>

#include "base/error.hpp"
#include "base/random.hpp"

namespace tilekit {

TileSet torus_with_decoys(int p, int q, int decoys, std::uint64_t seed) {
  if (p < 1 || q < 1 || decoys < 0) throw InputError(fmt::format("torus set: bad size {} x {} + {}", p, q, decoys));
  const std::uint64_t c = std::uint64_t(p) * std::uint64_t(q);
  if (c > 65535 || std::uint64_t(decoys) + c > c * c * c * c)
    throw InputError(fmt::format("torus set: {} x {} with {} decoys does not fit", p, q, decoys));
  std::vector<WangTile> tiles;
  std::set<WangTile> seen;
  auto colour = [q](int i, int j) { return Colour(i * q + j); };
  for (int i = 0; i < p; ++i)
    for (int j = 0; j < q; ++j) {
      WangTile t{colour(i, j), colour(i, (j + 1) % q), colour((i + 1) % p, j), colour(i, j)};
      tiles.push_back(t);
      seen.insert(t);
    }
  SplitMix64 rng(seed);
  while (tiles.size() < c + std::size_t(decoys)) {
    WangTile t{Colour(rng.below(c)), Colour(rng.below(c)), Colour(rng.below(c)), Colour(rng.below(c))};
    if (seen.insert(t).second) tiles.push_back(t);
  }
  return TileSet::wang(tiles, fmt::format("torus-{}x{}+{}", p, q, decoys),
                       fmt::format("{} x {} torus tiles and {} decoys (seed {})", p, q, decoys, seed), Colour(c),
                       Colour(c));
}

}  // namespace tilekit
