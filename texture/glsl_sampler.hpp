#pragma once
// The GLSL ES 3.0 texture sampler of tile-based texture mapping (thesis sec. 5.4), grown from the
// atlas lookup snippet (atlas/lookup_formats.cpp): the same lattice hashes as the C++ tilings
// (tiling/lattice_hash.hpp, bit for bit: integer arithmetic only), the same direct stochastic
// tiling, the packing position, and trilinear sampling of the mip-mapped atlas at a level of
// detail computed from derivatives of the virtual texture coordinate (not of the atlas
// coordinate, which jumps at every tile border).
//
// API of the library part (paste it after `#version 300 es` and the precision statements):
//   uniform sampler2D tk_atlas;                     // the atlas with its mip chain, GL_REPEAT
//   vec4 tk_texture(vec2 uv, vec2 duvdx, vec2 duvdy);  // uv in tiles, u east, v south
//   int tk_virtual_tile(ivec2 tile);                // the tiling
//   ivec2 tk_tile_position(int tile);               // (row, col) in the atlas
//   vec4 tk_sample_tile(ivec2 tile, vec2 f, float lod);
#include <string>

#include "texture/cpu_renderer.hpp"
#include "texture/texture_atlas.hpp"

namespace tilekit {

// What the fragment shader of the headless renderer (gl_renderer.hpp) outputs.
enum class GlslMode {
  Texture,        // the rendered texture (the view's row table, texture/view.hpp)
  LatticeColour,  // lattice colour of hash 0 at (x, y) + tk_origin, in red (tests: the hash is bit-identical)
  TileIndex,      // virtual tile index at (x, y) + tk_origin, as 4 bytes (tests)
  PlainTexture,   // one textureLod of the atlas per fragment, no tiling (the benchmark baseline)
};

std::string glsl_sampler_library(const AtlasLookup& lookup, int tile_px, const VirtualTiling& tiling);
// The library as a file: a header comment with the API and how the file was made.
std::string glsl_sampler_file(const TextureAtlas& atlas, const RenderOptions& o);
// The complete fragment shader of the headless renderer (#version 300 es, main()).
std::string glsl_fragment_shader(const AtlasLookup& lookup, int tile_px, const VirtualTiling& tiling, GlslMode mode);
std::string glsl_vertex_shader();  // a full-screen triangle

}  // namespace tilekit
