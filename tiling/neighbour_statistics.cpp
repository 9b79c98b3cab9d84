#include "tiling/neighbour_statistics.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <mutex>

#include "base/error.hpp"
#include "base/parallel.hpp"
#include "tiling/halton_tiling.hpp"
#include "tiling/lattice_tiling.hpp"
#include "base/random.hpp"
#include "tilesets/tile_set.hpp"

namespace tilekit {

void NeighbourStatistics::merge(const NeighbourStatistics& o) {
  corners += o.corners;
  sum += o.sum;
  sum_squares += o.sum_squares;
  for (std::size_t k = 0; k < interior_histogram.size(); ++k) interior_histogram[k] += o.interior_histogram[k];
}

double NeighbourStatistics::mean() const {
  return corners ? double(sum) / double(corners) : 0.0;
}

double NeighbourStatistics::deviation() const {
  if (!corners) return 0.0;
  const double m = mean();
  return std::sqrt(std::max(0.0, double(sum_squares) / double(corners) - m * m));
}

void count_identical_neighbours(const std::uint16_t* colours, int rows, int cols, NeighbourStatistics& stats) {
  for (int r = 0; r < rows; ++r) {
    const std::uint16_t* row = colours + std::size_t(r) * cols;
    const std::uint16_t* up = r > 0 ? row - cols : nullptr;
    const std::uint16_t* down = r + 1 < rows ? row + cols : nullptr;
    for (int c = 0; c < cols; ++c) {
      const std::uint16_t v = row[c];
      unsigned n = 0;
      const bool left = c > 0, right = c + 1 < cols;
      if (left) n += row[c - 1] == v;
      if (right) n += row[c + 1] == v;
      if (up) n += (up[c] == v) + (left && up[c - 1] == v) + (right && up[c + 1] == v);
      if (down) n += (down[c] == v) + (left && down[c - 1] == v) + (right && down[c + 1] == v);
      stats.sum += n;
      stats.sum_squares += n * n;
      if (up && down && left && right) ++stats.interior_histogram[n];
    }
  }
  stats.corners += std::uint64_t(rows) * std::uint64_t(cols);
}

namespace {

// Identically coloured in-lattice neighbours of point (x, y) of a w x h lattice, by random access.
template <class Lattice>
unsigned neighbours_at(const Lattice& h, std::int64_t x, std::int64_t y, std::int64_t w, std::int64_t hgt) {
  const std::uint32_t v = h.colour(x, y);
  unsigned n = 0;
  for (std::int64_t dy = -1; dy <= 1; ++dy)
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      if ((dx == 0 && dy == 0) || x + dx < 0 || y + dy < 0 || x + dx >= w || y + dy >= hgt) continue;
      n += h.colour(x + dx, y + dy) == v;
    }
  return n;
}

void sample_neighbours(NeighbourAnalysis& out, NeighbourAlgo algo, HashKind hash, std::uint64_t seed,
                       std::uint64_t samples) {
  std::vector<std::uint64_t> ends;  // prefix sums of the corner counts
  std::uint64_t total = 0;
  for (const auto& r : out.resolutions) ends.push_back(total += std::uint64_t(r[0] + 1) * std::uint64_t(r[1] + 1));
  std::vector<std::uint64_t> picks(samples);
  SplitMix64 rng(derive_seed(seed, 0x5a));
  for (auto& p : picks) p = rng.below(total);
  std::sort(picks.begin(), picks.end());
  std::size_t next = 0;
  for (std::size_t t = 0; t < out.resolutions.size(); ++t) {
    const std::int64_t w = out.resolutions[t][0] + 1, h = out.resolutions[t][1] + 1;
    const std::uint64_t begin = t == 0 ? 0 : ends[t - 1];
    auto count = [&](const auto& lattice) {
      for (; next < picks.size() && picks[next] < ends[t]; ++next) {
        const std::uint64_t k = picks[next] - begin;
        const std::int64_t x = std::int64_t(k % std::uint64_t(w)), y = std::int64_t(k / std::uint64_t(w));
        const unsigned n = neighbours_at(lattice, x, y, w, h);
        out.stats.sum += n;
        out.stats.sum_squares += n * n;
        ++out.stats.corners;
        if (x > 0 && y > 0 && x + 1 < w && y + 1 < h) ++out.stats.interior_histogram[n];
      }
    };
    if (algo == NeighbourAlgo::Direct)
      count(ColourHash(hash, out.colours, derive_seed(seed, t + 1)));
    else
      count(HaltonColouring(out.colours, std::uint64_t(w), std::uint64_t(h)));
  }
}

}  // namespace

