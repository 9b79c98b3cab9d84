#pragma once
// Test fixture: a random valid patch of a Wang tile set, by randomised row-major
// backtracking (fixture only; the product searches with solver::solve()).
#include <algorithm>
#include <optional>
#include <random>
#include <vector>

#include "aperiodic/maps.hpp"

namespace tilekit::test {

inline std::optional<Patch> random_wang_patch(const std::vector<WangTile>& w, int rows, int cols, std::uint64_t seed,
                                              std::uint64_t max_nodes = 5'000'000) {
  std::mt19937_64 rng(seed);
  Patch p(rows, cols);
  const int n = rows * cols;
  const std::size_t cells = static_cast<std::size_t>(n);
  std::vector<std::vector<std::int64_t>> order(cells);
  std::vector<std::size_t> next(cells, 0);
  std::uint64_t nodes = 0;
  auto fits = [&](int cell, std::size_t k) {
    int r = cell / cols, c = cell % cols;
    if (c > 0 && w[std::size_t(p.at(r, c - 1))].e != w[k].w) return false;
    if (r > 0 && w[std::size_t(p.at(r - 1, c))].s != w[k].n) return false;
    return true;
  };
  int cell = 0;
  order[0].resize(w.size());
  for (std::size_t k = 0; k < w.size(); ++k) order[0][k] = std::int64_t(k);
  std::shuffle(order[0].begin(), order[0].end(), rng);
  while (cell < n) {
    if (++nodes > max_nodes) return std::nullopt;
    auto& o = order[std::size_t(cell)];
    bool placed = false;
    while (next[std::size_t(cell)] < o.size()) {
      std::size_t k = std::size_t(o[next[std::size_t(cell)]++]);
      if (fits(cell, k)) {
        p.cells[std::size_t(cell)] = std::int64_t(k);
        placed = true;
        break;
      }
    }
    if (placed) {
      ++cell;
      if (cell < n) {
        auto& o2 = order[std::size_t(cell)];
        o2.resize(w.size());
        for (std::size_t k = 0; k < w.size(); ++k) o2[k] = std::int64_t(k);
        std::shuffle(o2.begin(), o2.end(), rng);
        next[std::size_t(cell)] = 0;
      }
    } else {
      p.cells[std::size_t(cell)] = -1;
      if (cell == 0) return std::nullopt;
      --cell;
    }
  }
  return p;
}

}  // namespace tilekit::test
