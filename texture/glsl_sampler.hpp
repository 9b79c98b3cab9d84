#pragma once
// The GLSL ES 3.0 samplers of the three methods of texture/cpu_renderer.hpp, line for line the CPU
// reference's operations:
//  - tiles (thesis sec. 5.4): the direct stochastic tiling as tiling/direct_tiling_glsl.hpp
//    generates it (bit-identical to the C++), the packing position (atlas/lookup.hpp), and per
//    anisotropic tap (texture/anisotropic.hpp) a textureLod of the mip-mapped atlas;
//  - hex and hpn: texture/baseline_samplers.hpp.
// The level of detail comes from derivatives of the virtual texture coordinate, not of the atlas
// coordinate, which jumps at every tile border.
//
// API of the tiles library (atlas.glsl; paste it after `#version 300 es` and the precision
// statements):
//   uniform sampler2D tk_atlas;                        // the atlas with its mip chain, GL_REPEAT
//   vec4 tk_texture(vec2 uv, vec2 duvdx, vec2 duvdy);  // uv in tiles, u east, v south; at most
//                                                      // TK_MAX_ANISO (default 16) taps
//   int tk_virtual_tile(ivec2 tile);                   // the tiling
//   ivec2 tk_tile_position(int tile);                  // (row, col) in the atlas
//   vec4 tk_sample(ivec2 tile, ivec2 frac, int taps, float lod, ivec2 axis);  // frac: 16 bits
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "texture/cpu_renderer.hpp"
#include "tiling/direct_tiling_glsl.hpp"

namespace tilekit {

// What the fragment shader of the headless renderer (gl_renderer.hpp) outputs.
enum class GlslMode {
  Texture,        // the rendered texture (the view's row table, texture/view.hpp)
  LatticeColour,  // tiles: colour of lattice hash 0 at (x, y) + tk_origin, in red (tests: the hash is bit-identical)
  TileIndex,      // tiles: virtual tile index at (x, y) + tk_origin, as 4 bytes (tests)
  PlainTexture,   // tiles: one textureLod of the atlas per fragment, no tiling (the benchmark baseline)
};

std::string glsl_sampler_library(const AtlasLookup& lookup, int tile_px, const DirectTiling& tiling, GlslTables tables);
// The tiles library as a file (atlas.glsl): a header comment with the API and how it was made.
std::string glsl_sampler_file(const TextureAtlas& atlas, const RenderOptions& o);
// The library of any method, tables as uniforms (one text for every seed; the browser preview
// uses this same text).
std::string glsl_method_library(const RenderSource& source, const RenderOptions& o);
// The complete fragment shader of the renderer and of the preview (#version 300 es, main()).
std::string glsl_fragment_shader(const RenderSource& source, const RenderOptions& o, GlslMode mode);
std::string glsl_vertex_shader();  // a full-screen triangle
// The uniform tables (uniform ivec4 NAME[...]) of glsl_fragment_shader for the seed and hash of o.
std::vector<std::pair<std::string, std::vector<std::int32_t>>> glsl_table_uniforms(const RenderSource& source,
                                                                                   const RenderOptions& o);

}  // namespace tilekit
