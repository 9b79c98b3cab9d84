// Tiling throughput (thesis ch. 3; Schloemer & Deussen 2010), one thread, one JSON line per case.
// Every case is timed alternately with a baseline loop writing (x ^ y) & mask into the same
// buffer, and reports medians of both and their ratio (goal for the direct corner tiling:
// within 2x of the baseline). Usage: build/bench_tiling [--size N] [--reps R] [--only NAME-PREFIX]
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "bench/bench_common.hpp"
#include "tilesets/compact_sets.hpp"
#include "tilesets/tile_set.hpp"
#include "tiling/controlled_tiling.hpp"
#include "tiling/direct_tiling.hpp"
#include "tiling/halton_tiling.hpp"
#include "tiling/scanline_tiling.hpp"

using namespace tilekit;
using tilekit::bench::median_midpoint;
using tilekit::bench::seconds_of;

namespace {

// Keeps the compiler from dropping stores into `p`.
inline void escape(const void* p) {
  asm volatile("" : : "g"(p) : "memory");
}

// The same lattice without x_period(): every tile of every row is evaluated.
struct EveryTile {
  const ColourHash& h;
  using RowCache = ColourHash::RowCache;
  std::uint32_t colours() const { return h.colours(); }
  std::uint32_t colour(std::int64_t x, std::int64_t y) const { return h.colour(x, y); }
  void prepare(RowCache& c, std::int64_t x0, std::size_t n) const { h.prepare(c, x0, n); }
  void row(RowCache& c, std::int64_t y, std::uint16_t* out) const { h.row(c, y, out); }
};

struct Bench {
  int size = 4096, reps = 7;
  std::string only;  // run only the cases whose name starts with this
  std::vector<TileIndex> buffer;

  void baseline(TileIndex mask) {
    TileIndex* out = buffer.data();
    const int n = size;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) out[std::size_t(y) * std::size_t(n) + std::size_t(x)] = TileIndex(x ^ y) & mask;
    escape(out);
  }

  // Runs `fill` (which writes rows x cols tiles into buffer) and the baseline alternately.
  void run(const std::string& name, std::uint32_t colours, int rows, int cols, const std::function<void()>& fill,
           int reps_override = 0, int threads = 1) {
    if (name.rfind(only, 0) != 0) return;
    const int reps_here = reps_override ? reps_override : reps;
    std::vector<double> t_case, t_base;
    fill();  // warm-up (tables, page faults)
    baseline(255);
    for (int r = 0; r < reps_here; ++r) {
      t_case.push_back(seconds_of(fill));
      escape(buffer.data());
      t_base.push_back(seconds_of([&] { baseline(255); }));
    }
    const double tiles = double(rows) * double(cols), mc = median_midpoint(t_case), mb = median_midpoint(t_base);
    // each repetition's case time against the baseline timed right after it (robust to load changes)
    std::vector<double> paired;
    for (std::size_t r = 0; r < t_case.size(); ++r)
      paired.push_back(t_case[r] / (t_base[r] / (double(size) * double(size)) * tiles));
    // the baseline always writes the full size x size buffer; scale it to this case's tile count
    const double base_per_tile = mb / (double(size) * double(size));
    nlohmann::json j = {{"bench", "tiling"},
                        {"case", name},
                        {"colors", colours},
                        {"grid", fmt::format("{}x{}", cols, rows)},
                        {"threads", threads},
                        {"cores", std::thread::hardware_concurrency()},
                        {"reps", reps_here},
                        {"median_seconds", mc},
                        {"tiles_per_second", tiles / mc},
                        {"baseline_median_seconds", base_per_tile * tiles},
                        {"baseline_tiles_per_second", 1.0 / base_per_tile},
                        {"ratio_to_baseline", mc / (base_per_tile * tiles)},
                        {"median_paired_ratio", median_midpoint(paired)}};
    fmt::print("{}\n", j.dump());
    std::fflush(stdout);
  }
};

}  // namespace

int main(int argc, char** argv) {
  Bench b;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--size")) b.size = std::max(16, std::atoi(argv[i + 1]));
    if (!std::strcmp(argv[i], "--reps")) b.reps = std::max(1, std::atoi(argv[i + 1]));
    if (!std::strcmp(argv[i], "--only")) b.only = argv[i + 1];
  }
  const int n = b.size;
  b.buffer.assign(std::size_t(n) * std::size_t(n), 0);
  TileIndex* out = b.buffer.data();

  for (std::uint32_t c : {2u, 3u, 4u})
    for (HashKind h : {HashKind::Permutation, HashKind::LongPeriod}) {
      const DirectCornerTiling a(c, h, 1);
      b.run(fmt::format("direct-corner/{}", hash_kind_name(h)), c, n, n, [&] { a.fill(0, 0, n, n, out); });
      if (h == HashKind::LongPeriod)  // rows in parallel (the baseline stays one thread)
        b.run(
            "direct-corner/long-period/2-threads", c, n, n, [&] { a.fill(0, 0, n, n, out, 2); }, 0, 2);
      if (h == HashKind::Permutation) {
        const EveryTile every{a.hash()};
        b.run("direct-corner/perm/every-tile-evaluated", c, n, n,
              [&] { fill_lattice_corner_tiles(every, 0, 0, n, n, out); });
      }
    }
  for (HashKind h : {HashKind::Permutation, HashKind::LongPeriod}) {
    const DirectWangTiling w(3, 3, h, 1);
    b.run(fmt::format("direct-wang-two-hashes/{}", hash_kind_name(h)), 3, n, n, [&] { w.fill(0, 0, n, n, out); });
    const DirectEdgeWangTiling e(3, 3, h, 1);
    b.run(fmt::format("direct-edge-wang/{}", hash_kind_name(h)), 3, n, n, [&] { e.fill(0, 0, n, n, out); });
    const DirectCompactWangTiling k(3, h, 1);
    b.run(fmt::format("direct-compact-wang/{}", hash_kind_name(h)), 3, n, n, [&] { k.fill(0, 0, n, n, out); });
  }
  {
    const HaltonCornerTiling hal(3, n, n);
    b.run("halton-corner", 3, n, n, [&] { hal.fill(out); });
  }
  {
    const TileSet wang = compact_wang_set(3), corner = compact_corner_set(3);
    b.run(
        "scanline-wang/compact-wang-3", 3, n, n,
        [&] {
          Tiling t = scanline_wang_tiling(wang, n, n, 1);
          std::memcpy(out, t.cells.data(), t.cells.size() * sizeof(TileIndex));
        },
        3);
    b.run(
        "scanline-corner/compact-corner-3", 3, n, n,
        [&] {
          Tiling t = scanline_corner_tiling(corner, n, n, 1);
          std::memcpy(out, t.cells.data(), t.cells.size() * sizeof(TileIndex));
        },
        3);
  }
  {
    const int m = std::min(n, 1024);
    const ProbabilityMap map = ProbabilityMap::ramp(3, 1, 16);
    const ControlledColouring h(map, m, m, HashKind::LongPeriod, 1);
    b.run(
        "controlled-corner/long-period", 3, m, m, [&] { fill_lattice_corner_tiles(h, 0, 0, m, m, out); }, 3);
  }
  return 0;
}
