#pragma once
// The GLSL ES 3.0 samplers of the three methods of render/cpu_renderer.hpp, line for line the CPU
// reference's operations:
//  - tiles (thesis sec. 5.4): the direct stochastic tiling as tiling/direct_tiling_glsl.hpp
//    generates it (bit-identical to the C++), the packing position (atlas/lookup.hpp), and per
//    anisotropic tap (render/anisotropic.hpp) a textureLod of the mip-mapped atlas. The renderer
//    and the preview page read the tiling from small integer textures (glsl_table_textures), made
//    by the C++ tiling itself: with the permutation hash the atlas cell of each tile of one
//    period (the tiling repeats every N tiles), so a tile costs one texelFetch; with the
//    long-period hash, whose period is too long for that, each permutation table over one period
//    (one texelFetch per table gives the table's part of the colours at a tile's four corners);
//  - hex and hpn: render/baseline_samplers.hpp.
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
//   ivec2 tk_tile_cell(ivec2 tile);                    // both: the (row, col) of the tile at `tile`
//   vec4 tk_sample(ivec2 tile, ivec2 frac, int taps, float lod, ivec2 axis);  // frac: 16 bits
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "render/anisotropic.hpp"
#include "render/cpu_renderer.hpp"
#include "render/shader_languages.hpp"
#include "render/view.hpp"
#include "tiling/direct_tiling_glsl.hpp"

namespace tilekit {

// What the fragment shader of the headless renderer (gl_renderer.hpp) outputs.
enum class GlslMode {
  Texture,       // the rendered texture (the view's row table, render/view.hpp)
  AtlasCell,     // tiles: the atlas cell of the tile at (x, y) + tk_origin: col, row as 16-bit pairs (tests)
  PlainTexture,  // tiles: one textureLod of the atlas per fragment, no tiling (the benchmark baseline)
  // tiles, a view whose every pixel has the same footprint of one tap (a flat view): Texture with
  // the level of detail a uniform, tk_lod, set from the CPU's anisotropic_footprint, and the
  // atlas cell of each tile read from a texture of the view's tiles (tk_window: glsl_tile_window)
  // instead of evaluating the lattice hash. GlRenderer chooses it for such views (the preview,
  // whose view changes, keeps Texture). The same pixels; on llvmpipe 1.6x (perm) to 3.3x (long-period) as fast
  // (BENCHMARKS.md).
  FlatTexture,
};

// texels_per_tile: the atlas's level-0 texels a tile (atlas_texels_per_tile).
std::string glsl_sampler_library(const AtlasLookup& lookup, float texels_per_tile, const DirectTiling& tiling,
                                 GlslTables tables);
// The tiles library as a file (atlas.glsl; atlas.vk.glsl and atlas.hlsl in the other languages of
// render/shader_languages.hpp): a header comment with the API and how it was made.
std::string glsl_sampler_file(const TextureAtlas& atlas, const RenderOptions& o,
                              ShaderLanguage language = ShaderLanguage::GlslEs);
// The library of any method, its tables as uniforms or integer textures (one text for every seed;
// the browser preview uses this same text).
std::string glsl_method_library(const RenderSource& source, const RenderOptions& o);
// The complete fragment shader of the renderer and of the preview (#version 300 es, main()).
std::string glsl_fragment_shader(const RenderSource& source, const RenderOptions& o, GlslMode mode);
std::string glsl_vertex_shader();  // a full-screen triangle

// The atlas cell of every tile a view shows (FlatTexture's tk_window, an RG16UI texture): tile
// (u0 + i, v0 + j) at texel (i, j), (row, col) of the packing, from the same C++ tiling as the
// CPU renderer. None where the view spans kMaxTileWindow tiles or more along an axis.
struct GlslTileWindow {
  std::int32_t u0 = 0, v0 = 0;
  int cols = 0, rows = 0;
  std::vector<std::uint16_t> cells;  // (row, col) per tile, row-major
};
inline constexpr int kMaxTileWindow = 4096;
std::optional<GlslTileWindow> glsl_tile_window(const TextureAtlas& atlas, const ViewRows& rows, int width,
                                               const RenderOptions& o);

// Whether every pixel of a view has the same footprint with one tap (what FlatTexture needs), and
// that footprint: no shear (dudy_step 0) and the same derivatives on every row.
bool uniform_footprint(const ViewRows& rows, float texels_per_tile, int max_aniso, Footprint* footprint = nullptr);
// The uniform tables (uniform ivec4 NAME[...]) of glsl_fragment_shader for the seed and hash of o
// (hex and hpn).
std::vector<std::pair<std::string, std::vector<std::int32_t>>> glsl_table_uniforms(const RenderSource& source,
                                                                                   const RenderOptions& o);
// An integer texture of glsl_fragment_shader, read by texelFetch (GL_NEAREST, one level):
// RG8UI (2 channels) or RGBA8UI (4), rows from the top (y = 0).
struct GlslTableTexture {
  std::string sampler;  // the usampler2D uniform
  int unit = 0, width = 0, height = 0, channels = 4;
  std::vector<std::uint8_t> texels;
};
// Whether the tiles method reads its tiling as one `tk_tiles` texture of atlas cells: with the
// permutation hash (period N = 256 both ways) and an atlas of at most 256 x 256 tiles.
bool glsl_tile_cell_texture(const AtlasLookup& lookup, HashKind hash);
// The tiles method's tiling for the seed and hash of o: `tk_tiles` (glsl_tile_cell_texture: (row,
// col) of tile (x, y), x, y < N) or else `tk_latticeK_T` (tiling/direct_tiling_glsl.hpp's
// glsl_hash_texture of each hash). Units from 3 (0: the atlas, 1: the view's rows, 2: hpn's
// look-up table). None for hex and hpn.
std::vector<GlslTableTexture> glsl_table_textures(const RenderSource& source, const RenderOptions& o);

}  // namespace tilekit
