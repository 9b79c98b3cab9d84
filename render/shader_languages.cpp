#include "render/shader_languages.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace tilekit {

namespace {

// HLSL names for GLSL's types and the built-ins the sampler uses (the rest: floor, sqrt, log2,
// min, max, clamp, abs, are the same).
const char* const kHlslPrelude =
    "#define vec2 float2\n#define vec3 float3\n#define vec4 float4\n"
    "#define ivec2 int2\n#define ivec3 int3\n#define ivec4 int4\n#define uvec2 uint2\n#define uvec4 uint4\n"
    "#define highp\n#define fract frac\n#define mix lerp\n"
    "#define floatBitsToInt asint\n#define intBitsToFloat asfloat\n"
    "#define textureLod(t, st, lod) t.SampleLevel(t##_sampler, st, lod)\n"
    "#define textureGrad(t, st, dx, dy) t.SampleGrad(t##_sampler, st, dx, dy)\n";

const char* const kAtlasGlslEs = "uniform highp sampler2D tk_atlas;";

}  // namespace

const char* shader_language_name(ShaderLanguage l) {
  switch (l) {
    case ShaderLanguage::GlslEs:
      return "glsl-es";
    case ShaderLanguage::GlslVulkan:
      return "glsl-vulkan";
    case ShaderLanguage::Hlsl:
      return "hlsl";
    case ShaderLanguage::Wgsl:
      return "wgsl";
  }
  return "";
}

const char* shader_language_extension(ShaderLanguage l) {
  switch (l) {
    case ShaderLanguage::GlslEs:
      return ".glsl";
    case ShaderLanguage::GlslVulkan:
      return ".vk.glsl";
    case ShaderLanguage::Hlsl:
      return ".hlsl";
    case ShaderLanguage::Wgsl:
      return ".wgsl";
  }
  return "";
}

