#include "render/glsl_sampler.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "base/text_escape.hpp"
#include "render/anisotropic.hpp"
#include "render/baseline_samplers.hpp"

namespace tilekit {

namespace {

// The renderer's tiling of the permutation hash is one look-up texture: the tiling repeats with
// the hash's period N in x and in y (thesis 3.4.1), so the atlas cell of every tile is known from
// N x N of them. A texel holds the cell's row and column in one byte each.
bool cell_texture(const AtlasLookup& l, const DirectTiling& t, GlslTables tables) {
  return tables == GlslTables::Texture && glsl_tile_cell_texture(l, t.hash_kind());
}

// A float as a GLSL literal: an integer as one (TK_TILE_PX 64), else 9 significant digits (the
// same float back).
std::string glsl_number(float v) {
  if (v == std::floor(v) && std::abs(v) < 1e7f) return fmt::format("{}", std::int64_t(v));
  return fmt::format("{:.9g}", double(v));
}

}  // namespace

bool glsl_tile_cell_texture(const AtlasLookup& l, HashKind hash) {
  return hash == HashKind::Permutation && l.rows <= 256 && l.cols <= 256;
}

std::string glsl_sampler_library(const AtlasLookup& l, float texels_per_tile, const DirectTiling& tiling,
                                 GlslTables tables) {
  check_same_set(l, tiling);
  std::string g;
  // TK_TILE_PX: the texels a tile, a float literal where the atlas was resampled to a power of two
  g += fmt::format("#define TK_COLORS {}\n#define TK_ROWS {}\n#define TK_COLS {}\n#define TK_TILE_PX {}\n", l.colours,
                   l.rows, l.cols, glsl_number(texels_per_tile));
  g += "#ifndef TK_MAX_ANISO\n#define TK_MAX_ANISO 16\n#endif\n";
  g += fmt::format("const float TK_INV_ROWS = {:.9g}, TK_INV_COLS = {:.9g};\n", 1.0f / float(l.rows),
                   1.0f / float(l.cols));
  g += "uniform highp sampler2D tk_atlas;\n";
  if (cell_texture(l, tiling, tables)) {
    const std::uint32_t n = std::uint32_t(tiling.hashes()[0]->x_period());
    g += glsl_floor_mod();
    g += fmt::format(
        "uniform highp usampler2D tk_tiles;  // (row, col) of tile (x, y) of the tiling, x, y < {0}\n"
        "ivec2 tk_tile_cell(ivec2 tile) {{  // the tiling's period is {0} tiles both ways\n"
        "  return ivec2(texelFetch(tk_tiles, ivec2({1}, {2}), 0).xy);\n"
        "}}\n",
        n, glsl_mod("tile.x", n), glsl_mod("tile.y", n));
  } else {
    g += direct_tiling_glsl(tiling, tables);
    g += lookup_glsl_position(l);
    g += "ivec2 tk_tile_cell(ivec2 tile) {  // the tile's (row, col) in the packing\n"
         "  return tk_tile_position(tk_virtual_tile(tile));\n"
         "}\n";
  }
  g += anisotropic_glsl();
  g += "// thesis 5.4: the tile's place in the packing plus the position f in [0,1)^2 inside the tile\n"
       "vec4 tk_sample_tile(ivec2 tile, vec2 f, float lod) {\n"
       "  ivec2 rc = tk_tile_cell(tile);\n"
       "  vec2 st = (vec2(float(rc.y), float(rc.x)) + f) * vec2(TK_INV_COLS, TK_INV_ROWS);\n"
       "  return textureLod(tk_atlas, st, lod);\n"
       "}\n"
       "// the taps of a footprint (tk_footprint), each through the tiling to its own tile\n"
       "vec4 tk_sample(ivec2 tile, ivec2 frac, int taps, float lod, ivec2 axis) {\n"
       "  if (taps == 1) return tk_sample_tile(tile, vec2(frac) / 65536.0, lod);  // the loop's one tap\n"
       "  vec4 sum = vec4(0.0);\n"
       "  for (int i = 0; i < taps; ++i) {\n"
       "    ivec2 q = frac + ivec2(tk_tap_offset(axis.x, i, taps), tk_tap_offset(axis.y, i, taps));\n"
       "    sum += tk_sample_tile(tile + (q >> 16), vec2(q & 65535) / 65536.0, lod);\n"
       "  }\n"
       "  return sum / float(taps);\n"
       "}\n"
       "// the hardware's anisotropic filter: one fetch with the virtual texture's gradients (dx, dy in\n"
       "// tiles per pixel; the atlas coordinate jumps at tile borders, its own derivatives would not do),\n"
       "// whose taps may cross into the atlas neighbour, a valid one (the atlas is a toroidal tiling)\n"
       "vec4 tk_sample_grad(ivec2 tile, vec2 f, vec2 dx, vec2 dy) {\n"
       "  ivec2 rc = tk_tile_cell(tile);\n"
       "  vec2 scale = vec2(TK_INV_COLS, TK_INV_ROWS);\n"
       "  return textureGrad(tk_atlas, (vec2(float(rc.y), float(rc.x)) + f) * scale, dx * scale, dy * scale);\n"
       "}\n"
       "vec4 tk_texture_grad(vec2 uv, vec2 duvdx, vec2 duvdy) {  // set the atlas's anisotropy, up to 16\n"
       "  vec2 cell = floor(uv);\n"
       "  return tk_sample_grad(ivec2(cell), uv - cell, duvdx, duvdy);\n"
       "}\n"
       "// uv in tiles of the virtual texture (u east, v south), with its screen derivatives\n"
       "vec4 tk_texture(vec2 uv, vec2 duvdx, vec2 duvdy) {\n"
       "  vec2 cell = floor(uv);\n"
       "  int taps;\n"
       "  float lod;\n"
       "  ivec2 axis;\n"
       "  tk_footprint(duvdx, duvdy, TK_MAX_ANISO, taps, lod, axis);\n"
       "  return tk_sample(ivec2(cell), ivec2((uv - cell) * 65536.0), taps, lod, axis);\n"
       "}\n";
  return g;
}

std::string glsl_sampler_file(const TextureAtlas& a, const RenderOptions& o, ShaderLanguage language) {
  const DirectTiling tiling(a.lookup.kind, a.lookup.colours, o.hash, o.seed);
  std::string g = fmt::format(
      "// Generated by `tilekit texture atlas` (hash {}, seed {}): {} sampler for tile-based texture\n"
      "// mapping (thesis sec. 5.4) with a {}x{} atlas of the complete {} set over {} colours, {}-pixel tiles;\n"
      "// packing: {} ({}).\n",
      hash_kind_name(o.hash), o.seed,
      language == ShaderLanguage::GlslEs       ? "GLSL ES 3.0"
      : language == ShaderLanguage::GlslVulkan ? "GLSL 4.50 (Vulkan)"
      : language == ShaderLanguage::Hlsl       ? "HLSL (Shader Model 5+)"
                                               : "WGSL (WebGPU)",
      a.lookup.rows, a.lookup.cols, kind_name(a.lookup.kind), a.lookup.colours, a.tile_px,
      comment_text(a.lookup.source), comment_text(a.lookup.how));  // the user's text (a manifest's)
  switch (language) {
    case ShaderLanguage::GlslEs:
      g += "// Paste after `#version 300 es` and `precision highp float; precision highp int;`.\n"
           "// Bind the atlas (all mip levels, GL_LINEAR_MIPMAP_LINEAR, GL_REPEAT) to tk_atlas and call\n"
           "//   vec4 tk_texture(vec2 uv, vec2 duvdx, vec2 duvdy)\n"
           "// with uv in tiles of the infinite virtual texture (u east, v south) and its derivatives\n"
           "// (dFdx(uv), dFdy(uv));";
      break;
    case ShaderLanguage::GlslVulkan:
      g += "// Paste after `#version 450`. The atlas (atlas.ktx2: every mip level; a sampler with linear\n"
           "// filtering, linear mipmaps and VK_SAMPLER_ADDRESS_MODE_REPEAT) is the combined image sampler\n"
           "// tk_atlas at layout(set = TK_SET, binding = TK_BINDING), 0 and 0 unless defined before this\n"
           "// text. Call vec4 tk_texture(vec2 uv, vec2 duvdx, vec2 duvdy) with uv in tiles of the infinite\n"
           "// virtual texture (u east, v south) and its derivatives (dFdx(uv), dFdy(uv));";
      break;
    case ShaderLanguage::Hlsl:
      g += "// Include in a pixel shader. The atlas (atlas.ktx2: every mip level) is Texture2D tk_atlas at\n"
           "// register TK_ATLAS_REGISTER (t0) with SamplerState tk_atlas_sampler at TK_SAMPLER_REGISTER (s0;\n"
           "// trilinear, address mode wrap); define them before this text to move them. Call\n"
           "//   float4 tk_texture(float2 uv, float2 duvdx, float2 duvdy)\n"
           "// with uv in tiles of the infinite virtual texture (u east, v south) and ddx(uv), ddy(uv);";
      break;
    case ShaderLanguage::Wgsl:
      g += "// Prepend to a WGSL module. The atlas (atlas.ktx2: every mip level) is tk_atlas at @group(0)\n"
           "// @binding(0) and tk_atlas_sampler (linear min/mag/mipmap filters, address mode repeat) at\n"
           "// @binding(1); edit those two lines to move them. Call\n"
           "//   fn tk_texture(uv: vec2<f32>, duvdx: vec2<f32>, duvdy: vec2<f32>) -> vec4<f32>\n"
           "// with uv in tiles of the infinite virtual texture (u east, v south) and dpdx(uv), dpdy(uv);";
      break;
  }
  g += language == ShaderLanguage::Wgsl
           ? "\n// it filters anisotropically with up to TK_MAX_ANISO taps (a const below; 1 is trilinear). The\n"
             "// tiling is bit-identical to tilekit's C++.\n"
           : "\n// it filters anisotropically with up to TK_MAX_ANISO taps (define it before this text to change\n"
             "// it; 1 is trilinear). The tiling is bit-identical to tilekit's C++.\n";
  if (a.colour_space == ColourSpace::Srgb)
    g += "// The atlas's colour space is sRGB: upload it as an sRGB format (GL_SRGB8_ALPHA8,\n"
         "// VK_FORMAT_R8G8B8A8_SRGB, DXGI_FORMAT_R8G8B8A8_UNORM_SRGB, rgba8unorm-srgb), so that it is filtered\n"
         "// in linear light and tk_texture returns linear colour.\n";
  const float texels = atlas_texels_per_tile(a);
  if (language == ShaderLanguage::Wgsl) return g + wgsl_sampler(a.lookup, texels, tiling);
  return g + sampler_in_language(glsl_sampler_library(a.lookup, texels, tiling, GlslTables::Inline), language);
}

std::string glsl_method_library(const RenderSource& s, const RenderOptions& o) {
  switch (s.method) {
    case RenderMethod::Tiles: {
      const TextureAtlas& a = *s.atlas;
      return glsl_sampler_library(a.lookup, atlas_texels_per_tile(a),
                                  DirectTiling(a.lookup.kind, a.lookup.colours, o.hash, o.seed), GlslTables::Texture);
    }
    case RenderMethod::Hex:
      return hex_glsl(*s.exemplar, PatchHashes(o.hash, o.seed), s.unit_px(), true);
    case RenderMethod::Hpn:
      return hpn_glsl(*s.exemplar, PatchHashes(o.hash, o.seed), s.unit_px(), true);
  }
  return {};
}

std::vector<std::pair<std::string, std::vector<std::int32_t>>> glsl_table_uniforms(const RenderSource& s,
                                                                                   const RenderOptions& o) {
  if (s.method == RenderMethod::Tiles) return {};  // tables as textures: glsl_table_textures
  const PatchHashes h(o.hash, o.seed);
  return {{"tk_patch_x_P", glsl_hash_uniforms(h.x)}, {"tk_patch_y_P", glsl_hash_uniforms(h.y)}};
}

std::vector<GlslTableTexture> glsl_table_textures(const RenderSource& s, const RenderOptions& o) {
  if (s.method != RenderMethod::Tiles) return {};
  const AtlasLookup& l = s.atlas->lookup;
  const DirectTiling tiling(l.kind, l.colours, o.hash, o.seed);
  std::vector<GlslTableTexture> textures;
  if (cell_texture(l, tiling, GlslTables::Texture)) {
    const int n = int(tiling.hashes()[0]->x_period());
    std::vector<TileIndex> tiles(std::size_t(n) * std::size_t(n));
    tiling.fill(0, 0, n, n, tiles.data());
    GlslTableTexture t{"tk_tiles", 3, n, n, 2, std::vector<std::uint8_t>(tiles.size() * 2)};
    for (std::size_t i = 0; i < tiles.size(); ++i) {
      t.texels[2 * i] = std::uint8_t(l.positions[tiles[i]].first);
      t.texels[2 * i + 1] = std::uint8_t(l.positions[tiles[i]].second);
    }
    textures.push_back(std::move(t));
  } else {
    const auto hashes = tiling.hashes();
    for (std::size_t k = 0; k < hashes.size(); ++k) {
      GlslHashTexture h = glsl_hash_texture(*hashes[k]);
      textures.push_back({fmt::format("tk_lattice{}_T", k), 3 + int(k), h.width, h.height, 4, std::move(h.rgba)});
    }
  }
  return textures;
}

std::string glsl_vertex_shader() {
  return "#version 300 es\n"
         "void main() {  // one triangle covering the viewport\n"
         "  vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);\n"
         "  gl_Position = vec4(p, 0.0, 1.0);\n"
         "}\n";
}

std::optional<GlslTileWindow> glsl_tile_window(const TextureAtlas& a, const ViewRows& vr, int width,
                                               const RenderOptions& o) {
  if (vr.rows.empty() || width < 1) return std::nullopt;
  std::int64_t u0 = INT64_MAX, u1 = INT64_MIN, v0 = INT64_MAX, v1 = INT64_MIN;
  for (const ViewRow& r : vr.rows) {
    u0 = std::min<std::int64_t>(u0, r.tile_u0 + std::int64_t(r.frac_u0 >> kFracBits));
    u1 = std::max<std::int64_t>(
        u1, r.tile_u0 + std::int64_t((r.frac_u0 + std::uint32_t(width - 1) * r.step_u) >> kFracBits));
    v0 = std::min<std::int64_t>(v0, r.tile_v);
    v1 = std::max<std::int64_t>(v1, r.tile_v);
  }
  if (u1 - u0 >= kMaxTileWindow || v1 - v0 >= kMaxTileWindow) return std::nullopt;
  GlslTileWindow w{std::int32_t(u0), std::int32_t(v0), int(u1 - u0 + 1), int(v1 - v0 + 1), {}};
  std::vector<TileIndex> tiles(std::size_t(w.cols) * std::size_t(w.rows));
  DirectTiling(a.lookup.kind, a.lookup.colours, o.hash, o.seed).fill(u0, v0, w.rows, w.cols, tiles.data());
  w.cells.resize(tiles.size() * 2);
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    w.cells[2 * i] = std::uint16_t(a.lookup.positions[tiles[i]].first);
    w.cells[2 * i + 1] = std::uint16_t(a.lookup.positions[tiles[i]].second);
  }
  return w;
}

