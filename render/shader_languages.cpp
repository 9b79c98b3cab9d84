#include "render/shader_languages.hpp"

#include <fmt/format.h>

#include <regex>
#include <sstream>
#include <stdexcept>

namespace tilekit {

namespace {

// HLSL names for GLSL's types and the built-ins the sampler uses (the rest: floor, sqrt, log2,
// min, max, clamp, abs, are the same).
const char* const kHlslPrelude =
    "#define vec2 float2\n#define vec3 float3\n#define vec4 float4\n"
    "#define ivec2 int2\n#define ivec3 int3\n#define ivec4 int4\n#define uvec2 uint2\n#define uvec4 uint4\n"
    "#define highp\n#define fract frac\n#define mix lerp\n"
    "#define floatBitsToInt asint\n#define intBitsToFloat asfloat\n"
    "#define textureLod(t, st, lod) t.SampleLevel(t##_sampler, st, lod)\n";

const char* const kAtlasGlslEs = "uniform highp sampler2D tk_atlas;";

}  // namespace

const char* shader_language_name(ShaderLanguage l) {
  return l == ShaderLanguage::GlslEs ? "glsl-es" : l == ShaderLanguage::GlslVulkan ? "glsl-vulkan" : "hlsl";
}

const char* shader_language_extension(ShaderLanguage l) {
  return l == ShaderLanguage::GlslEs ? ".glsl" : l == ShaderLanguage::GlslVulkan ? ".vk.glsl" : ".hlsl";
}

std::string sampler_in_language(const std::string& glsl, ShaderLanguage language) {
  if (language == ShaderLanguage::GlslEs) return glsl;
  // const T NAME[N] = T[N](   (a constant array: HLSL's is static const T NAME[N] = { ... };)
  static const std::regex array_open(R"(^const (\w+) (\w+)\[(\d+)\] = \w+\[\d+\]\((.*)$)");
  std::string out = language == ShaderLanguage::Hlsl ? kHlslPrelude : "";
  std::istringstream in(glsl);
  std::string line;
  bool in_array = false, atlas = false;
  while (std::getline(in, line)) {
    std::smatch m;
    if (line == kAtlasGlslEs) {
      atlas = true;
      if (language == ShaderLanguage::GlslVulkan)
        line =
            "#ifndef TK_SET\n#define TK_SET 0\n#endif\n#ifndef TK_BINDING\n#define TK_BINDING 0\n#endif\n"
            "layout(set = TK_SET, binding = TK_BINDING) uniform sampler2D tk_atlas;";
      else
        line =
            "#ifndef TK_ATLAS_REGISTER\n#define TK_ATLAS_REGISTER t0\n#endif\n"
            "#ifndef TK_SAMPLER_REGISTER\n#define TK_SAMPLER_REGISTER s0\n#endif\n"
            "Texture2D<float4> tk_atlas : register(TK_ATLAS_REGISTER);\n"
            "SamplerState tk_atlas_sampler : register(TK_SAMPLER_REGISTER);  // trilinear, wrap (repeat)";
    } else if (line.rfind("uniform ", 0) == 0) {
      throw std::logic_error("sampler_in_language: a uniform other than the atlas: " + line);
    } else if (language == ShaderLanguage::Hlsl && std::regex_match(line, m, array_open)) {
      std::string rest = m[4].str();
      in_array = true;
      if (rest.size() >= 2 && rest.compare(rest.size() - 2, 2, ");") == 0) {
        rest.replace(rest.size() - 2, 2, "};");
        in_array = false;
      }
      line = fmt::format("static const {} {}[{}] = {{{}", m[1].str(), m[2].str(), m[3].str(), rest);
    } else if (language == ShaderLanguage::Hlsl && in_array) {
      if (line.size() >= 2 && line.compare(line.size() - 2, 2, ");") == 0) {
        line.replace(line.size() - 2, 2, "};");
        in_array = false;
      }
    } else if (language == ShaderLanguage::Hlsl && line.rfind("const ", 0) == 0) {
      line = "static " + line;  // a global const of HLSL is otherwise a uniform
    }
    out += line;
    out += '\n';
  }
  if (in_array || !atlas) throw std::logic_error("sampler_in_language: an unterminated array or no atlas");
  return out;
}

}  // namespace tilekit
