#pragma once
// Direct stochastic tiling algorithms (thesis sec. 3.3): the tile at any (x, y) is computed
// on its own from lattice hashes, without building the tiling up to that point. Each class
// offers tile(x, y) (random access) and fill() (a whole window, each hash evaluated once);
// both give the same tiles. Coordinates as in lattice_tiling.hpp (rows grow to the south).
#include <cstdint>
#include <memory>
#include <vector>

#include "tilesets/tile.hpp"
#include "tilesets/tile_grid.hpp"
#include "tiling/lattice_hash.hpp"
#include "tiling/lattice_tiling.hpp"

namespace tilekit {

// Corner tiles over C colours (thesis sec. 3.3.1): the corners of tile (x, y) are h at the
// four lattice points around it. Produces the complete corner set.
class DirectCornerTiling {
 public:
  DirectCornerTiling(std::uint32_t colours, HashKind kind, std::uint64_t seed) : h_(kind, colours, seed) {}
  std::uint32_t colours() const { return h_.colours(); }
  const ColourHash& hash() const { return h_; }
  TileIndex tile(std::int64_t x, std::int64_t y) const { return lattice_corner_tile(h_, x, y); }
  void fill(std::int64_t x0, std::int64_t y0, int rows, int cols, TileIndex* out, int threads = 1) const {
    fill_lattice_corner_tiles(h_, x0, y0, rows, cols, out, threads);
  }
  Tiling generate(int rows, int cols, std::int64_t x0 = 0, std::int64_t y0 = 0) const;

 private:
  ColourHash h_;
};

// Wang tiles over C_h x C_v colours with two hashes h_h, h_v (thesis sec. 3.3.2.1): each edge
// colour is the sum modulo C of the hash values at its two end points. Complete Wang set.
class DirectWangTiling {
 public:
  DirectWangTiling(std::uint32_t ch, std::uint32_t cv, HashKind kind, std::uint64_t seed);
  std::uint32_t ch() const { return hh_.colours(); }
  std::uint32_t cv() const { return hv_.colours(); }
  const ColourHash& horizontal_hash() const { return hh_; }
  const ColourHash& vertical_hash() const { return hv_; }
  TileIndex tile(std::int64_t x, std::int64_t y) const;
  void fill(std::int64_t x0, std::int64_t y0, int rows, int cols, TileIndex* out) const;
  Tiling generate(int rows, int cols, std::int64_t x0 = 0, std::int64_t y0 = 0) const;

 private:
  ColourHash hh_, hv_;
};

// Compact Wang tiles over C colours with one hash (thesis sec. 3.3.2.2): edge colours are sums
// modulo C of corner values, so N + S = E + W (mod C): the C^3 tiles of compact-wang3-C.
class DirectCompactWangTiling {
 public:
  DirectCompactWangTiling(std::uint32_t colours, HashKind kind, std::uint64_t seed) : h_(kind, colours, seed) {}
  std::uint32_t colours() const { return h_.colours(); }
  TileIndex tile(std::int64_t x, std::int64_t y) const;
  void fill(std::int64_t x0, std::int64_t y0, int rows, int cols, TileIndex* out) const;
  Tiling generate(int rows, int cols, std::int64_t x0 = 0, std::int64_t y0 = 0) const;

 private:
  ColourHash h_;
};

// Wang tiles over C_h x C_v colours with one hash on a lattice twice as dense (thesis sec.
// 3.3.2.3): the edge midpoints of tile (x, y) are the points (2x+1, 2y), (2x+2, 2y+1),
// (2x+1, 2y+2), (2x, 2y+1) (N, E, S, W with rows growing south). The hash has lcm(C_h, C_v)
// colours, reduced modulo C_h or C_v per edge. Complete Wang set.
class DirectEdgeWangTiling {
 public:
  DirectEdgeWangTiling(std::uint32_t ch, std::uint32_t cv, HashKind kind, std::uint64_t seed);
  std::uint32_t ch() const { return ch_; }
  std::uint32_t cv() const { return cv_; }
  TileIndex tile(std::int64_t x, std::int64_t y) const;
  void fill(std::int64_t x0, std::int64_t y0, int rows, int cols, TileIndex* out) const;
  Tiling generate(int rows, int cols, std::int64_t x0 = 0, std::int64_t y0 = 0) const;

 private:
  std::uint32_t ch_, cv_;
  ColourHash h_;
  std::vector<std::uint16_t> mod_h_, mod_v_;  // v -> v % C_h, v % C_v for v < lcm(C_h, C_v)
};

// The direct stochastic tiling of the complete corner set (thesis 3.3.1) or the complete Wang set
// with two hashes (3.3.2.1) over C colours: the one that tile-based texture mapping (thesis 5.4)
// evaluates. The atlas lookup, the CPU renderer and the GLSL text (direct_tiling_glsl.hpp) all
// use this class, so they agree tile for tile. Axes as above: x east, y south.
class DirectTiling {
 public:
  DirectTiling(TileKind kind, std::uint32_t colours, HashKind hash, std::uint64_t seed);
  TileKind kind() const { return kind_; }
  std::uint32_t colours() const;
  HashKind hash_kind() const { return hash_; }
  std::uint64_t seed() const { return seed_; }
  TileIndex tile(std::int64_t x, std::int64_t y) const;
  void fill(std::int64_t x0, std::int64_t y0, int rows, int cols, TileIndex* out) const;
  // The lattice hashes: corner tiles one, Wang tiles the horizontal-edge and the vertical-edge one.
  std::vector<const ColourHash*> hashes() const;

 private:
  TileKind kind_;
  HashKind hash_;
  std::uint64_t seed_;
  std::unique_ptr<DirectCornerTiling> corner_;
  std::unique_ptr<DirectWangTiling> wang_;
};

}  // namespace tilekit