NeighbourAlgo parse_neighbour_algo(const std::string& name) {
  if (name == "direct") return NeighbourAlgo::Direct;
  if (name == "halton") return NeighbourAlgo::Halton;
  throw InputError(fmt::format("unknown algorithm '{}' for the neighbour analysis (expected direct or halton)", name));
}

NeighbourAnalysis analyze_neighbours(std::uint32_t colours, NeighbourAlgo algo, int tilings, int max_size,
                                     std::uint64_t seed, HashKind hash, const std::function<void(int, int)>& progress,
                                     std::uint64_t samples) {
  check_colour_count(colours);
  if (tilings < 1) throw RequestError("tilings", fmt::format("`tilings` must be at least 1, got {}", tilings));
  if (max_size < 1 || max_size > 65536)
    throw RequestError("max_size", fmt::format("`max_size` must be between 1 and 65536, got {}", max_size));
  NeighbourAnalysis out;
  out.colours = colours;
  SplitMix64 rng(seed);
  for (int t = 0; t < tilings; ++t)
    out.resolutions.push_back(
        {int(1 + rng.below(std::uint64_t(max_size))), int(1 + rng.below(std::uint64_t(max_size)))});
  if (samples > 0) {
    sample_neighbours(out, algo, hash, seed, samples);
    if (progress) progress(tilings, tilings);
    return out;
  }
  std::mutex mutex;
  int done = 0;
  parallel_for(tilings, resolve_threads(0), [&](std::int64_t t) {
    const int tx = out.resolutions[std::size_t(t)][0], ty = out.resolutions[std::size_t(t)][1];
    std::vector<std::uint16_t> lattice;
    if (algo == NeighbourAlgo::Direct)
      lattice =
          lattice_colours(ColourHash(hash, colours, derive_seed(seed, std::uint64_t(t) + 1)), 0, 0, ty + 1, tx + 1);
    else
      lattice =
          lattice_colours(HaltonColouring(colours, std::uint64_t(tx) + 1, std::uint64_t(ty) + 1), 0, 0, ty + 1, tx + 1);
    NeighbourStatistics s;
    count_identical_neighbours(lattice.data(), ty + 1, tx + 1, s);
    std::lock_guard<std::mutex> lock(mutex);
    out.stats.merge(s);
    ++done;
    if (progress) progress(done, tilings);
  });
  return out;
}

std::optional<PaperTable1Row> paper_table1(std::uint32_t colours) {
  // Schloemer & Deussen 2010, Table 1 (mean stochastic, mean ours, std. dev. stochastic, ours)
  static const PaperTable1Row rows[] = {{3.9970, 3.4967, 1.4142, 0.5857}, {2.6653, 2.1548, 1.3337, 0.6322},
                                        {1.9981, 1.5566, 1.2241, 0.6620}, {1.5981, 1.1536, 1.1311, 0.6965},
                                        {1.3328, 0.8032, 1.0536, 0.6720}, {1.1421, 0.6968, 0.9890, 0.6516},
                                        {0.9993, 0.6058, 0.9350, 0.6236}};
  if (colours < 2 || colours > 8) return std::nullopt;
  return rows[colours - 2];
}

}  // namespace tilekit
