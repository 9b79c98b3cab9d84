// The tiles sampler in every language (render/shader_languages.hpp), compiled by Debian's
// glslangValidator: GLSL ES 3.0; GLSL 4.50 for Vulkan to SPIR-V (-V) that spirv-val accepts; HLSL
// through glslang's HLSL front end (-D -V), its SPIR-V checked by spirv-val too. Every kind, both
// hashes, a set whose position table is stored and one whose is constructed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>
#include <string>

#include "../cli_runner.hpp"
#include "atlas/lookup.hpp"
#include "render/glsl_sampler.hpp"
#include "render/shader_languages.hpp"

namespace tilekit {
namespace {

int run_shell(const std::string& cmd) {
  return std::system(cmd.c_str());
}

std::string with_main(const std::string& library, ShaderLanguage l) {
  switch (l) {
    case ShaderLanguage::GlslEs:
      return "#version 300 es\nprecision highp float;\nprecision highp int;\n" + library +
             "in vec2 uv;\nout vec4 colour;\n"
             "void main() { colour = tk_texture(uv, dFdx(uv), dFdy(uv)) + tk_texture_grad(uv, dFdx(uv), dFdy(uv)); }\n";
    case ShaderLanguage::GlslVulkan:
      return "#version 450\n#define TK_SET 1\n#define TK_BINDING 2\n" + library +
             "layout(location = 0) in vec2 uv;\nlayout(location = 0) out vec4 colour;\n"
             "void main() { colour = tk_texture(uv, dFdx(uv), dFdy(uv)) + tk_texture_grad(uv, dFdx(uv), dFdy(uv)); }\n";
    case ShaderLanguage::Hlsl:
      return library +
             "float4 main(float4 position : SV_Position, float2 uv : TEXCOORD0) : SV_Target {\n"
             "  return tk_texture(uv, ddx(uv), ddy(uv)) + tk_texture_grad(uv, ddx(uv), ddy(uv));\n}\n";
    case ShaderLanguage::Wgsl:  // compiled in chromium's WebGPU: tests/render/wgsl_webgpu.test.mjs
      break;
  }
  return {};
}

TEST(ShaderLanguages, EveryLanguageCompilesAndVulkanAndHlslPassSpirvVal) {
  ASSERT_EQ(run_shell("command -v glslangValidator >/dev/null && command -v spirv-val >/dev/null"), 0)
      << "glslangValidator or spirv-val missing: run scripts/setup.sh";
  test::TempDir d;
  for (auto [kind, c] :
       {std::pair{TileKind::Corner, 2u}, std::pair{TileKind::Corner, 3u}, std::pair{TileKind::Wang, 2u}})
    for (HashKind h : {HashKind::Permutation, HashKind::LongPeriod}) {
      const TextureAtlas a{atlas_lookup(kind, c), 64, {}, ""};
      for (ShaderLanguage l : {ShaderLanguage::GlslEs, ShaderLanguage::GlslVulkan, ShaderLanguage::Hlsl}) {
        const std::string text = glsl_sampler_file(a, RenderOptions{h, 5, 1, false}, l);
        const std::string src = d / (std::string("t") + (l == ShaderLanguage::Hlsl ? ".hlsl" : ".frag"));
        test::write_text(src, with_main(text, l));
        const std::string spv = d / "t.spv", log = d / "log.txt";
        const std::string compile = l == ShaderLanguage::GlslEs ? "glslangValidator " + src
                                    : l == ShaderLanguage::GlslVulkan
                                        ? "glslangValidator -V " + src + " -o " + spv
                                        : "glslangValidator -D -V -e main -S frag " + src + " -o " + spv;
        ASSERT_EQ(run_shell(compile + " > " + log + " 2>&1"), 0)
            << shader_language_name(l) << " " << kind_name(kind) << " C=" << c << "\n"
            << test::slurp(log);
        if (l != ShaderLanguage::GlslEs) {
          EXPECT_EQ(run_shell("spirv-val " + spv + " > " + log + " 2>&1"), 0) << test::slurp(log);
        }
      }
    }
}

TEST(ShaderLanguages, TheRewriteKeepsEveryTableAndRefusesWhatItDoesNotKnow) {
  const TextureAtlas a{atlas_lookup(TileKind::Corner, 2), 64, {}, ""};  // a stored position table
  const std::string es = glsl_sampler_file(a, {}, ShaderLanguage::GlslEs);
  const std::string hlsl = glsl_sampler_file(a, {}, ShaderLanguage::Hlsl);
  // The same tables, value for value: the text between the brackets of every array is unchanged.
  auto values = [](const std::string& s, const std::string& name, char open, char close) {
    const std::size_t at = s.find(name + "[");
    const std::size_t from = s.find(open, s.find('=', at)) + 1;
    return s.substr(from, s.find(close, from) - from);
  };
  EXPECT_EQ(values(es, "tk_lattice0_P", '(', ')'), values(hlsl, "tk_lattice0_P", '{', '}'));
  EXPECT_EQ(values(es, "TK_POSITION", '(', ')'), values(hlsl, "TK_POSITION", '{', '}'));
  EXPECT_NE(hlsl.find("static const int TK_POSITION["), std::string::npos);
  EXPECT_NE(hlsl.find("static const float TK_INV_ROWS"), std::string::npos);
  EXPECT_THROW(sampler_in_language("uniform highp sampler2D tk_atlas;\nuniform int x;\n", ShaderLanguage::Hlsl),
               std::logic_error);
  EXPECT_THROW(sampler_in_language("const int A[2] = int[2](\n 1, 2\n", ShaderLanguage::Hlsl), std::logic_error);
}

}  // namespace
}  // namespace tilekit
