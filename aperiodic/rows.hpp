#pragma once
// A necessary condition for periodic tilings, from the row transducer (Kari 1996, Culik
// 1996; also Jeandel-Rao's transducer method): a tiling with horizontal period q stacks
// q-periodic rows, i.e. closed walks of length q in the row transducer (states = E/W
// colours, one edge per tile). Let G_q be the graph whose vertices are words of q N/S
// colours and whose edges are those rows (north word -> south word). A tiling of the
// p x q torus is a closed walk of length p in G_q, so it needs G_q to have a cycle; if the
// recurrent part of G_q (vertices on or between cycles) is empty, no tiling of the plane
// has horizontal period q, for any vertical period. `aperiodic verify` uses this to skip
// torus shapes before it calls the solver; it never proves that a tiling exists.
#include <chrono>
#include <cstddef>
#include <vector>

#include "base/run_control.hpp"
#include "tilesets/tile.hpp"

namespace tilekit {

struct PeriodicRows {
  bool enumerated = false;    // false: more than max_rows rows; nothing is known
  std::size_t rows = 0;       // q-periodic rows up to rotation (closed walks of length q)
  std::size_t recurrent = 0;  // rows left after removing those with no row above or below
};

// q-periodic rows of a Wang set (rows = true) or columns (rows = false: the transposed set).
// Past `deadline` the enumeration stops with enumerated = false.
// With `catch_signals`, a caught signal (base/signals.hpp) stops it the same way.
PeriodicRows periodic_rows(const std::vector<WangTile>& tiles, int q, bool rows, std::size_t max_rows = 2'000'000,
                           const Deadline& deadline = {}, bool catch_signals = false);

}  // namespace tilekit
