#include "render/baseline_samplers.hpp"

#include <fmt/format.h>

#include <cmath>

#include "base/random.hpp"
#include "render/sampling.hpp"
#include "tiling/direct_tiling_glsl.hpp"

namespace tilekit {

PatchHashes::PatchHashes(HashKind kind, std::uint64_t seed)
    : x(kind, 256, derive_seed(seed, 1)), y(kind, 256, derive_seed(seed, 2)) {}

namespace {

// The constants of the grid, written into the GLSL with the same digits.
constexpr float kSkewX = 0.577350269f;      // 1 / sqrt 3
constexpr float kSkewY = 1.15470054f;       // 2 / sqrt 3
constexpr float kHalfSqrt3 = 0.866025404f;  // sqrt 3 / 2

struct Triangle {
  float w[3];
  std::int32_t vx[3], vy[3];
};

// The triangle of point g (in triangle sides) and its barycentric weights (Heitz & Neyret 2018).
Triangle triangle_grid(float gx, float gy) {
  const float sx = gx - kSkewX * gy, sy = kSkewY * gy;
  const float bx = std::floor(sx), by = std::floor(sy);
  const float fx = sx - bx, fy = sy - by, z = 1.0f - fx - fy;
  const float s = z <= 0.0f ? 1.0f : 0.0f, s2 = 2.0f * s - 1.0f;
  const std::int32_t b0 = std::int32_t(bx), b1 = std::int32_t(by), si = std::int32_t(s);
  return {{-z * s2, s - fy * s2, s - fx * s2}, {b0 + si, b0 + si, b0 + 1 - si}, {b1 + si, b1 + 1 - si, b1 + si}};
}

struct Geometry {
  float unit, frac_scale, inv_cell, cell, lo[2], step[2], inv_size[2];
  Geometry(const ExemplarSurface& s, int unit_px)
      : unit(float(unit_px)),
        frac_scale(float(unit_px) / 65536.0f),
        inv_cell(1.0f / s.cell_px),
        cell(s.cell_px),
        lo{s.centre_lo[0], s.centre_lo[1]},
        step{(s.centre_hi[0] - s.centre_lo[0]) / 256.0f, (s.centre_hi[1] - s.centre_lo[1]) / 256.0f},
        inv_size{1.0f / float(s.width), 1.0f / float(s.height)} {}
};

// The three patch points of a pixel: where each vertex's patch shows the pixel's texel p.
struct Patches {
  Triangle t;
  float ex[3], ey[3];
};

Patches patches(const Geometry& g, const PatchHashes& h, const PixelPosition& p) {
  const float px = float(p.tile_u) * g.unit + float(p.frac_u) * g.frac_scale;
  const float py = float(p.tile_v) * g.unit + float(p.frac_v) * g.frac_scale;
  Patches r;
  r.t = triangle_grid(px * g.inv_cell, py * g.inv_cell);
  for (int k = 0; k < 3; ++k) {
    const std::int32_t vx = r.t.vx[k], vy = r.t.vy[k];
    const float cx = (float(vx) + 0.5f * float(vy)) * g.cell, cy = kHalfSqrt3 * float(vy) * g.cell;
    const float centre_x = g.lo[0] + (float(h.x.colour(vx, vy)) + 0.5f) * g.step[0];
    const float centre_y = g.lo[1] + (float(h.y.colour(vx, vy)) + 0.5f) * g.step[1];
    r.ex[k] = px - cx + centre_x;
    r.ey[k] = py - cy + centre_y;
  }
  return r;
}

// The anisotropic fetch at exemplar texel (ex, ey): the mean of the footprint's taps.
template <class Levels>
std::array<float, 4> fetch(const Levels& levels, const Geometry& g, float ex, float ey, const Footprint& f) {
  std::array<float, 4> sum{0, 0, 0, 0};
  for (int i = 0; i < f.taps; ++i) {
    const float ox = float(tap_offset(f.axis_u, i, f.taps)) * g.frac_scale;
    const float oy = float(tap_offset(f.axis_v, i, f.taps)) * g.frac_scale;
    const std::array<float, 4> c =
        sample_trilinear(levels, (ex + ox) * g.inv_size[0], (ey + oy) * g.inv_size[1], f.lod);
    for (int k = 0; k < 4; ++k) sum[std::size_t(k)] += c[std::size_t(k)];
  }
  for (float& v : sum) v /= float(f.taps);
  return sum;
}

}  // namespace

std::array<float, 4> sample_hex(const ExemplarSurface& s, const PatchHashes& h, const PixelPosition& p,
                                const Footprint& f, int unit_px) {
  const Geometry g(s, unit_px);
  const Patches q = patches(g, h, p);
  std::array<std::array<float, 4>, 3> c;
  float W[3], sum = 0;
  for (int k = 0; k < 3; ++k) {
    c[std::size_t(k)] = fetch(s.levels, g, q.ex[k], q.ey[k], f);
    const auto& v = c[std::size_t(k)];
    const float lum = (v[0] / 255.0f) * 0.299f + (v[1] / 255.0f) * 0.587f + (v[2] / 255.0f) * 0.114f;
    const float w = q.t.w[k], w2 = w * w, w4 = w2 * w2;
    W[k] = (0.4f + 0.6f * lum) * (w4 * w2 * w);  // Mikkelsen 2022: D_i w_i^7
    sum += W[k];
  }
  std::array<float, 4> out{0, 0, 0, 0};
  for (int k = 0; k < 3; ++k)
    for (int ch = 0; ch < 4; ++ch) out[std::size_t(ch)] += (W[k] / sum) * c[std::size_t(k)][std::size_t(ch)];
  return out;
}

std::array<float, 4> sample_hpn(const ExemplarSurface& s, const PatchHashes& h, const PixelPosition& p,
                                const Footprint& f, int unit_px) {
  const Geometry g(s, unit_px);
  const Patches q = patches(g, h, p);
  float G[3] = {0, 0, 0};
  for (int k = 0; k < 3; ++k) {
    const std::array<float, 4> v = fetch(s.gaussian, g, q.ex[k], q.ey[k], f);
    for (int ch = 0; ch < 3; ++ch) G[ch] += q.t.w[k] * v[std::size_t(ch)];
  }
  // Heitz & Neyret 2018: the blend of Gaussians keeps mean 1/2 and, divided by the norm of the
  // weights, the variance of the input.
  const float norm = std::sqrt(q.t.w[0] * q.t.w[0] + q.t.w[1] * q.t.w[1] + q.t.w[2] * q.t.w[2]);
  const float levels = float(s.lut.height);
  const float lod = std::clamp(f.lod + 0.5f * std::log2(float(f.taps)), 0.0f, levels - 1.0f);
  const float t = (lod + 0.5f) / levels;
  float v[3];
  for (int ch = 0; ch < 3; ++ch)
    v[ch] = sample_bilinear_clamped(s.lut, (G[ch] - 0.5f) / norm + 0.5f, t)[std::size_t(ch)];
  std::array<float, 4> out{0, 0, 0, 255};
  for (int ch = 0; ch < 3; ++ch) {
    const float c = s.mean[std::size_t(ch)] + s.basis[std::size_t(ch)] * v[0] + s.basis[std::size_t(3 + ch)] * v[1] +
                    s.basis[std::size_t(6 + ch)] * v[2];
    out[std::size_t(ch)] = std::clamp(c, 0.0f, 1.0f) * 255.0f;
  }
  return out;
}

namespace {

std::string f9(float v) {
  return fmt::format("{:.9g}", v);
}
std::string float_literal(float v) {  // a GLSL float literal that reads back as v
  std::string s = f9(v);
  if (s.find_first_of(".eE") == std::string::npos) s += ".0";
  return s;
}

std::string common_glsl(const ExemplarSurface& s, const PatchHashes& h, int unit_px, bool uniform_tables) {
  const Geometry g(s, unit_px);
  const GlslTables tables = uniform_tables ? GlslTables::Uniform : GlslTables::Inline;
  std::string t = fmt::format("#define TK_TILE_PX {}\n", unit_px);
  t += fmt::format(
      "const float TK_CELL = {}, TK_INV_CELL = {}, TK_FRAC_SCALE = {};\n"
      "const vec2 TK_CENTRE_LO = vec2({}, {}), TK_CENTRE_STEP = vec2({}, {}), TK_INV_SIZE = vec2({}, {});\n",
      float_literal(g.cell), float_literal(g.inv_cell), float_literal(g.frac_scale), float_literal(g.lo[0]),
      float_literal(g.lo[1]), float_literal(g.step[0]), float_literal(g.step[1]), float_literal(g.inv_size[0]),
      float_literal(g.inv_size[1]));
  t += "uniform highp sampler2D tk_exemplar;\n";
  t += glsl_floor_mod();
  t += colour_hash_glsl(h.x, "tk_patch_x", tables);
  t += colour_hash_glsl(h.y, "tk_patch_y", tables);
  t += anisotropic_glsl();
  t += fmt::format(
      "// the triangle grid (Heitz & Neyret 2018): g in triangle sides\n"
      "void tk_triangle_grid(vec2 g, out vec3 w, out ivec2 v1, out ivec2 v2, out ivec2 v3) {{\n"
      "  float sx = g.x - {} * g.y, sy = {} * g.y;\n"
      "  float bx = floor(sx), by = floor(sy);\n"
      "  float fx = sx - bx, fy = sy - by, z = 1.0 - fx - fy;\n"
      "  float s = z <= 0.0 ? 1.0 : 0.0, s2 = 2.0 * s - 1.0;\n"
      "  w = vec3(-z * s2, s - fy * s2, s - fx * s2);\n"
      "  ivec2 b = ivec2(int(bx), int(by));\n"
      "  int si = int(s);\n"
      "  v1 = b + ivec2(si, si);\n"
      "  v2 = b + ivec2(si, 1 - si);\n"
      "  v3 = b + ivec2(1 - si, si);\n"
      "}}\n"
      "// where vertex v's patch shows texel p of the plane: v's position moved to its random centre\n"
      "vec2 tk_patch_point(vec2 p, ivec2 v) {{\n"
      "  float cx = (float(v.x) + 0.5 * float(v.y)) * TK_CELL, cy = {} * float(v.y) * TK_CELL;\n"
      "  float centre_x = TK_CENTRE_LO.x + (float(tk_patch_x(v)) + 0.5) * TK_CENTRE_STEP.x;\n"
      "  float centre_y = TK_CENTRE_LO.y + (float(tk_patch_y(v)) + 0.5) * TK_CENTRE_STEP.y;\n"
      "  return vec2(p.x - cx + centre_x, p.y - cy + centre_y);\n"
      "}}\n"
      "// the anisotropic fetch at exemplar texel e (texture/anisotropic.hpp)\n"
      "vec4 tk_fetch(vec2 e, int taps, float lod, ivec2 axis) {{\n"
      "  vec4 sum = vec4(0.0);\n"
      "  for (int i = 0; i < taps; ++i) {{\n"
      "    float ox = float(tk_tap_offset(axis.x, i, taps)) * TK_FRAC_SCALE;\n"
      "    float oy = float(tk_tap_offset(axis.y, i, taps)) * TK_FRAC_SCALE;\n"
      "    sum += textureLod(tk_exemplar, vec2((e.x + ox) * TK_INV_SIZE.x, (e.y + oy) * TK_INV_SIZE.y), lod);\n"
      "  }}\n"
      "  return sum / float(taps);\n"
      "}}\n"
      "vec2 tk_texel(ivec2 tile, ivec2 frac) {{\n"
      "  return vec2(float(tile.x) * float(TK_TILE_PX) + float(frac.x) * TK_FRAC_SCALE,\n"
      "              float(tile.y) * float(TK_TILE_PX) + float(frac.y) * TK_FRAC_SCALE);\n"
      "}}\n",
      float_literal(kSkewX), float_literal(kSkewY), float_literal(kHalfSqrt3));
  return t;
}

}  // namespace

std::string hex_glsl(const ExemplarSurface& s, const PatchHashes& h, int unit_px, bool uniform_tables) {
  return common_glsl(s, h, unit_px, uniform_tables) +
         "// hex tiling (Mikkelsen 2022): W_i = (0.4 + 0.6 L_i) w_i^7, normalised\n"
         "vec4 tk_sample(ivec2 tile, ivec2 frac, int taps, float lod, ivec2 axis) {\n"
         "  vec2 p = tk_texel(tile, frac);\n"
         "  vec3 w;\n"
         "  ivec2 v1, v2, v3;\n"
         "  tk_triangle_grid(p * TK_INV_CELL, w, v1, v2, v3);\n"
         "  vec4 c1 = tk_fetch(tk_patch_point(p, v1), taps, lod, axis);\n"
         "  vec4 c2 = tk_fetch(tk_patch_point(p, v2), taps, lod, axis);\n"
         "  vec4 c3 = tk_fetch(tk_patch_point(p, v3), taps, lod, axis);\n"
         "  vec3 lum = vec3(c1.r * 0.299 + c1.g * 0.587 + c1.b * 0.114, c2.r * 0.299 + c2.g * 0.587 + c2.b * 0.114,\n"
         "                  c3.r * 0.299 + c3.g * 0.587 + c3.b * 0.114);\n"
         "  vec3 w2 = w * w, w4 = w2 * w2;\n"
         "  vec3 W = (0.4 + 0.6 * lum) * (w4 * w2 * w);\n"
         "  float sum = W.x + W.y + W.z;\n"
         "  return (W.x / sum) * c1 + (W.y / sum) * c2 + (W.z / sum) * c3;\n"
         "}\n";
}

std::string hpn_glsl(const ExemplarSurface& s, const PatchHashes& h, int unit_px, bool uniform_tables) {
  std::string t = common_glsl(s, h, unit_px, uniform_tables);
  t += "uniform highp sampler2D tk_lut;  // the inverse transformation per level (RGBA16F)\n";
  t += fmt::format("const float TK_LUT_LEVELS = {};\n", float_literal(float(s.lut.height)));
  t += fmt::format("const vec3 TK_MEAN = vec3({}, {}, {});\n", float_literal(s.mean[0]), float_literal(s.mean[1]),
                   float_literal(s.mean[2]));
  t += fmt::format("const mat3 TK_BASIS = mat3({}, {}, {}, {}, {}, {}, {}, {}, {});\n", float_literal(s.basis[0]),
                   float_literal(s.basis[1]), float_literal(s.basis[2]), float_literal(s.basis[3]),
                   float_literal(s.basis[4]), float_literal(s.basis[5]), float_literal(s.basis[6]),
                   float_literal(s.basis[7]), float_literal(s.basis[8]));
  t += "// histogram-preserving blending (Heitz & Neyret 2018)\n"
       "vec4 tk_sample(ivec2 tile, ivec2 frac, int taps, float lod, ivec2 axis) {\n"
       "  vec2 p = tk_texel(tile, frac);\n"
       "  vec3 w;\n"
       "  ivec2 v1, v2, v3;\n"
       "  tk_triangle_grid(p * TK_INV_CELL, w, v1, v2, v3);\n"
       "  vec3 G = w.x * tk_fetch(tk_patch_point(p, v1), taps, lod, axis).rgb +\n"
       "           w.y * tk_fetch(tk_patch_point(p, v2), taps, lod, axis).rgb +\n"
       "           w.z * tk_fetch(tk_patch_point(p, v3), taps, lod, axis).rgb;\n"
       "  float norm = sqrt(w.x * w.x + w.y * w.y + w.z * w.z);\n"
       "  float l = clamp(lod + 0.5 * log2(float(taps)), 0.0, TK_LUT_LEVELS - 1.0);\n"
       "  float t = (l + 0.5) / TK_LUT_LEVELS;\n"
       "  vec3 g = (G - 0.5) / norm + 0.5;\n"
       "  vec3 d = vec3(textureLod(tk_lut, vec2(g.x, t), 0.0).x, textureLod(tk_lut, vec2(g.y, t), 0.0).y,\n"
       "                textureLod(tk_lut, vec2(g.z, t), 0.0).z);  // the decorrelated channels\n"
       "  vec3 c = vec3(TK_MEAN.x + TK_BASIS[0].x * d.x + TK_BASIS[1].x * d.y + TK_BASIS[2].x * d.z,\n"
       "                TK_MEAN.y + TK_BASIS[0].y * d.x + TK_BASIS[1].y * d.y + TK_BASIS[2].y * d.z,\n"
       "                TK_MEAN.z + TK_BASIS[0].z * d.x + TK_BASIS[1].z * d.y + TK_BASIS[2].z * d.z);\n"
       "  return vec4(clamp(c, 0.0, 1.0), 1.0);\n"
       "}\n";
  return t;
}

}  // namespace tilekit
