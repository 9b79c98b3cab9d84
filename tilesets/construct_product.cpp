// Corner packings of C = a*b colours with gcd(a, b) = 1 from an a-packing A and a b-packing B
// P(r, c) = A(r mod a^2, c mod a^2) + a * B(r mod b^2, c mod b^2) on the a^2 b^2
// torus. By the Chinese remainder theorem (gcd(a^2, b^2) = 1) the cell (r, c) corresponds to
// one pair of cells of A and B, and the window at (r, c) is the digit-wise combination of the
// two windows there, so every window over ab colours occurs exactly once.
#include <cassert>

#include "tilesets/construct_internal.hpp"

namespace tilekit {

std::vector<Colour> corner_product_pegs(const std::vector<Colour>& pegs_a, std::uint32_t a,
                                        const std::vector<Colour>& pegs_b, std::uint32_t b) {
  const std::uint64_t na = std::uint64_t(a) * a, nb = std::uint64_t(b) * b, n = na * nb;
  assert(pegs_a.size() == na * na && pegs_b.size() == nb * nb);
  std::vector<Colour> pegs(n * n);
  for (std::uint64_t r = 0; r < n; ++r)
    for (std::uint64_t c = 0; c < n; ++c)
      pegs[r * n + c] = pegs_a[(r % na) * na + c % na] + a * pegs_b[(r % nb) * nb + c % nb];
  return pegs;
}

}  // namespace tilekit
