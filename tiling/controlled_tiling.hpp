#pragma once
// Controllable corner tiling (Schloemer & Deussen 2010, sec. 3.3, eq. 7): a colour probability
// map rho gives every lattice point a discrete distribution over the C colours, and the colour
// of lattice point (x, y) is a realisation of X(rho(x / T_x, y / T_y)). Each distribution is
// sampled in O(1) with Walker's alias method (Walker 1977); the random number of (x, y) comes
// from a position hash (the paper uses the long-period hash of [LD06b], thesis eq. 3.7), so a
// corner shared by neighbouring tiles gets the same colour when each tile is evaluated alone.
#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <utility>
#include <vector>

#include "tiling/lattice_hash.hpp"
#include "tiling/lattice_tiling.hpp"

namespace tilekit {

// A discrete colour probability map: rows x cols pixels, each a distribution over C colours.
// JSON file: {"colors": C, "rows": R, "cols": K, "p": [[[p_0, ..., p_{C-1}], ...K], ...R]}.
// Each pixel's probabilities are >= 0 and sum to 1 (within 1e-6; they are then renormalised).
struct ProbabilityMap {
  std::uint32_t colours = 0;
  int rows = 0, cols = 0;
  std::vector<double> p;  // (r * cols + c) * colours + colour

  const double* at(int r, int c) const { return p.data() + (std::size_t(r) * cols + c) * colours; }

  // A built-in map: a left-to-right ramp through the colours 0..C-1 in `cols` steps, each pixel
  // mixing only two consecutive colours (so colours two or more apart never share a tile when
  // the lattice is as fine as the map).
  static ProbabilityMap ramp(std::uint32_t colours, int rows, int cols);
};

// Throws InputError naming `origin` and the problem.
ProbabilityMap probability_map_from_json(const nlohmann::json& j, const std::string& origin);
ProbabilityMap read_probability_map(const std::string& path);
nlohmann::json probability_map_to_json(const ProbabilityMap& m);

// Walker's alias table for one distribution: sample(u) for u uniform in [0, 1) picks column
// j = floor(u C), then j itself if the fractional part is below U[j], else its alias V[j].
class AliasTable {
 public:
  AliasTable(const double* p, std::uint32_t colours);
  std::uint32_t sample(double u) const {
    const double s = u * double(u_.size());
    std::size_t j = std::size_t(s);
    if (j >= u_.size()) j = u_.size() - 1;
    return (s - double(j)) < u_[j] ? std::uint32_t(j) : v_[j];
  }
  const std::vector<double>& threshold() const { return u_; }
  const std::vector<std::uint32_t>& alias() const { return v_; }

 private:
  std::vector<double> u_;
  std::vector<std::uint32_t> v_;
};

// Uniform numbers in [0, 1) per lattice point from a 3-D lattice hash (thesis eq. 3.4 / 3.7):
// u(x, y) = sum_k h(x, y, k) R^-(k+1) with enough digits k for 32 bits of resolution. With one
// permutation table the digits depend on h(x, y) alone, so u takes only N distinct values.
class PositionRandom {
 public:
  PositionRandom(HashKind kind, std::uint64_t seed);
  double operator()(std::int64_t x, std::int64_t y) const;
  // The hash the digits come from: one 256-entry table (perm) or LongPeriodHash::thesis_tiling_hash,
  // seeded with derive_seed(seed, 11) or derive_seed(seed, 12).
  const std::vector<PermutationHash>& tables() const { return tables_; }
  std::uint32_t range() const { return range_; }
  int digits() const { return digits_; }

 private:
  std::vector<PermutationHash> tables_;
  std::uint32_t range_;
  int digits_;
};

class ControlledColouring {
 public:
  // A colouring of the lattice of a T_x x T_y tiling (tiling_cols x tiling_rows tiles).
  ControlledColouring(const ProbabilityMap& map, int tiling_rows, int tiling_cols, HashKind kind, std::uint64_t seed);

  std::uint32_t colours() const { return c_; }
  // eq. (7): the map pixel of lattice point (x, y), nearest to (x / T_x, y / T_y) (clamped).
  std::pair<int, int> pixel_of(std::int64_t x, std::int64_t y) const;
  std::uint32_t colour(std::int64_t x, std::int64_t y) const;
  double random(std::int64_t x, std::int64_t y) const { return rng_(x, y); }

  struct RowCache {
    std::int64_t x0 = 0;
    std::vector<int> pixel_col;
  };
  void prepare(RowCache& cache, std::int64_t x0, std::size_t n) const;
  void row(RowCache& cache, std::int64_t y, std::uint16_t* out) const;

  // Pairs of distinct colours (a < b) that can be corners of one tile of this tiling: some 2x2
  // window of lattice points has a point with p_a > 0 and another with p_b > 0 (the paper's
  // 8-neighbourhood scan, done on the sampled lattice so that it holds at any map resolution).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> compatible_pairs() const;

 private:
  std::uint32_t c_;
  int map_rows_, map_cols_;
  int tx_, ty_;
  std::vector<AliasTable> alias_;      // one per map pixel
  std::vector<std::uint8_t> support_;  // (pixel * C + colour) -> p > 0
  PositionRandom rng_;
};

// Corner tiling of rows x cols tiles from a probability map.
Tiling controlled_corner_tiling(const ProbabilityMap& map, int rows, int cols, HashKind kind, std::uint64_t seed);

}  // namespace tilekit
