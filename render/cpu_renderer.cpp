#include "render/cpu_renderer.hpp"

#include <fmt/format.h>

#include <cmath>

#include "base/error.hpp"
#include "base/parallel.hpp"
#include "base/progress.hpp"
#include "render/anisotropic.hpp"
#include "render/baseline_samplers.hpp"
#include "render/sampling.hpp"

namespace tilekit {

RenderMethod parse_render_method(const std::string& name) {
  if (name == "tiles") return RenderMethod::Tiles;
  if (name == "hex") return RenderMethod::Hex;
  if (name == "hpn") return RenderMethod::Hpn;
  throw RequestError("method", fmt::format("`method` must be tiles, hex or hpn, got '{}'", name));
}

const char* render_method_name(RenderMethod m) {
  return m == RenderMethod::Tiles ? "tiles" : m == RenderMethod::Hex ? "hex" : "hpn";
}

std::vector<Image> atlas_levels_8bit(const TextureAtlas& a) {
  std::vector<Image> out;
  out.reserve(a.levels.size());
  for (const Image& l : a.levels) out.push_back(l.to_depth(8));
  return out;
}

std::size_t RenderSource::memory_bytes() const {
  if (method != RenderMethod::Tiles) return exemplar->memory_bytes(method == RenderMethod::Hpn);
  std::size_t bytes = 0;
  for (const Image& l : atlas->levels) bytes += l.pixels.size();
  return bytes;
}

namespace {

// Tilekit's method (thesis sec. 5.4) at one pixel: every anisotropic tap through the tiling to
// its tile, the tile's place in the packing plus the position inside the tile, one trilinear
// fetch. With one tap the tile comes from the row's tiles, filled once per row.
struct TileSampler {
  const TextureAtlas& a;
  const DirectTiling tiling;
  const float inv_cols, inv_rows;
  const std::vector<Image>& levels;  // a.levels, at 8 bits
  const bool srgb;                   // filtered in linear light (GL: SRGB8_ALPHA8)

  const bool hardware;

  // fu, fv: the position in the tile in fixed point; beyond [0, 1) (the hardware filter's taps)
  // it reaches into the atlas neighbours, wrapping around the atlas.
  std::array<float, 4> tap(TileIndex tile, std::int64_t fu, std::int64_t fv, float lod) const {
    const auto [row, col] = a.lookup.positions[tile];
    const float s = (float(col) + float(fu) / float(kFracOne)) * inv_cols;
    const float t = (float(row) + float(fv) / float(kFracOne)) * inv_rows;
    return srgb ? sample_trilinear_srgb(levels, s, t, lod) : sample_trilinear(levels, s, t, lod);
  }

