#pragma once
// The GLSL ES 3.0 text of the lattice hashes and of the direct stochastic tiling (thesis 3.3),
// generated here, in one place, from the same ColourHash tables that the C++ code evaluates
// (lattice_hash.hpp, direct_tiling.hpp): integer arithmetic only, so a shader gives the same
// colour and the same tile as the C++ at every lattice point, bit for bit (tests/render).
//
// Axis convention, the one of lattice_tiling.hpp and of every part of Tilekit (the atlas lookup,
// the renderers, the shaders): x grows to the east, y to the south (image rows); tile (x, y)
// covers [x, x+1) x [y, y+1) and its corners are the lattice points NW = (x, y), NE = (x+1, y),
// SW = (x, y+1), SE = (x+1, y+1).
//
// What the text of direct_tiling_glsl defines:
//   int tk_mod(int v, int n, int wrap);   // floored v mod n (negative coordinates too)
//   int tk_latticeK(ivec2 p);             // hash K's colour at p
//   ivec4 tk_latticeK(ivec2 p);           // hash K's colours at NW, NE, SW, SE of tile p
//   int tk_virtual_tile(ivec2 tile);      // the tile index (thesis eq. 2.5 corner, 2.2 Wang)
#include <cstdint>
#include <string>
#include <vector>

#include "tiling/direct_tiling.hpp"

namespace tilekit {

// Where the permutation tables live in the text.
enum class GlslTables {
  Inline,   // `const int` arrays: a self-contained snippet for one seed
  Uniform,  // `uniform ivec4 NAME_P[...]`, set from glsl_hash_uniforms: one text for every seed
  Texture,  // `uniform usampler2D NAME_T`, texels from glsl_hash_texture: one text for every seed,
            // and the fastest on a CPU rasteriser (one texelFetch per table instead of two
            // dynamically indexed reads per table and corner)
};

// tk_mod, which every generated hash function calls; once per shader.
std::string glsl_floor_mod();
// The GLSL expression of the floored `v` mod n (tk_mod, or an unsigned remainder where 2^32 is a
// multiple of n).
std::string glsl_mod(const std::string& v, std::uint32_t n);

// One lattice hash (ColourHash::colour, thesis eq. 3.3 or 3.6) as GLSL:
//   int NAME(ivec2 p)      the colour at p
//   ivec4 NAME4(ivec2 p)   the colours at p, p + (1,0), p + (0,1), p + (1,1)
// Uniform tables are named NAME_P.
std::string colour_hash_glsl(const ColourHash& h, const std::string& name, GlslTables tables);
// The values of NAME_P for GlslTables::Uniform: the permutation tables concatenated and padded
// to whole ivec4s (4 ints each).
std::vector<std::int32_t> glsl_hash_uniforms(const ColourHash& h);

// The texels of NAME_T for GlslTables::Texture, an RGBA8UI texture of width sum N_i and height
// max N_i: component i over one period, N_i x N_i texels from column o_i = N_0 + ... + N_{i-1};
// texel (o_i + a, b) holds, for the lattice points (a, b), (a+1, b), (a, b+1), (a+1, b+1) (indices
// mod N_i), the component's value P_i[(P_i[a] + b) mod N_i] reduced mod C. As the range N_j is a
// multiple of C, (sum mod N_j) mod C = sum mod C, so the colours at the four corners of tile (x, y)
// are the sum of one texel per component, mod C. C <= 255.
struct GlslHashTexture {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
};
GlslHashTexture glsl_hash_texture(const ColourHash& h);

// tk_mod, tk_lattice0 (and tk_lattice1 for Wang tiles) and tk_virtual_tile. The uniform
// tables are tk_lattice0_P and tk_lattice1_P, the textures tk_lattice0_T and tk_lattice1_T.
std::string direct_tiling_glsl(const DirectTiling& t, GlslTables tables);

}  // namespace tilekit
