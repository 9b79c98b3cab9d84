#pragma once
// The tiles sampler of atlas.glsl (render/glsl_sampler.hpp) in the languages engines take, made
// from that one GLSL ES 3.0 text (one source of tables and constants: the tiling, the packing
// position and the anisotropic taps are written once, in glsl_sampler_library):
//  - GLSL 4.50 for Vulkan (atlas.vk.glsl): the atlas a combined image sampler at
//    layout(set = TK_SET, binding = TK_BINDING) (both 0 unless defined before the text); compiles
//    with `glslangValidator -V` to SPIR-V that `spirv-val` accepts;
//  - HLSL, Shader Model 5 and later (atlas.hlsl): Texture2D tk_atlas : register(TK_ATLAS_REGISTER)
//    and SamplerState tk_atlas_sampler : register(TK_SAMPLER_REGISTER) (t0 and s0 unless
//    defined), float4 tk_texture(float2 uv, float2 duvdx, float2 duvdy) (ddx(uv), ddy(uv));
//    compiles with glslang's HLSL front end (`glslangValidator -D -V`).
//  - WGSL (atlas.wgsl; WebGPU has no preprocessor, so wgsl_sampler writes it from the same tables
//    and constants, the C++ hash's permutation tables and the packing's positions, operation for
//    operation as glsl_sampler_library): tk_atlas (texture_2d<f32>) and tk_atlas_sampler at
//    @group(0) @binding(0) and (1), fn tk_texture(uv: vec2<f32>, duvdx: vec2<f32>, duvdy:
//    vec2<f32>) -> vec4<f32> (dpdx(uv), dpdy(uv)).
// The text's types and built-ins map one to one (vec2 -> float2, textureLod -> SampleLevel, ...);
// what differs in syntax (constant arrays, global constants, the atlas's declaration) is rewritten
// line by line, and a line the rewrite does not know is an error (std::logic_error), not a guess.
#include <string>

#include "atlas/lookup.hpp"
#include "tiling/direct_tiling.hpp"

namespace tilekit {

enum class ShaderLanguage { GlslEs, GlslVulkan, Hlsl, Wgsl };
const char* shader_language_name(ShaderLanguage l);       // "glsl-es", "glsl-vulkan", "hlsl", "wgsl"
const char* shader_language_extension(ShaderLanguage l);  // ".glsl", ".vk.glsl", ".hlsl", ".wgsl"

// glsl_sampler_library's text (GlslTables::Inline: every table a constant array) in `language`.
// (Not for Wgsl: std::logic_error.)
std::string sampler_in_language(const std::string& glsl_es_library, ShaderLanguage language);

// The WGSL tiles library: the tiling with its tables inline, the packing position (a table), the
// anisotropic footprint and taps, the same operations in the same order as the GLSL.
std::string wgsl_sampler(const AtlasLookup& lookup, float texels_per_tile, const DirectTiling& tiling);

}  // namespace tilekit
