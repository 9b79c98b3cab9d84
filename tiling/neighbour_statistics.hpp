#pragma once
// Identically coloured neighbours of lattice corners (Schloemer & Deussen 2010, sec. 3.2,
// Table 1): for each corner of a tiling, the number of its 8 neighbours (inside the lattice)
// with its own colour; mean and RMS deviation over all corners of many tilings of random
// resolution. For i.i.d. uniform colours an interior corner's count is Binomial(8, 1/C).
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tiling/lattice_hash.hpp"

namespace tilekit {

struct NeighbourStatistics {
  std::uint64_t corners = 0;                          // all lattice points counted
  std::uint64_t sum = 0, sum_squares = 0;             // of the per-corner counts
  std::array<std::uint64_t, 9> interior_histogram{};  // counts of points with all 8 neighbours

  void merge(const NeighbourStatistics& o);
  double mean() const;
  double deviation() const;  // RMS deviation about the mean, pooled over all corners
};

// Adds the counts of a rows x cols lattice of colours (row-major) to `stats`.
void count_identical_neighbours(const std::uint16_t* colours, int rows, int cols, NeighbourStatistics& stats);

enum class NeighbourAlgo { Direct, Halton };
NeighbourAlgo parse_neighbour_algo(const std::string& name);  // "direct" | "halton"; InputError otherwise

struct NeighbourAnalysis {
  std::uint32_t colours = 0;
  NeighbourStatistics stats;
  std::vector<std::array<int, 2>> resolutions;  // [T_x, T_y] of each tiling
};

// The Table 1 protocol: `tilings` tilings of T_x x T_y tiles, T_x and T_y uniform in
// [1, max_size] (seeded), lattices of (T_x + 1) x (T_y + 1) corners, boundary corners counting
// their in-lattice neighbours. `direct` colours each lattice with a fresh ColourHash (seeded
// per tiling), `halton` with HaltonColouring. `progress(done, total)` is called after each tiling.
// With `samples` > 0, only that many corners are counted, drawn uniformly from all corners of
// all tilings (a tiling is hit in proportion to its size), each evaluated by random access:
// an unbiased estimate of the same pooled statistics, far faster than counting every corner.
NeighbourAnalysis analyze_neighbours(std::uint32_t colours, NeighbourAlgo algo, int tilings, int max_size,
                                     std::uint64_t seed, HashKind hash,
                                     const std::function<void(int, int)>& progress = {}, std::uint64_t samples = 0);

// Table 1 of the paper (mean and deviation, stochastic and Halton), for C = 2..8.
struct PaperTable1Row {
  double stochastic_mean, halton_mean, stochastic_deviation, halton_deviation;
};
std::optional<PaperTable1Row> paper_table1(std::uint32_t colours);

}  // namespace tilekit
