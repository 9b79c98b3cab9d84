#pragma once
// All points of any window of the infinite plane from a Poisson disk tile set, through the
// direct stochastic tiling (thesis sec. 3.3): the tile at (tx, ty) is computed on its own from
// lattice hashes, and its points are copied with the offset (tx, ty) times the tile size, so
// the cost is proportional to the output and any window can be made at any time (random
// access: two windows agree, bit for bit, on their overlap).
//
// Coordinates: tile (tx, ty) covers [tx s, (tx + 1) s) x [ty s, (ty + 1) s) with s =
// sqrt(N / density); y grows to the south like the tilings of tiling/. A point is
// tx * s + u * s (u its tile coordinate), whatever the window. Coordinates are doubles, exact
// to about 1e-16 of their size, so windows far from the origin keep their distances (float32
// lost the disk radius from about 1e6 on).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "points/poisson_tiles.hpp"
#include "tiling/lattice_hash.hpp"

namespace tilekit {
class ProgressReporter;
}

namespace tilekit::points {

// The half-open window [x0, x1) x [y0, y1).
struct Window {
  double x0 = 0, y0 = 0, x1 = 1, y1 = 1;
  double width() const { return x1 - x0; }
  double height() const { return y1 - y0; }
  double area() const { return width() * height(); }
};
// "x0,y0,x1,y1"; InputError naming `what` otherwise (x0 < x1, y0 < y1, finite, a finite area); by
// default the request field `window` (a RequestError, base/error.hpp).
Window parse_window(const std::string& text, const char* what = "`window`");

class PoissonTileGenerator {
 public:
  // `period` > 0 makes the lattice colouring repeat every `period` tiles in x and y (hashes of
  // coordinates modulo the period, thesis sec. 7.6.2.4), so the point set is toroidal.
  PoissonTileGenerator(const PoissonTileSet& set, HashKind hash, std::uint64_t seed, std::int64_t period = 0);

  const PoissonTileSet& set() const { return set_; }
  std::int64_t period() const { return period_; }
  double tile_size(double density) const;

  // Interleaved (x, y) of every point in the window, tile row by tile row (north to
  // south), tiles west to east, each tile's points in stored order. Rows run on `threads`
  // threads; the output does not depend on the thread count. `progress` counts rows.
  std::vector<double> generate(const Window& w, double density, int threads = 1,
                              ProgressReporter* progress = nullptr) const;
  // The same into `out`, whose contents are replaced and whose capacity is kept: an application
  // that asks for window after window reuses one buffer and pays no page faults for it.
  void generate_into(std::vector<double>& out, const Window& w, double density, int threads = 1,
                     ProgressReporter* progress = nullptr) const;

  // The same points handed to `sink` a row of tiles at a time, north to south, in the order
  // generate() gives them, on the calling thread; rows are made `threads` at a time. Memory is a
  // few rows per thread whatever the window's size, so a window can be streamed to a file.
  void generate_rows(const Window& w, double density, const std::function<void(const std::vector<double>&)>& sink,
                     int threads = 1, ProgressReporter* progress = nullptr) const;

  // The tile index (into set().tiles) of tile (tx, ty).
  std::uint64_t tile_index(std::int64_t tx, std::int64_t ty) const;

 private:
  struct Scratch;
  struct Rows {  // the tiles a window touches, and their side
    double side;
    std::int64_t tx0, tx1, ty0, ty1;
  };
  Rows rows_of(const Window& w, double density) const;
  void row(std::int64_t ty, std::int64_t tx0, std::int64_t tx1, const Window& w, double s, Scratch& scratch,
           std::vector<double>& out) const;
  void row_indices(std::int64_t ty, std::int64_t tx0, std::int64_t cols, Scratch& scratch) const;
  std::uint32_t lattice(std::int64_t x, std::int64_t y) const;  // corner and dual sets
  // A colour at (mx, my) of the doubled lattice: edge-based sets' Wang edge colours from hash_,
  // corner sets' edge colours from edge_hash_.
  std::uint32_t edge(const ColourHash& h, std::int64_t mx, std::int64_t my) const;

  const PoissonTileSet& set_;
  ColourHash hash_;
  std::optional<ColourHash> edge_hash_;  // corner sets with edge colours
  std::int64_t period_;
  std::vector<std::uint32_t> offset_;  // tile t holds points offset_[t] .. offset_[t+1]
  std::vector<double> uv_;             // interleaved tile coordinates (u, v)
  double umax_ = 0;                    // the largest u or v
};

}  // namespace tilekit::points
