#include "tiling/controlled_tiling.hpp"

#include <fmt/format.h>

#include <bitset>
#include <cmath>
#include <nlohmann/json.hpp>

#include "base/error.hpp"
#include "base/json_input.hpp"
#include "base/random.hpp"

namespace tilekit {

ProbabilityMap ProbabilityMap::ramp(std::uint32_t colours, int rows, int cols) {
  if (colours < 1 || colours > 255) throw InputError(fmt::format("colours must be between 1 and 255, got {}", colours));
  if (rows < 1 || cols < 1) throw InputError("a probability map needs at least one pixel");
  ProbabilityMap m{colours, rows, cols, std::vector<double>(std::size_t(rows) * cols * colours, 0.0)};
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const double t = cols == 1 ? 0.0 : double(c) / double(cols - 1) * double(colours - 1);
      std::uint32_t j = std::min(std::uint32_t(t), colours - 1);
      const double f = t - double(j);
      double* p = m.p.data() + (std::size_t(r) * cols + c) * colours;
      p[j] += 1.0 - f;
      if (f > 0 && j + 1 < colours) p[j + 1] += f;
    }
  return m;
}

ProbabilityMap probability_map_from_json(const nlohmann::json& doc, const std::string& origin) {
  const JsonIn j(doc, origin);
  j.object();
  ProbabilityMap m;
  m.colours = std::uint32_t(j.at("colors").integer(1, 255));
  m.rows = int(j.at("rows").integer(1, 4096));
  m.cols = int(j.at("cols").integer(1, 4096));
  // Sizes are checked row by row against the document before anything is stored, so a header
  // promising 4096x4096x255 probabilities allocates nothing it does not hold.
  const JsonIn p = j.at("p");
  p.array(std::size_t(m.rows), std::size_t(m.rows));
  for (int r = 0; r < m.rows; ++r) {
    const JsonIn row = p[std::size_t(r)];
    row.array(std::size_t(m.cols), std::size_t(m.cols));
    for (int c = 0; c < m.cols; ++c) {
      const JsonIn px = row[std::size_t(c)];
      px.array(m.colours, m.colours);
      double sum = 0;
      const std::size_t first = m.p.size();
      for (std::uint32_t k = 0; k < m.colours; ++k) {
        m.p.push_back(px[k].number(0, 1));
        sum += m.p.back();
      }
      if (std::abs(sum - 1.0) > 1e-6) throw px.error(fmt::format("probabilities sum to {}, not 1", sum));
      for (std::size_t k = first; k < m.p.size(); ++k) m.p[k] /= sum;
    }
  }
  return m;
}

ProbabilityMap read_probability_map(const std::string& path) {
  return probability_map_from_json(read_json_file(path, "probability map"), path);
}

nlohmann::json probability_map_to_json(const ProbabilityMap& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < m.rows; ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (int c = 0; c < m.cols; ++c) row.push_back(std::vector<double>(m.at(r, c), m.at(r, c) + m.colours));
    rows.push_back(std::move(row));
  }
  return {{"colors", m.colours}, {"rows", m.rows}, {"cols", m.cols}, {"p", rows}};
}

AliasTable::AliasTable(const double* p, std::uint32_t colours) : u_(colours, 1.0), v_(colours) {
  // Walker (1977), in Vose's stable form: scale to mean 1, pair each small column with a
  // large one that tops it up to 1 and becomes its alias.
  std::vector<double> q(colours);
  std::vector<std::uint32_t> small, large;
  for (std::uint32_t c = 0; c < colours; ++c) {
    q[c] = p[c] * colours;
    v_[c] = c;
    (q[c] < 1.0 ? small : large).push_back(c);
  }
  while (!small.empty() && !large.empty()) {
    std::uint32_t s = small.back(), l = large.back();
    small.pop_back();
    u_[s] = q[s];
    v_[s] = l;
    q[l] = (q[l] + q[s]) - 1.0;
    if (q[l] < 1.0) {
      large.pop_back();
      small.push_back(l);
    }
  }
  // what is left is 1 up to rounding: keep those columns whole, unless their mass is zero
  for (std::uint32_t c : small) u_[c] = p[c] > 0 ? 1.0 : 0.0;
  for (std::uint32_t c : large) u_[c] = 1.0;
  // a column without mass must always defer to its alias
  for (std::uint32_t c = 0; c < colours; ++c)
    if (p[c] <= 0 && v_[c] == c) {
      for (std::uint32_t d = 0; d < colours; ++d)
        if (p[d] > 0) {
          v_[c] = d;
          break;
        }
      u_[c] = 0.0;
    }
}

PositionRandom::PositionRandom(HashKind kind, std::uint64_t seed) {
  if (kind == HashKind::Permutation) {
    tables_.emplace_back(256, derive_seed(seed, 11));
    range_ = 256;
  } else {
    const LongPeriodHash h = LongPeriodHash::thesis_tiling_hash(derive_seed(seed, 12));
    tables_ = h.tables();
    range_ = h.range();  // the final modulo divisor is the first table (size 24)
  }
  digits_ = 1;
  for (double span = range_; span < 4294967296.0; span *= range_) ++digits_;
}

