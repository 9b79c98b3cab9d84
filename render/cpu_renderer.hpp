#pragma once
// The CPU reference renderer of a window of an infinite textured plane, by one of three methods:
//  - tiles (thesis sec. 5.4, Tilekit's method): every pixel goes through the direct stochastic
//    tiling (tiling/direct_tiling.hpp) to a tile, through the packing to the tile's place in the
//    atlas, and is sampled from the atlas's mip chain;
//  - hex and hpn, the baselines that sample the exemplar directly (render/baseline_samplers.hpp).
// Filtering follows OpenGL's rules (render/sampling.hpp) with anisotropic taps along the
// footprint's major axis (render/anisotropic.hpp; max_aniso 1 is trilinear). The GLSL renderer
// (glsl_sampler.hpp, gl_renderer.hpp) does the same on the GPU; tests compare the two.
#include <cstdint>
#include <string>

#include "render/exemplar_surface.hpp"
#include "render/view.hpp"
#include "texture/texture_atlas.hpp"
#include "tiling/direct_tiling.hpp"

namespace tilekit {

struct RenderOptions {
  HashKind hash = HashKind::LongPeriod;  // the lattice hash of the tiling or of the patch centres (thesis 3.4)
  std::uint64_t seed = 1;
  int threads = 1;
  bool progress = false;
  int max_aniso = 1;  // 1: trilinear; up to kMaxAnisotropy taps along the footprint
  // tiles: the hardware's anisotropic filter (`filter` "hardware"): one fetch per pixel, the
  // gradients of the virtual texture given to the sampler (textureGrad), whose taps (the same
  // footprint rule, render/anisotropic.hpp) run along the major axis in the atlas from the pixel's
  // own tile, across its border into the atlas neighbour (a valid neighbour: the atlas is a
  // toroidal tiling, GL_REPEAT), instead of each through the tiling ("taps", the default).
  bool hardware_filter = false;
};

enum class RenderMethod { Tiles, Hex, Hpn };
// "tiles", "hex" or "hpn"; InputError otherwise.
RenderMethod parse_render_method(const std::string& name);
const char* render_method_name(RenderMethod m);

// What a render samples: the atlas (tiles) or the exemplar surface (hex, hpn).
struct RenderSource {
  RenderMethod method = RenderMethod::Tiles;
  const TextureAtlas* atlas = nullptr;
  const ExemplarSurface* exemplar = nullptr;
  // Texels per unit of the view's fixed point: the atlas's tile size; 64 for the baselines.
  int unit_px() const { return method == RenderMethod::Tiles ? atlas->tile_px : 64; }
  // Level-0 texels a unit: unit_px, but for an atlas resampled to a power of two
  // (texture_atlas.hpp), its width over its columns.
  float texels_per_unit() const {
    return method == RenderMethod::Tiles ? atlas_texels_per_tile(*atlas) : float(unit_px());
  }
  // Texture fetches (trilinear taps and look-ups) of one pixel with `taps` anisotropic taps; one
  // for tiles with the hardware filter (the shader's; the hardware's taps are inside it).
  bool hardware_filter = false;
  int fetches(int taps) const {
    return method == RenderMethod::Tiles ? (hardware_filter ? 1 : taps)
           : method == RenderMethod::Hex ? 3 * taps
                                         : 3 * taps + 3;
  }
  std::size_t memory_bytes() const;  // texture memory: the atlas's or the exemplar surface's mip chain (and LUT)
};

// An atlas's levels as the renderers sample them: 8 bits (16-bit atlases rounded). An atlas whose
// colour space is sRGB is filtered in linear light and its render encoded back to sRGB (GL: an
// SRGB8_ALPHA8 texture and the shader's tk_srgb_encode); linear and normal atlases as stored.
std::vector<Image> atlas_levels_8bit(const TextureAtlas& a);

Image render_cpu(const RenderSource& source, const View& view, const RenderOptions& o);
// The mean texture fetches per pixel of a view (RenderSource::fetches of every pixel's taps).
double mean_fetches(const RenderSource& source, const View& view, int max_aniso);
inline Image render_cpu(const TextureAtlas& a, const View& view, const RenderOptions& o) {
  return render_cpu(RenderSource{RenderMethod::Tiles, &a, nullptr}, view, o);
}

}  // namespace tilekit
