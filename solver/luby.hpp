#pragma once
// The Luby restart sequence 1,1,2,1,1,2,4,1,1,2,1,1,2,4,8,... (Luby, Sinclair, Zuckerman 1993,
// "Optimal speedup of Las Vegas algorithms"): restart i runs for luby(i) * base nodes.
#include <cstdint>
#include <limits>

namespace tilekit {

// luby(i) for every i >= 1 (luby(0) is taken as luby(1)). The largest term is 2^63, at
// i = 2^64 - 1; no shift ever reaches 64 bits, so a huge restart count from a checkpoint
// cannot make the loop run forever.
constexpr std::uint64_t luby(std::uint64_t i) {
  if (i == 0) i = 1;
  for (;;) {
    // k = the smallest k with 2^k - 1 >= i (k <= 64).
    int k = 1;
    while (k < 64 && (std::uint64_t(1) << k) - 1 < i) ++k;
    const std::uint64_t full = k == 64 ? std::numeric_limits<std::uint64_t>::max() : (std::uint64_t(1) << k) - 1;
    if (i == full) return std::uint64_t(1) << (k - 1);
    i -= (std::uint64_t(1) << (k - 1)) - 1;
  }
}

// luby(i) * base nodes, saturating instead of wrapping around.
constexpr std::uint64_t luby_limit(std::uint64_t i, std::uint64_t base) {
  const std::uint64_t l = luby(i);
  return base != 0 && l > std::numeric_limits<std::uint64_t>::max() / base ? std::numeric_limits<std::uint64_t>::max()
                                                                            : l * base;
}

static_assert(luby(1) == 1 && luby(2) == 1 && luby(3) == 2 && luby(7) == 4 && luby(8) == 1 && luby(15) == 8);
static_assert(luby(std::numeric_limits<std::uint64_t>::max()) == std::uint64_t(1) << 63);
static_assert(luby(std::uint64_t(1) << 63) == 1 && luby(0) == 1);
static_assert(luby_limit(std::numeric_limits<std::uint64_t>::max(), 2000) == std::numeric_limits<std::uint64_t>::max());

}  // namespace tilekit
