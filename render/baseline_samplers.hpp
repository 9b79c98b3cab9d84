#pragma once
// The two baselines of `texture render --method hex|hpn`, on the CPU and as GLSL ES 3.0 text, both
// sampling the exemplar directly (render/exemplar_surface.hpp) on a triangle grid:
//  - the grid (Heitz & Neyret 2018, the same in Mikkelsen 2022): the plane in units of the
//    triangle side, skewed by (x - y / sqrt 3, 2 y / sqrt 3), floored; the three vertices of the
//    pixel's triangle with barycentric weights w1, w2, w3. Each vertex v shows the exemplar
//    translated so that v's position lands on a random patch centre (two lattice hashes of v,
//    tiling/lattice_hash.hpp, 256 steps per axis across the centre range).
//  - hex (Mikkelsen 2022): the three patches blended with W_i = D_i w_i^7, D_i = 0.4 + 0.6 L_i,
//    L_i the luminance (0.299, 0.587, 0.114) of patch i's texel, normalised to sum 1 (his
//    fall-off contrast 0.6 and exponent 7; no rotation).
//  - hpn (Heitz & Neyret 2018): the Gaussianized patches blended preserving mean and variance,
//    G = (sum w_i G_i - 1/2) / sqrt(sum w_i^2) + 1/2, then every channel through the inverse
//    transformation of the mip level the fetches used, and the PCA basis back to RGB.
// Each of the three fetches is the anisotropic fetch of render/anisotropic.hpp (N taps along the
// footprint's major axis, in texels); the grid is evaluated once, at the pixel.
//
// CPU and GLSL run the same float operations in the same order (the constants are printed with
// 9 significant digits, which reads back as the same float), so the renders agree within the
// filtering differences of the GPU (tests/render). The only discontinuities of the grid, a
// vertex changing across a triangle edge, have weight 0 on that edge, so a rounding difference
// there changes nothing visible.
#include <array>
#include <cstdint>
#include <string>

#include "render/anisotropic.hpp"
#include "render/exemplar_surface.hpp"
#include "tiling/lattice_hash.hpp"

namespace tilekit {

// The two hashes that place the patches: 256 colours each, seeds derived from `seed`.
struct PatchHashes {
  ColourHash x, y;
  PatchHashes(HashKind kind, std::uint64_t seed);
};

// A pixel: texel position (tile, frac) of the view's fixed point (render/view.hpp) with
// `unit_px` texels per tile, and its footprint (anisotropic_footprint with tile_px = unit_px).
struct PixelPosition {
  std::int32_t tile_u = 0, tile_v = 0;
  std::uint32_t frac_u = 0, frac_v = 0;
};

std::array<float, 4> sample_hex(const ExemplarSurface& s, const PatchHashes& h, const PixelPosition& p,
                                const Footprint& f, int unit_px);
std::array<float, 4> sample_hpn(const ExemplarSurface& s, const PatchHashes& h, const PixelPosition& p,
                                const Footprint& f, int unit_px);

// GLSL defining `vec4 tk_sample(ivec2 tile, ivec2 frac, int taps, float lod, ivec2 axis)` for the
// method (TK_TILE_PX = unit_px), with the patch hashes as tk_patch_x / tk_patch_y
// (tiling/direct_tiling_glsl.hpp) and the samplers tk_exemplar (hex: the RGBA8 mip chain; hpn:
// the Gaussianized RGBA16F chain) and tk_lut (hpn: the inverse transformations).
std::string hex_glsl(const ExemplarSurface& s, const PatchHashes& h, int unit_px, bool uniform_tables);
std::string hpn_glsl(const ExemplarSurface& s, const PatchHashes& h, int unit_px, bool uniform_tables);

}  // namespace tilekit
