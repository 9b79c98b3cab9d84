#pragma once
// The CPU reference renderer of tile-based texture mapping (thesis sec. 5.4): every pixel of a
// window of the infinite virtual texture goes through the direct stochastic tiling (thesis
// 3.3.1 for corner tiles, 3.3.2.1 for Wang tiles; tiling/direct_tiling.hpp) to a tile, through
// the packing to the tile's place in the atlas, and is sampled trilinearly from the atlas's mip
// chain at the level of detail its derivatives give, with OpenGL's rules (LINEAR_MIPMAP_LINEAR,
// REPEAT). The GLSL sampler (glsl_sampler.hpp) does the same on the GPU; tests compare them.
#include <array>
#include <cstdint>
#include <memory>

#include "texture/texture_atlas.hpp"
#include "texture/view.hpp"
#include "tiling/direct_tiling.hpp"

namespace tilekit {

struct RenderOptions {
  HashKind hash = HashKind::LongPeriod;  // the lattice hash of the direct stochastic tiling (thesis 3.4)
  std::uint64_t seed = 1;
  int threads = 1;
  bool progress = false;
};

// The direct stochastic tiling of the virtual texture: tile (x, y) is in column x and row y,
// rows growing to the south (tiling/lattice_tiling.hpp).
class VirtualTiling {
 public:
  VirtualTiling(TileKind kind, std::uint32_t colours, HashKind hash, std::uint64_t seed);
  TileKind kind() const { return kind_; }
  TileIndex tile(std::int64_t x, std::int64_t y) const;
  void fill_row(std::int64_t x0, std::int64_t y, int cols, TileIndex* out) const;
  // The lattice hashes: corner tiles one, Wang tiles the horizontal-edge and the vertical-edge one.
  std::vector<const ColourHash*> hashes() const;

 private:
  TileKind kind_;
  std::unique_ptr<DirectCornerTiling> corner_;
  std::unique_ptr<DirectWangTiling> wang_;
};

// GL_LINEAR_MIPMAP_LINEAR sampling with GL_REPEAT at atlas coordinate (s, t) in [0, 1)^2 and
// level of detail lambda (OpenGL ES 3.0 sec. 3.8.10-3.8.11): components in 0..255.
std::array<float, 4> sample_trilinear(const TextureAtlas& a, float s, float t, float lambda);

Image render_cpu(const TextureAtlas& a, const View& view, const RenderOptions& o);

}  // namespace tilekit