double PositionRandom::operator()(std::int64_t x, std::int64_t y) const {
  // u = sum_k h(x, y, k) R^-(k+1) with h the 3-D hash of eq. (3.4) / (3.7). The inner part
  // P_i[(P_i[x % N_i] + y) % N_i] of each table does not depend on k: it is looked up once.
  std::uint32_t inner[8];
  const std::size_t m = tables_.size();
  for (std::size_t i = 0; i < m; ++i) inner[i] = tables_[i](x, y);
  double u = 0, scale = 1.0 / range_;
  for (int k = 0; k < digits_; ++k) {
    std::uint32_t sum = 0;
    for (std::size_t i = 0; i < m; ++i) {
      const PermutationHash& t = tables_[i];
      const std::uint32_t s = inner[i] + std::uint32_t(k) % t.size();
      sum += t.table()[s >= t.size() ? s - t.size() : s];
    }
    u += double(sum % range_) * scale;
    scale /= range_;
  }
  return u;
}

ControlledColouring::ControlledColouring(const ProbabilityMap& map, int tiling_rows, int tiling_cols, HashKind kind,
                                         std::uint64_t seed)
    : c_(map.colours), map_rows_(map.rows), map_cols_(map.cols), tx_(tiling_cols), ty_(tiling_rows), rng_(kind, seed) {
  if (tiling_rows < 1 || tiling_cols < 1) throw InputError("a controlled tiling needs at least one tile");
  alias_.reserve(std::size_t(map.rows) * map.cols);
  support_.resize(std::size_t(map.rows) * map.cols * c_);
  for (int r = 0; r < map.rows; ++r)
    for (int c = 0; c < map.cols; ++c) {
      alias_.emplace_back(map.at(r, c), c_);
      for (std::uint32_t k = 0; k < c_; ++k) support_[(std::size_t(r) * map.cols + c) * c_ + k] = map.at(r, c)[k] > 0;
    }
}

std::pair<int, int> ControlledColouring::pixel_of(std::int64_t x, std::int64_t y) const {
  // eq. (7): rho(x / T_x, y / T_y), nearest pixel; round(u (K - 1)) in integers
  auto nearest = [](std::int64_t v, std::int64_t t, int k) {
    v = std::clamp<std::int64_t>(v, 0, t);
    return int((2 * v * (k - 1) + t) / (2 * t));
  };
  return {nearest(y, ty_, map_rows_), nearest(x, tx_, map_cols_)};
}

std::uint32_t ControlledColouring::colour(std::int64_t x, std::int64_t y) const {
  auto [r, c] = pixel_of(x, y);
  return alias_[std::size_t(r) * map_cols_ + c].sample(rng_(x, y));
}

void ControlledColouring::prepare(RowCache& cache, std::int64_t x0, std::size_t n) const {
  cache.x0 = x0;
  cache.pixel_col.resize(n);
  for (std::size_t k = 0; k < n; ++k) cache.pixel_col[k] = pixel_of(x0 + std::int64_t(k), 0).second;
}

void ControlledColouring::row(RowCache& cache, std::int64_t y, std::uint16_t* out) const {
  const int r = pixel_of(cache.x0, y).first;
  for (std::size_t k = 0; k < cache.pixel_col.size(); ++k) {
    const std::int64_t x = cache.x0 + std::int64_t(k);
    out[k] = std::uint16_t(alias_[std::size_t(r) * map_cols_ + cache.pixel_col[k]].sample(rng_(x, y)));
  }
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> ControlledColouring::compatible_pairs() const {
  using Mask = std::bitset<256>;
  auto support = [&](std::int64_t x, std::int64_t y) {
    auto [r, c] = pixel_of(x, y);
    Mask m;
    const std::uint8_t* s = support_.data() + (std::size_t(r) * map_cols_ + c) * c_;
    for (std::uint32_t k = 0; k < c_; ++k)
      if (s[k]) m.set(k);
    return m;
  };
  std::vector<Mask> partners(c_);
  for (std::int64_t y = 0; y < ty_; ++y)
    for (std::int64_t x = 0; x < tx_; ++x) {
      const Mask m[4] = {support(x, y), support(x + 1, y), support(x, y + 1), support(x + 1, y + 1)};
      for (int i = 0; i < 4; ++i) {
        Mask others;
        for (int j = 0; j < 4; ++j)
          if (j != i) others |= m[j];
        for (std::uint32_t a = 0; a < c_; ++a)
          if (m[i][a]) partners[a] |= others;
      }
    }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (std::uint32_t a = 0; a < c_; ++a)
    for (std::uint32_t b = a + 1; b < c_; ++b)
      if (partners[a][b]) out.emplace_back(a, b);
  return out;
}

Tiling controlled_corner_tiling(const ProbabilityMap& map, int rows, int cols, HashKind kind, std::uint64_t seed) {
  ControlledColouring h(map, rows, cols, kind, seed);
  return lattice_corner_tiling(h, rows, cols);
}

}  // namespace tilekit
