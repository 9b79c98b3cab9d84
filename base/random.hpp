#pragma once
// A small seeded random number generator (SplitMix64, Steele et al. 2014) for the tiling
// algorithms: explicit seed, no global state, identical streams on every platform
// (std::uniform_int_distribution is not portable across standard libraries).
#include <cstdint>

namespace tilekit {

class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}

  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
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

}  // namespace tilekit
