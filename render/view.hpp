#pragma once
// The window of the infinite virtual texture that a render shows (thesis sec. 5.4), as one
// affine map per pixel row: u (tile units, to the east) grows by a fixed step from pixel to
// pixel, v (tile units, to the south) is constant along the row. A flat view has one scale; a
// tilted view is a ground plane seen in perspective, far (more texels per pixel) at the top.
//
// The rows are quantised to fixed point (kFracBits bits of a tile) once, on the CPU, and both
// renderers, the CPU reference and the GLSL shader, read the same integers: every pixel lands
// in the same tile at the same in-tile position in both, whatever the GPU's float rounding.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace tilekit {

inline constexpr int kFracBits = 16;  // fixed-point bits of a tile
inline constexpr std::uint32_t kFracOne = 1u << kFracBits;
inline constexpr int kMaxViewSide = 8192;  // pixels per side of a rendered window

struct View {
  int width = 512, height = 512;
  double scale = 1;                   // texels of the virtual texture per pixel (at the bottom row when tilted)
  double origin_u = 0, origin_v = 0;  // texel of the virtual texture at the window's top-left corner
  double tilt = 0;                    // 0 flat; t > 0: rows at the top are (1 + t)^2 times farther
};

struct ViewRow {
  std::int32_t tile_u0 = 0;  // pixel x sits in tile column tile_u0 + ((frac_u0 + x * step_u) >> kFracBits)
  std::uint32_t frac_u0 = 0, step_u = 0;
  std::int32_t tile_v = 0;  // the row's tile row and in-tile position (kFracBits)
  std::uint32_t frac_v = 0;
  // Derivatives of (u, v) in tiles per pixel: du/dx = dudx, dv/dy = dvdy, dv/dx = 0 and
  // du/dy = dudy0 + x * dudy_step (a tilted view shears).
  float dudx = 0, dvdy = 0, dudy0 = 0;
};

struct ViewRows {
  std::vector<ViewRow> rows;
  float dudy_step = 0;
};

// InputError for a view the fixed point cannot hold (size outside 1..kMaxViewSide, a step of 2 tiles or
// more per pixel, coordinates beyond +-2^30 tiles, non-finite or negative scale or tilt).
ViewRows view_rows(const View& v, int tile_px);

// The texel-space level of detail of pixel x of a row, as OpenGL computes it from the
// derivatives: lambda = log2 of the longer screen-axis footprint, in level-0 texels. The
// GLSL sampler evaluates the same expression.
inline float view_lod(const ViewRow& r, float dudy_step, int x, int tile_px) {
  const float dudy = r.dudy0 + float(x) * dudy_step;
  const float along_x = std::abs(r.dudx), along_y = std::sqrt(dudy * dudy + r.dvdy * r.dvdy);
  return std::log2(float(tile_px) * std::max(along_x, along_y));
}

}  // namespace tilekit
