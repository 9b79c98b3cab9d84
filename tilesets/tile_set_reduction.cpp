#include "tilesets/tile_set_reduction.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "base/error.hpp"

namespace tilekit {

namespace {

void check_range(std::int64_t c, std::int64_t k) {
  check_colour_count(c);
  if (k < 0 || 2 * k > c)
    throw InputError(fmt::format("k disjoint colour pairs need 0 <= k <= C/2, got k={} for C={}", k, c));
}

std::int64_t pow4(std::int64_t v) {
  return v * v * v * v;
}

std::int64_t binom(std::int64_t n, std::int64_t r) {
  std::int64_t b = 1;
  for (std::int64_t i = 1; i <= r; ++i) b = b * (n - r + i) / i;
  return b;
}

}  // namespace

std::int64_t reduced_size_closed_form(std::int64_t c, std::int64_t k) {
  check_range(c, k);
  return pow4(c) - 2 * k * (6 * c * c - 12 * c - 6 * k + 13);  // paper sec. 3.3 / appendix A
}

std::int64_t reduced_size_inclusion_exclusion(std::int64_t c, std::int64_t k) {
  check_range(c, k);
  // appendix A: M_i = (C - i)^4 tiles lack i given colours (i <= 2k <= C here)
  auto m = [&](std::int64_t i) { return pow4(c - i); };
  // eq. (9): T_s = sum_{i=1..s} binom(s, i) (-1)^(i+1) M_i tiles lack at least one colour of S
  auto t = [&](std::int64_t s) {
    std::int64_t sum = 0;
    for (std::int64_t i = 1; i <= s; ++i) sum += binom(s, i) * ((i % 2) ? 1 : -1) * m(i);
    return sum;
  };
  // appendix A: N_k = sum_{p=1..k} binom(k, p) (-1)^(p+1) T_2p; N_0 = C^4
  if (k == 0) return pow4(c);
  std::int64_t n = 0;
  for (std::int64_t p = 1; p <= k; ++p) n += binom(k, p) * ((p % 2) ? 1 : -1) * t(2 * p);
  return n;
}

std::int64_t reduced_size_brute_force(std::uint32_t c, std::uint32_t k) {
  check_range(c, k);
  std::vector<ColourPair> pairs;
  for (std::uint32_t p = 0; p < k; ++p) pairs.emplace_back(2 * p, 2 * p + 1);
  return std::int64_t(reduced_corner_set(c, pairs).size());
}

TileSet reduced_corner_set(std::uint32_t c, const std::vector<ColourPair>& excluded) {
  check_colour_count(c);
  std::vector<CornerTile> tiles;
  for (TileIndex i = 0; i < complete_size(c, c); ++i) {
    const CornerTile t = corner_tile(i, c);
    const Colour cs[4] = {t.ne, t.se, t.sw, t.nw};
    auto holds = [&](Colour v) { return std::find(cs, cs + 4, v) != cs + 4; };
    bool keep = true;
    for (const auto& [a, b] : excluded)
      if (holds(a) && holds(b)) keep = false;
    if (keep) tiles.push_back(t);
  }
  return TileSet::corner(std::move(tiles), fmt::format("reduced-corner-{}", c),
                         fmt::format("complete corner set over {} colours without {} excluded colour pairs "
                                     "(Schloemer & Deussen 2010, sec. 3.3)",
                                     c, excluded.size()),
                         c);
}

std::vector<ColourPair> excluded_pairs(std::uint32_t c, const std::vector<ColourPair>& compatible) {
  std::set<ColourPair> ok;
  for (auto [a, b] : compatible) ok.insert({std::min(a, b), std::max(a, b)});
  std::vector<ColourPair> out;
  for (std::uint32_t a = 0; a < c; ++a)
    for (std::uint32_t b = a + 1; b < c; ++b)
      if (!ok.count({a, b})) out.emplace_back(a, b);
  return out;
}

}  // namespace tilekit
