#include "render/anisotropic.hpp"

namespace tilekit {

// Line for line the operations of anisotropic_footprint and tap_offset (anisotropic.hpp).
std::string anisotropic_glsl() {
  return "// anisotropic footprint (texture/anisotropic.hpp): derivatives in tiles per pixel\n"
         "void tk_footprint(vec2 dx, vec2 dy, int max_aniso, out int taps, out float lod, out ivec2 axis) {\n"
         "  float lx = sqrt(dx.x * dx.x + dx.y * dx.y), ly = sqrt(dy.x * dy.x + dy.y * dy.y);\n"
         "  float major = max(lx, ly), minor = min(lx, ly);\n"
         "  taps = 1;\n"
         "  while (taps < max_aniso && float(taps) * minor < major) ++taps;\n"
         "  lod = log2(float(TK_TILE_PX) * major / float(taps));\n"
         "  vec2 a = clamp(lx >= ly ? dx : dy, -256.0, 256.0);\n"
         "  axis = taps > 1 ? ivec2(floor(a * 65536.0 + 0.5)) : ivec2(0);\n"
         "}\n"
         "int tk_tap_offset(int a, int i, int n) {  // round(a (2i + 1 - n) / (2n)) on magnitudes\n"
         "  int m = 2 * i + 1 - n;\n"
         "  int q = (abs(a) * abs(m) + n) / (2 * n);\n"
         "  return (a < 0) != (m < 0) ? -q : q;\n"
         "}\n";
}

}  // namespace tilekit