  std::array<float, 4> sample(const PixelPosition& p, TileIndex tile_here, const Footprint& f) const {
    if (f.taps == 1) return tap(tile_here, p.frac_u, p.frac_v, f.lod);
    if (hardware) {  // the taps in the atlas around the pixel's own tile
      std::array<float, 4> sum{0, 0, 0, 0};
      for (int i = 0; i < f.taps; ++i) {
        const auto c = tap(tile_here, std::int64_t(p.frac_u) + tap_offset(f.axis_u, i, f.taps),
                           std::int64_t(p.frac_v) + tap_offset(f.axis_v, i, f.taps), f.lod);
        for (int k = 0; k < 4; ++k) sum[std::size_t(k)] += c[std::size_t(k)];
      }
      for (float& c : sum) c /= float(f.taps);
      return sum;
    }
    std::array<float, 4> sum{0, 0, 0, 0};
    for (int i = 0; i < f.taps; ++i) {
      const std::int32_t u = std::int32_t(p.frac_u) + tap_offset(f.axis_u, i, f.taps);
      const std::int32_t v = std::int32_t(p.frac_v) + tap_offset(f.axis_v, i, f.taps);
      const TileIndex tile = tiling.tile(p.tile_u + (u >> kFracBits), p.tile_v + (v >> kFracBits));
      const auto c = tap(tile, std::uint32_t(u) & (kFracOne - 1), std::uint32_t(v) & (kFracOne - 1), f.lod);
      for (int k = 0; k < 4; ++k) sum[std::size_t(k)] += c[std::size_t(k)];
    }
    for (float& c : sum) c /= float(f.taps);
    return sum;
  }
};

}  // namespace

double mean_fetches(const RenderSource& src, const View& view, int max_aniso) {
  const int unit = src.unit_px();
  const ViewRows vr = view_rows(view, unit);
  double sum = 0;
  for (const ViewRow& r : vr.rows)
    for (int x = 0; x < view.width; ++x)
      sum += src.fetches(anisotropic_footprint(r.dudx, 0.0f, r.dudy0 + float(x) * vr.dudy_step, r.dvdy,
                                               src.texels_per_unit(), max_aniso)
                             .taps);
  return sum / (double(view.width) * double(view.height));
}

Image render_cpu(const RenderSource& src, const View& view, const RenderOptions& o) {
  if (src.method == RenderMethod::Tiles ? !src.atlas : !src.exemplar)
    throw RequestError(
        "method", fmt::format("`method` {} needs {}", render_method_name(src.method),
                              src.method == RenderMethod::Tiles ? "an atlas (`atlas`)" : "an exemplar (`exemplar`)"));
  if (o.max_aniso < 1 || o.max_aniso > kMaxAnisotropy)
    throw RequestError("max_aniso", fmt::format("`max_aniso` must be 1..{}, got {}", kMaxAnisotropy, o.max_aniso));
  const int unit = src.unit_px();
  const float texels = src.texels_per_unit();
  const ViewRows vr = view_rows(view, unit);
  std::unique_ptr<TileSampler> tiles;
  std::unique_ptr<PatchHashes> patches;
  const std::vector<Image> levels8 =
      src.method == RenderMethod::Tiles ? atlas_levels_8bit(*src.atlas) : std::vector<Image>{};
  bool srgb_out = false;
  if (src.method == RenderMethod::Tiles) {
    const TextureAtlas& a = *src.atlas;
    srgb_out = a.colour_space == ColourSpace::Srgb;
    tiles.reset(new TileSampler{a, DirectTiling(a.lookup.kind, a.lookup.colours, o.hash, o.seed),
                                1.0f / float(a.lookup.cols), 1.0f / float(a.lookup.rows), levels8, srgb_out,
                                o.hardware_filter});
  } else {
    patches = std::make_unique<PatchHashes>(o.hash, o.seed);
  }
  Image out{view.width, view.height, std::vector<std::uint8_t>(std::size_t(view.width) * std::size_t(view.height) * 4)};
  ProgressReporter progress(fmt::format("render {}x{}", view.width, view.height), view.height, o.progress);
  parallel_for(view.height, o.threads, [&](std::int64_t j) {
    const ViewRow& r = vr.rows[std::size_t(j)];
    const std::int32_t first = r.tile_u0 + std::int32_t(r.frac_u0 >> kFracBits);
    const std::int32_t last =
        r.tile_u0 + std::int32_t((r.frac_u0 + std::uint32_t(view.width - 1) * r.step_u) >> kFracBits);
    std::vector<TileIndex> row_tiles;
    if (tiles) {
      row_tiles.resize(std::size_t(last - first + 1));
      tiles->tiling.fill(first, r.tile_v, 1, int(row_tiles.size()), row_tiles.data());
    }
    for (int x = 0; x < view.width; ++x) {
      const std::uint32_t fixed = r.frac_u0 + std::uint32_t(x) * r.step_u;
      const PixelPosition p{r.tile_u0 + std::int32_t(fixed >> kFracBits), r.tile_v, fixed & (kFracOne - 1), r.frac_v};
      const float dudy = r.dudy0 + float(x) * vr.dudy_step;
      const Footprint f = tiles && o.hardware_filter
                              ? hardware_footprint(r.dudx, 0.0f, dudy, r.dvdy, texels, o.max_aniso)
                              : anisotropic_footprint(r.dudx, 0.0f, dudy, r.dvdy, texels, o.max_aniso);
      const std::array<float, 4> c = tiles ? tiles->sample(p, row_tiles[std::size_t(p.tile_u - first)], f)
                                     : src.method == RenderMethod::Hex
                                         ? sample_hex(*src.exemplar, *patches, p, f, unit)
                                         : sample_hpn(*src.exemplar, *patches, p, f, unit);
      std::uint8_t* px = out.at(x, int(j));
      for (int k = 0; k < 4; ++k) {
        const float v = srgb_out && k < 3 ? srgb_encode_255(c[std::size_t(k)]) : c[std::size_t(k)];
        px[k] = std::uint8_t(std::clamp(std::lround(v), 0l, 255l));
      }
    }
    progress.add(1);
  });
  progress.finish();
  return out;
}

}  // namespace tilekit
