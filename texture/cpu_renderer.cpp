#include "texture/cpu_renderer.hpp"

#include <fmt/format.h>

#include <cmath>

#include "base/parallel.hpp"
#include "base/progress.hpp"

namespace tilekit {

VirtualTiling::VirtualTiling(TileKind kind, std::uint32_t colours, HashKind hash, std::uint64_t seed) : kind_(kind) {
  if (kind == TileKind::Corner)
    corner_ = std::make_unique<DirectCornerTiling>(colours, hash, seed);
  else
    wang_ = std::make_unique<DirectWangTiling>(colours, colours, hash, seed);
}

TileIndex VirtualTiling::tile(std::int64_t x, std::int64_t y) const {
  return corner_ ? corner_->tile(x, y) : wang_->tile(x, y);
}

void VirtualTiling::fill_row(std::int64_t x0, std::int64_t y, int cols, TileIndex* out) const {
  if (corner_)
    corner_->fill(x0, y, 1, cols, out);
  else
    wang_->fill(x0, y, 1, cols, out);
}

std::vector<const ColourHash*> VirtualTiling::hashes() const {
  if (corner_) return {&corner_->hash()};
  return {&wang_->horizontal_hash(), &wang_->vertical_hash()};
}

namespace {

// Bilinear filtering of one level (GL_LINEAR, GL_REPEAT), accumulated into acc with weight w.
void bilinear(const Image& img, float s, float t, float w, float* acc) {
  const float u = s * float(img.width) - 0.5f, v = t * float(img.height) - 0.5f;
  const float fu = std::floor(u), fv = std::floor(v), a = u - fu, b = v - fv;
  auto wrap = [](long i, int n) { return int(((i % n) + n) % n); };
  const int i0 = wrap(long(fu), img.width), i1 = wrap(long(fu) + 1, img.width);
  const int j0 = wrap(long(fv), img.height), j1 = wrap(long(fv) + 1, img.height);
  const std::uint8_t *p00 = img.at(i0, j0), *p10 = img.at(i1, j0), *p01 = img.at(i0, j1), *p11 = img.at(i1, j1);
  const float w00 = (1 - a) * (1 - b) * w, w10 = a * (1 - b) * w, w01 = (1 - a) * b * w, w11 = a * b * w;
  for (int c = 0; c < 4; ++c) acc[c] += w00 * p00[c] + w10 * p10[c] + w01 * p01[c] + w11 * p11[c];
}

}  // namespace

std::array<float, 4> sample_trilinear(const TextureAtlas& a, float s, float t, float lambda) {
  std::array<float, 4> acc{0, 0, 0, 0};
  const int q = int(a.levels.size()) - 1;
  if (!(lambda > 0)) {  // magnification (c = 0 for LINEAR with LINEAR_MIPMAP_LINEAR)
    bilinear(a.levels[0], s, t, 1, acc.data());
  } else if (lambda >= float(q)) {
    bilinear(a.levels[std::size_t(q)], s, t, 1, acc.data());
  } else {
    const int d1 = int(std::floor(lambda));
    const float f = lambda - float(d1);
    bilinear(a.levels[std::size_t(d1)], s, t, 1 - f, acc.data());
    bilinear(a.levels[std::size_t(d1 + 1)], s, t, f, acc.data());
  }
  return acc;
}

Image render_cpu(const TextureAtlas& a, const View& view, const RenderOptions& o) {
  const ViewRows vr = view_rows(view, a.tile_px);
  const VirtualTiling tiling(a.lookup.kind, a.lookup.colours, o.hash, o.seed);
  Image out{view.width, view.height, std::vector<std::uint8_t>(std::size_t(view.width) * std::size_t(view.height) * 4)};
  const float inv_cols = 1.0f / float(a.lookup.cols), inv_rows = 1.0f / float(a.lookup.rows);
  ProgressReporter progress(fmt::format("render {}x{}", view.width, view.height), view.height, o.progress);
  parallel_for(view.height, o.threads, [&](std::int64_t j) {
    const ViewRow& r = vr.rows[std::size_t(j)];
    const std::int32_t first = r.tile_u0 + std::int32_t(r.frac_u0 >> kFracBits);
    const std::int32_t last =
        r.tile_u0 + std::int32_t((r.frac_u0 + std::uint32_t(view.width - 1) * r.step_u) >> kFracBits);
    std::vector<TileIndex> tiles(std::size_t(last - first + 1));
    tiling.fill_row(first, r.tile_v, int(tiles.size()), tiles.data());
    const float fv = float(r.frac_v) / float(kFracOne);
    for (int x = 0; x < view.width; ++x) {
      const std::uint32_t fixed = r.frac_u0 + std::uint32_t(x) * r.step_u;
      const std::int32_t tu = r.tile_u0 + std::int32_t(fixed >> kFracBits);
      const float fu = float(fixed & (kFracOne - 1)) / float(kFracOne);
      const auto [row, col] = a.lookup.positions[tiles[std::size_t(tu - first)]];
      // thesis sec. 5.4: the tile's place in the packing plus the position inside the tile
      const float s = (float(col) + fu) * inv_cols, t = (float(row) + fv) * inv_rows;
      const std::array<float, 4> c = sample_trilinear(a, s, t, view_lod(r, vr.dudy_step, x, a.tile_px));
      std::uint8_t* p = out.at(x, int(j));
      for (int k = 0; k < 4; ++k) p[k] = std::uint8_t(std::clamp(std::lround(c[std::size_t(k)]), 0l, 255l));
    }
    progress.add(1);
  });
  progress.finish();
  return out;
}

}  // namespace tilekit
