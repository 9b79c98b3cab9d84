#pragma once
// Reduced corner tile sets (Schloemer & Deussen 2010, sec. 3.3 and appendix A): when some pairs
// of colours can never be corners of the same tile, every tile holding such a pair can be left
// out of the set while every tiling the probability map allows stays possible.
#include <cstdint>
#include <utility>
#include <vector>

#include "tilesets/tile_set.hpp"

namespace tilekit {

using ColourPair = std::pair<std::uint32_t, std::uint32_t>;

// N_k = C^4 - 2k(6C^2 - 12C - 6k + 13): tiles left when k disjoint pairs are excluded,
// 0 <= k <= floor(C / 2) (paper sec. 3.3, appendix A). Throws InputError outside that range.
std::int64_t reduced_size_closed_form(std::int64_t c, std::int64_t k);
// The same count by the appendix's inclusion-exclusion: M_i = (C - i)^4 (tiles without i given
// colours), T_s = sum_{i=1..s} binom(s, i) (-1)^(i+1) M_i (eq. 9), N_k = sum_{p=1..k} binom(k, p)
// (-1)^(p+1) T_2p.
std::int64_t reduced_size_inclusion_exclusion(std::int64_t c, std::int64_t k);
// The same count by enumerating all C^4 tiles and dropping those holding both colours of one of
// the pairs (0,1), (2,3), ..., (2k-2, 2k-1).
std::int64_t reduced_size_brute_force(std::uint32_t c, std::uint32_t k);

// The corner tiles over C colours none of whose corners hold both colours of an excluded pair.
TileSet reduced_corner_set(std::uint32_t c, const std::vector<ColourPair>& excluded);
// The pairs a < b not in `compatible` (every pair of distinct colours, minus the compatible ones).
std::vector<ColourPair> excluded_pairs(std::uint32_t c, const std::vector<ColourPair>& compatible);

}  // namespace tilekit
