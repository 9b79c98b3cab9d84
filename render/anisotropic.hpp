#pragma once
// Anisotropic filtering, the footprint rule of EXT_texture_filter_anisotropic as GPUs implement
// it: a pixel's footprint in the texture is spanned by its two screen derivatives; its longer
// axis (major) is covered by N trilinear taps, N = ceil(major / minor) up to the maximum
// anisotropy (16 on GPUs), evenly spaced along that axis, each at the level of detail of
// major / N instead of major. A surface seen at a grazing angle is then filtered over its short
// axis only as much as needed, instead of being blurred to the long axis' level.
//
// Both renderers evaluate exactly this: the CPU one through anisotropic_footprint and tap_offset
// below, the shaders through the text of anisotropic_glsl(), with the same float operations (no
// division, no transcendental function except the log2 of the level of detail, which only
// moves the trilinear weights) and the tap offsets in the fixed point of render/view.hpp, in
// integers, so that every tap of a pixel lands in the same tile in both.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <string>

#include "render/view.hpp"

namespace tilekit {

inline constexpr int kMaxAnisotropy = 16;

struct Footprint {
  int taps = 1;                         // N
  float lod = 0;                        // lambda of every tap: log2(texels_per_tile * major / N)
  std::int32_t axis_u = 0, axis_v = 0;  // the major axis in tiles, fixed point (kFracBits)
};

// The footprint of a pixel with derivatives (dudx, dvdx) and (dudy, dvdy) in tiles per pixel, on a
// texture of texels_per_tile level-0 texels a tile (an atlas resampled to a power of two: not a
// whole number). max_aniso 1 is trilinear filtering (one tap at log2(texels_per_tile * major),
// OpenGL's lambda).
inline Footprint anisotropic_footprint(float dudx, float dvdx, float dudy, float dvdy, float texels_per_tile,
                                       int max_aniso) {
  const float lx = std::sqrt(dudx * dudx + dvdx * dvdx), ly = std::sqrt(dudy * dudy + dvdy * dvdy);
  const float major = std::max(lx, ly), minor = std::min(lx, ly);
  Footprint f;
  while (f.taps < max_aniso && float(f.taps) * minor < major) ++f.taps;
  f.lod = std::log2(texels_per_tile * major / float(f.taps));
  if (f.taps > 1) {  // the axis in fixed point, bounded so that tap_offset stays within 32 bits
    auto fixed = [](float a) { return std::int32_t(std::floor(std::clamp(a, -256.0f, 256.0f) * 65536.0f + 0.5f)); };
    f.axis_u = fixed(lx >= ly ? dudx : dudy);
    f.axis_v = fixed(lx >= ly ? dvdx : dvdy);
  }
  return f;
}

// The footprint of the hardware's anisotropic filter (textureGrad with a sampler's anisotropy, the
// `hardware` filter of render/cpu_renderer.hpp) as SwiftShader (Chromium's WebGL2 and WebGPU
// without a GPU) computes it, the footprint rule EXT_texture_filter_anisotropic suggests by area:
// in texels, major^2 the longer derivative's square length, det = |dx x dy| the pixel's area,
// anisotropy = min(major^2 / det, max_aniso), N = that rounded to the nearest integer (half to
// even) taps along the major axis, at log2(major / anisotropy) (not / N: the level of the minor
// axis, major^2 / det being major / minor; log2 approximated as SwiftShader does). Other GPUs
// filter otherwise (llvmpipe: an elliptical weighted average); the GLSL = CPU tests of that
// filter run on SwiftShader.
inline Footprint hardware_footprint(float dudx, float dvdx, float dudy, float dvdy, float texels_per_tile,
                                    int max_aniso) {
  const float px = texels_per_tile;
  const float ux = dudx * px, vx = dvdx * px, uy = dudy * px, vy = dvdy * px;
  const float lx2 = ux * ux + vx * vx, ly2 = uy * uy + vy * vy;
  const float major2 = std::max(lx2, ly2), det = std::abs(ux * vy - uy * vx);
  const float aniso = std::min(major2 / det, float(max_aniso));  // det 0: the most
  Footprint f;
  f.taps = std::max(1, int(std::nearbyint(aniso)));
  // log2(sqrt(v)) as SwiftShader evaluates it (log2sqrt: the bits of v^2 read as an integer, a
  // piecewise-linear log2, exact at powers of two)
  const float v = major2 / (aniso * aniso), v2 = v * v;
  const float bits = float(std::bit_cast<std::int32_t>(v2));
  f.lod = (bits - float(0x3F800000)) * 0x1p-25f;
  if (f.taps > 1) {
    auto fixed = [](float a) { return std::int32_t(std::floor(std::clamp(a, -256.0f, 256.0f) * 65536.0f + 0.5f)); };
    f.axis_u = fixed(lx2 >= ly2 ? dudx : dudy);
    f.axis_v = fixed(lx2 >= ly2 ? dvdx : dvdy);
  }
  return f;
}

// Offset of tap i of n along one fixed-point axis component a: round(a (2i + 1 - n) / (2n)),
// computed on magnitudes (GLSL leaves the integer division of negative numbers undefined).
inline std::int32_t tap_offset(std::int32_t a, int i, int n) {
  const std::int32_t m = 2 * i + 1 - n, q = ((a < 0 ? -a : a) * (m < 0 ? -m : m) + n) / (2 * n);
  return (a < 0) != (m < 0) ? -q : q;
}

// The same two functions in GLSL ES 3.0 (TK_TILE_PX must be defined: the texels a tile, an
// integer or a float literal):
//   void tk_footprint(vec2 dx, vec2 dy, int max_aniso, out int taps, out float lod, out ivec2 axis);
//   int tk_tap_offset(int a, int i, int n);
std::string anisotropic_glsl();

}  // namespace tilekit
