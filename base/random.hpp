#pragma once
// The one seeded random number generator of the project (SplitMix64, Steele, Lea and Flood,
// OOPSLA 2014) and a shuffle of our own: explicit seeds, no global state, and identical
// streams on every platform and standard library (std::uniform_int_distribution and
// std::shuffle are not specified bit for bit, so a seed would name different results).
#include <cstdint>
#include <iterator>
#include <utility>

namespace tilekit {

// The SplitMix64 output function of x + golden gamma: a strong 64-bit mix, also the
// project's seeded hash for value orders and restart seeds.
constexpr std::uint64_t mix_seed(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}

  std::uint64_t next() {
    const std::uint64_t z = state_;
    state_ += 0x9e3779b97f4a7c15ull;
    return mix_seed(z);
  }

  // Uniform integer in [0, n), n >= 1, without modulo bias (Lemire 2019, multiply-shift with rejection).
  std::uint64_t below(std::uint64_t n) {
    for (;;) {
      unsigned __int128 m = static_cast<unsigned __int128>(next()) * n;
      auto low = static_cast<std::uint64_t>(m);
      if (low >= n || low >= (-n) % n) return static_cast<std::uint64_t>(m >> 64);
    }
  }

  // Uniform real in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  std::uint64_t state_;
};

// Mixes a seed and a stream number into an independent seed (for several tables from one seed).
inline std::uint64_t derive_seed(std::uint64_t seed, std::uint64_t stream) {
  SplitMix64 g(seed ^ (stream * 0xd1b54a32d192ed03ull));
  g.next();
  return g.next();
}

// Fisher-Yates shuffle (Knuth, TAOCP vol. 2, Algorithm P) driven by SplitMix64: the same
// permutation for the same seed with any standard library.
template <std::random_access_iterator It>
void shuffle(It first, It last, SplitMix64& rng) {
  const auto n = static_cast<std::uint64_t>(last - first);
  for (std::uint64_t i = n; i > 1; --i) {
    const auto j = rng.below(i);
    using std::swap;
    swap(first[static_cast<std::ptrdiff_t>(i - 1)], first[static_cast<std::ptrdiff_t>(j)]);
  }
}

}  // namespace tilekit