std::string sampler_in_language(const std::string& glsl, ShaderLanguage language) {
  if (language == ShaderLanguage::GlslEs) return glsl;
  if (language == ShaderLanguage::Wgsl) throw std::logic_error("sampler_in_language: WGSL is wgsl_sampler's");
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

namespace {

// v mod n, floored, in WGSL: bitcast<u32> keeps a negative v's bit pattern; wrap = 2^32 mod n
// (direct_tiling_glsl.hpp's glsl_mod).
std::string wgsl_mod(const std::string& v, std::uint32_t n) {
  const std::uint32_t wrap = std::uint32_t((std::uint64_t(1) << 32) % n);
  return wrap ? fmt::format("tk_mod({}, {}, {})", v, n, wrap) : fmt::format("i32(bitcast<u32>({}) % {}u)", v, n);
}

std::string wgsl_array(const std::string& name, const std::vector<std::int32_t>& values) {
  std::string s = fmt::format("var<private> {}: array<i32, {}> = array<i32, {}>(", name, values.size(), values.size());
  for (std::size_t i = 0; i < values.size(); ++i)
    s += (i ? (i % 24 ? ", " : ",\n  ") : "\n  ") + std::to_string(values[i]);
  return s + ");\n";
}

// colour_hash_glsl's four-corner form (tiling/direct_tiling_glsl.cpp) in WGSL.
std::string wgsl_colour_hash(const ColourHash& h, const std::string& name) {
  std::vector<std::int32_t> all;
  for (const ColourHash::Component& c : h.components()) all.insert(all.end(), c.p.begin(), c.p.end());
  std::string g = wgsl_array(name + "_P", all);
  g += fmt::format("fn {}4(p: vec2<i32>) -> vec4<i32> {{  // at p, p + (1,0), p + (0,1), p + (1,1)\n", name);
  g += "  var s = vec4<i32>(0, 0, 0, 0);\n  var a: i32;\n  var b: i32;\n  var ya: i32;\n  var yb: i32;\n";
  std::uint32_t off = 0;
  const std::string P = name + "_P";
  for (const ColourHash::Component& c : h.components()) {
    const std::uint32_t n = c.n;
    auto p = [&](const std::string& i) { return fmt::format("{}[{} + {}]", P, off, i); };
    g += fmt::format(
        "  a = {mx}; b = select(a + 1, 0, a + 1 == {n});\n"
        "  ya = {my}; yb = select(ya + 1, 0, ya + 1 == {n});\n"
        "  a = {pa}; b = {pb};\n"
        "  s += vec4<i32>({q0}, {q1},\n                 {q2}, {q3});\n",
        fmt::arg("n", n), fmt::arg("mx", wgsl_mod("p.x", n)), fmt::arg("my", wgsl_mod("p.y", n)),
        fmt::arg("pa", p("a")), fmt::arg("pb", p("b")), fmt::arg("q0", p(fmt::format("(a + ya) % {}", n))),
        fmt::arg("q1", p(fmt::format("(b + ya) % {}", n))), fmt::arg("q2", p(fmt::format("(a + yb) % {}", n))),
        fmt::arg("q3", p(fmt::format("(b + yb) % {}", n))));
    off += n;
  }
  g += fmt::format("  return (s % {}) % {};\n}}\n", h.range(), h.colours());
  return g;
}

}  // namespace

std::string wgsl_sampler(const AtlasLookup& l, float texels_per_tile, const DirectTiling& tiling) {
  check_same_set(l, tiling);
  std::string g = fmt::format(
      "const TK_COLORS: i32 = {};\nconst TK_ROWS: i32 = {};\nconst TK_COLS: i32 = {};\n"
      "const TK_TILE_PX: f32 = {:.9g};  // level-0 texels a tile\n"
      "const TK_MAX_ANISO: i32 = 16;  // 1: trilinear\n"
      "const TK_INV_ROWS: f32 = {:.9g};\nconst TK_INV_COLS: f32 = {:.9g};\n",
      l.colours, l.rows, l.cols, double(texels_per_tile), 1.0f / float(l.rows), 1.0f / float(l.cols));
  g += "@group(0) @binding(0) var tk_atlas: texture_2d<f32>;  // every mip level\n"
       "@group(0) @binding(1) var tk_atlas_sampler: sampler;  // linear, mipmap linear, repeat\n";
  g += fmt::format(
      "// direct stochastic tiling, {} hash, seed {}; x east, y south, tile (x, y) has its NW\n"
      "// corner at lattice point (x, y)\n",
      hash_kind_name(tiling.hash_kind()), tiling.seed());
  g += "fn tk_mod(v: i32, n: i32, wrap: i32) -> i32 {  // floored v mod n; wrap = 2^32 mod n\n"
       "  let r = bitcast<u32>(v) % u32(n);\n"
       "  return select(i32(r), i32((r + u32(n - wrap)) % u32(n)), v < 0);\n"
       "}\n";
  const auto hashes = tiling.hashes();
  for (std::size_t k = 0; k < hashes.size(); ++k) g += wgsl_colour_hash(*hashes[k], fmt::format("tk_lattice{}", k));
  const std::uint32_t c = tiling.colours();
  if (tiling.kind() == TileKind::Corner)
    g += fmt::format(
        "fn tk_virtual_tile(p: vec2<i32>) -> i32 {{  // corner tiles (thesis 3.3.1)\n"
        "  let h = tk_lattice04(p);  // NW, NE, SW, SE\n"
        "  return ((h.y * {0} + h.w) * {0} + h.z) * {0} + h.x;  // thesis eq. (2.5)\n"
        "}}\n",
        c);
  else
    g += fmt::format(
        "fn tk_virtual_tile(p: vec2<i32>) -> i32 {{  // Wang tiles, two hashes (thesis 3.3.2.1)\n"
        "  let hh = tk_lattice04(p);\n  let hv = tk_lattice14(p);  // NW, NE, SW, SE\n"
        "  let n = (hh.x + hh.y) % {0};\n  let e = (hv.y + hv.w) % {0};\n"
        "  let s = (hh.w + hh.z) % {0};\n  let w = (hv.z + hv.x) % {0};\n"
        "  return ((n * {0} + e) * {0} + s) * {0} + w;  // thesis eq. (2.2)\n"
        "}}\n",
        c);
  std::vector<std::int32_t> positions;
  for (const auto& [row, col] : l.positions) positions.push_back(std::int32_t(row * l.cols + col));
  g += wgsl_array("TK_POSITION", positions);
  g += "fn tk_tile_cell(tile: vec2<i32>) -> vec2<i32> {  // the tile's (row, col) in the packing\n"
       "  let p = TK_POSITION[tk_virtual_tile(tile)];\n"
       "  return vec2<i32>(p / TK_COLS, p % TK_COLS);\n"
       "}\n"
       "struct TkFootprint { taps: i32, lod: f32, axis: vec2<i32> }\n"
       "// anisotropic footprint (render/anisotropic.hpp): derivatives in tiles per pixel\n"
       "fn tk_footprint(dx: vec2<f32>, dy: vec2<f32>, max_aniso: i32) -> TkFootprint {\n"
       "  let lx = sqrt(dx.x * dx.x + dx.y * dx.y);\n  let ly = sqrt(dy.x * dy.x + dy.y * dy.y);\n"
       "  let major = max(lx, ly);\n  let minor = min(lx, ly);\n"
       "  var f: TkFootprint;\n  f.taps = 1;\n"
       "  while (f.taps < max_aniso && f32(f.taps) * minor < major) { f.taps += 1; }\n"
       "  f.lod = log2(TK_TILE_PX * major / f32(f.taps));\n"
       "  let a = clamp(select(dy, dx, lx >= ly), vec2<f32>(-256.0, -256.0), vec2<f32>(256.0, 256.0));\n"
       "  f.axis = select(vec2<i32>(0, 0), vec2<i32>(floor(a * 65536.0 + 0.5)), f.taps > 1);\n"
       "  return f;\n"
       "}\n"
       "fn tk_tap_offset(a: i32, i: i32, n: i32) -> i32 {  // round(a (2i + 1 - n) / (2n)) on magnitudes\n"
       "  let m = 2 * i + 1 - n;\n"
       "  let q = (abs(a) * abs(m) + n) / (2 * n);\n"
       "  return select(q, -q, (a < 0) != (m < 0));\n"
       "}\n"
       "// thesis 5.4: the tile's place in the packing plus the position f in [0,1)^2 inside the tile\n"
       "fn tk_sample_tile(tile: vec2<i32>, f: vec2<f32>, lod: f32) -> vec4<f32> {\n"
       "  let rc = tk_tile_cell(tile);\n"
       "  let st = (vec2<f32>(f32(rc.y), f32(rc.x)) + f) * vec2<f32>(TK_INV_COLS, TK_INV_ROWS);\n"
       "  return textureSampleLevel(tk_atlas, tk_atlas_sampler, st, lod);\n"
       "}\n"
       "// the taps of a footprint (tk_footprint), each through the tiling to its own tile\n"
       "fn tk_sample(tile: vec2<i32>, sub: vec2<i32>, f: TkFootprint) -> vec4<f32> {\n"
       "  if (f.taps == 1) { return tk_sample_tile(tile, vec2<f32>(sub) / 65536.0, f.lod); }\n"
       "  var sum = vec4<f32>(0.0, 0.0, 0.0, 0.0);\n"
       "  for (var i = 0; i < f.taps; i += 1) {\n"
       "    let q = sub + vec2<i32>(tk_tap_offset(f.axis.x, i, f.taps), tk_tap_offset(f.axis.y, i, f.taps));\n"
       "    sum += tk_sample_tile(tile + (q >> vec2<u32>(16u, 16u)), vec2<f32>(q & vec2<i32>(65535, 65535)) / 65536.0,"
       " f.lod);\n"
       "  }\n"
       "  return sum / f32(f.taps);\n"
       "}\n"
       "// the hardware's anisotropic filter (the GLSL's tk_sample_grad): one fetch with the virtual\n"
       "// texture's gradients; set the sampler's maxAnisotropy (up to 16)\n"
       "fn tk_sample_grad(tile: vec2<i32>, f: vec2<f32>, dx: vec2<f32>, dy: vec2<f32>) -> vec4<f32> {\n"
       "  let rc = tk_tile_cell(tile);\n"
       "  let scale = vec2<f32>(TK_INV_COLS, TK_INV_ROWS);\n"
       "  return textureSampleGrad(tk_atlas, tk_atlas_sampler, (vec2<f32>(f32(rc.y), f32(rc.x)) + f) * scale, dx * "
       "scale,"
       " dy * scale);\n"
       "}\n"
       "fn tk_texture_grad(uv: vec2<f32>, duvdx: vec2<f32>, duvdy: vec2<f32>) -> vec4<f32> {\n"
       "  let cell = floor(uv);\n"
       "  return tk_sample_grad(vec2<i32>(cell), uv - cell, duvdx, duvdy);\n"
       "}\n"
       "// uv in tiles of the virtual texture (u east, v south), with its screen derivatives\n"
       "fn tk_texture(uv: vec2<f32>, duvdx: vec2<f32>, duvdy: vec2<f32>) -> vec4<f32> {\n"
       "  let cell = floor(uv);\n"
       "  return tk_sample(vec2<i32>(cell), vec2<i32>((uv - cell) * 65536.0), tk_footprint(duvdx, duvdy, "
       "TK_MAX_ANISO));\n"
       "}\n";
  return g;
}

}  // namespace tilekit