bool uniform_footprint(const ViewRows& vr, float texels_per_tile, int max_aniso, Footprint* footprint) {
  if (vr.rows.empty() || vr.dudy_step != 0) return false;
  const ViewRow& first = vr.rows.front();
  for (const ViewRow& r : vr.rows)
    if (r.dudx != first.dudx || r.dvdy != first.dvdy || r.dudy0 != first.dudy0) return false;
  const Footprint f = anisotropic_footprint(first.dudx, 0.0f, first.dudy0, first.dvdy, texels_per_tile, max_aniso);
  if (f.taps != 1) return false;
  if (footprint) *footprint = f;
  return true;
}

std::string glsl_fragment_shader(const RenderSource& s, const RenderOptions& o, GlslMode mode) {
  std::string g = "#version 300 es\nprecision highp float;\nprecision highp int;\nprecision highp isampler2D;\n";
  g += glsl_method_library(s, o);
  g += "uniform highp isampler2D tk_rows;  // per pixel row: (tile_u0, frac_u0, step_u, tile_v), (frac_v, dudx, dvdy, "
       "dudy0)\n"
       "uniform float tk_dudy_step;\n"
       "uniform int tk_height;\n"
       "uniform int tk_max_aniso;\n"
       "uniform ivec2 tk_origin;\n";
  if (mode == GlslMode::FlatTexture)
    g += "uniform float tk_lod;  // every pixel's footprint: one tap at this level\n"
         "uniform highp usampler2D tk_window;  // the atlas cell (row, col) of every tile the view shows\n"
         "uniform ivec2 tk_window0;  // the first of those tiles\n";
  // An sRGB atlas is an SRGB8_ALPHA8 texture (filtered in linear light); the render is encoded
  // back to sRGB here, as render_cpu does (render/sampling.hpp's srgb_encode_255).
  const bool srgb_out = s.method == RenderMethod::Tiles && s.atlas && s.atlas->colour_space == ColourSpace::Srgb &&
                        mode != GlslMode::AtlasCell;
  if (srgb_out)
    g += "vec3 tk_srgb_encode(vec3 c) {\n"
         "  c = clamp(c, 0.0, 1.0);\n"
         "  return mix(1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, 12.92 * c, lessThanEqual(c, vec3(0.0031308)));\n"
         "}\n";
  g += "out vec4 tk_colour;\n"
       "void main() {\n"
       "  ivec2 px = ivec2(gl_FragCoord.xy);\n"
       "  int j = tk_height - 1 - px.y;  // image row, 0 at the top\n";
  switch (mode) {
    case GlslMode::Texture:
      g += "  ivec4 r0 = texelFetch(tk_rows, ivec2(0, j), 0), r1 = texelFetch(tk_rows, ivec2(1, j), 0);\n"
           "  uint fu = uint(r0.y) + uint(px.x) * uint(r0.z);  // fixed point, texture/view.hpp\n"
           "  ivec2 tile = ivec2(r0.x + int(fu >> 16u), r0.w);\n"
           "  ivec2 frac = ivec2(int(fu & 65535u), r1.x);\n"
           "  float dudx = intBitsToFloat(r1.y), dvdy = intBitsToFloat(r1.z);\n"
           "  float dudy = intBitsToFloat(r1.w) + float(px.x) * tk_dudy_step;\n"
           "  int taps;\n"
           "  float lod;\n"
           "  ivec2 axis;\n";
      if (s.method == RenderMethod::Tiles && o.hardware_filter)
        g += "  tk_colour = tk_sample_grad(tile, vec2(frac) / 65536.0, vec2(dudx, 0.0), vec2(dudy, dvdy));\n";
      else
        g += "  tk_footprint(vec2(dudx, 0.0), vec2(dudy, dvdy), tk_max_aniso, taps, lod, axis);\n"
             "  tk_colour = tk_sample(tile, frac, taps, lod, axis);\n";
      break;
    case GlslMode::FlatTexture:
      g += "  ivec4 r0 = texelFetch(tk_rows, ivec2(0, j), 0);\n"
           "  int frac_v = texelFetch(tk_rows, ivec2(1, j), 0).x;\n"
           "  uint fu = uint(r0.y) + uint(px.x) * uint(r0.z);  // fixed point, texture/view.hpp\n"
           "  ivec2 tile = ivec2(r0.x + int(fu >> 16u), r0.w);\n"
           "  ivec2 rc = ivec2(texelFetch(tk_window, tile - tk_window0, 0).xy);  // tk_tile_cell(tile)\n"
           "  vec2 f = vec2(ivec2(int(fu & 65535u), frac_v)) / 65536.0;\n"
           "  vec2 st = (vec2(float(rc.y), float(rc.x)) + f) * vec2(TK_INV_COLS, TK_INV_ROWS);  // tk_sample_tile\n"
           "  tk_colour = textureLod(tk_atlas, st, tk_lod);\n";
      break;
    case GlslMode::PlainTexture:
      g += "  tk_colour = textureLod(tk_atlas, gl_FragCoord.xy * (1.0 / 1024.0), 0.0);\n";
      break;
    case GlslMode::AtlasCell:
      g += "  ivec2 rc = tk_tile_cell(ivec2(px.x, j) + tk_origin);\n"
           "  tk_colour = vec4(rc.y & 255, rc.y >> 8, rc.x & 255, rc.x >> 8) / 255.0;\n";
      break;
  }
  if (srgb_out) g += "  tk_colour.rgb = tk_srgb_encode(tk_colour.rgb);\n";
  return g + "}\n";
}

}  // namespace tilekit
