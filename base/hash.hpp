#pragma once
// The one stable hash of the project: FNV-1a over bytes (Fowler, Noll, Vo), optionally followed
// by the MurmurHash3 64-bit finaliser so that nearby inputs spread over all 64 bits. Stable
// across runs, machines and standard libraries, so its values may be stored in files
// (checkpoint checksums, solution hashes, tile-set content hashes, run fingerprints).
#include <cstdint>
#include <string_view>

namespace tilekit {

class StableHash {
 public:
  // The n low bytes of v, least significant first (a fixed little-endian serialisation).
  StableHash& add(std::uint64_t v, int n = 8) {
    for (int i = 0; i < n; ++i) h_ = (h_ ^ ((v >> (8 * i)) & 0xff)) * kPrime;
    return *this;
  }
  StableHash& add(std::string_view text) {
    for (unsigned char c : text) h_ = (h_ ^ c) * kPrime;
    return *this;
  }
  // Plain FNV-1a.
  std::uint64_t fnv() const { return h_; }
  // FNV-1a, then the MurmurHash3 finaliser (fmix64).
  std::uint64_t mixed() const {
    std::uint64_t x = h_;
    x ^= x >> 33;
    x *= 0xff51afd7ed558ccdull;
    x ^= x >> 33;
    x *= 0xc4ceb9fe1a85ec53ull;
    x ^= x >> 33;
    return x;
  }

 private:
  static constexpr std::uint64_t kOffset = 0xcbf29ce484222325ull, kPrime = 0x100000001b3ull;
  std::uint64_t h_ = kOffset;
};

// FNV-1a of a text (checksums).
inline std::uint64_t fnv1a64(std::string_view text) { return StableHash().add(text).fnv(); }
// FNV-1a + finaliser of a text (identifiers).
inline std::uint64_t stable_hash64(std::string_view text) { return StableHash().add(text).mixed(); }

}  // namespace tilekit
