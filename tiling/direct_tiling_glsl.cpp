#include "tiling/direct_tiling_glsl.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "base/error.hpp"

namespace tilekit {

namespace {

std::string joined(const std::vector<std::int32_t>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? (i % 24 ? ", " : ",\n  ") : "") + std::to_string(v[i]);
  return s;
}

std::vector<std::int32_t> concatenated(const ColourHash& h) {
  std::vector<std::int32_t> all;
  for (const ColourHash::Component& c : h.components()) all.insert(all.end(), c.p.begin(), c.p.end());
  return all;
}

}  // namespace

std::string glsl_floor_mod() {
  return "// floored v mod n; wrap = 2^32 mod n (uint(v) keeps the bit pattern of a negative v)\n"
         "int tk_mod(int v, int n, int wrap) {\n"
         "  uint r = uint(v) % uint(n);\n"
         "  return v < 0 ? int((r + uint(n - wrap)) % uint(n)) : int(r);\n"
         "}\n";
}

std::vector<std::int32_t> glsl_hash_uniforms(const ColourHash& h) {
  std::vector<std::int32_t> all = concatenated(h);
  all.resize((all.size() + 3) / 4 * 4, 0);
  return all;
}

// Where 2^32 is a multiple of n (n a power of two), the unsigned remainder of v's bit pattern is
// already the floored one.
std::string glsl_mod(const std::string& v, std::uint32_t n) {
  const std::uint32_t wrap = std::uint32_t((std::uint64_t(1) << 32) % n);
  return wrap ? fmt::format("tk_mod({}, {}, {})", v, n, wrap) : fmt::format("int(uint({}) % {}u)", v, n);
}

GlslHashTexture glsl_hash_texture(const ColourHash& h) {
  if (h.colours() > 255) throw InputError(fmt::format("hash textures hold up to 255 colours, not {}", h.colours()));
  GlslHashTexture t;
  for (const ColourHash::Component& c : h.components()) {
    t.width += int(c.n);
    t.height = std::max(t.height, int(c.n));
  }
  t.rgba.assign(std::size_t(t.width) * std::size_t(t.height) * 4, 0);
  int column = 0;
  for (const ColourHash::Component& c : h.components()) {
    const std::uint32_t n = c.n;
    auto value = [&](std::uint32_t a, std::uint32_t b) {  // thesis eq. (3.3) of one table, mod C
      return std::uint8_t(c.p[(c.p[a % n] + b % n) % n] % h.colours());
    };
    for (std::uint32_t b = 0; b < n; ++b)
      for (std::uint32_t a = 0; a < n; ++a) {
        std::uint8_t* texel = &t.rgba[(std::size_t(b) * std::size_t(t.width) + std::size_t(column) + a) * 4];
        texel[0] = value(a, b);
        texel[1] = value(a + 1, b);
        texel[2] = value(a, b + 1);
        texel[3] = value(a + 1, b + 1);
      }
    column += int(n);
  }
  return t;
}

namespace {

// GlslTables::Texture: one texelFetch per component gives its values at the four corners.
std::string colour_hash_texture_glsl(const ColourHash& h, const std::string& name) {
  std::string sum;
  std::uint32_t column = 0;
  for (const ColourHash::Component& c : h.components()) {
    sum += fmt::format("{}texelFetch({}_T, ivec2({}{}, {}), 0)", sum.empty() ? "" : "\n      + ", name,
                       column ? fmt::format("{} + ", column) : "", glsl_mod("p.x", c.n), glsl_mod("p.y", c.n));
    column += c.n;
  }
  return fmt::format(
      "uniform highp usampler2D {0}_T;\n"
      "ivec4 {0}4(ivec2 p) {{  // at p, p + (1,0), p + (0,1), p + (1,1): sum of the tables, mod C\n"
      "  uvec4 s = {1};\n"
      "  return ivec4(s % {2}u);\n"
      "}}\n"
      "int {0}(ivec2 p) {{  // thesis eq. ({3})\n"
      "  return {0}4(p).x;\n"
      "}}\n",
      name, sum, h.colours(), h.components().size() == 1 ? "3.3" : "3.6");
}

}  // namespace

// Component i of the hash is the permutation table P_i of size N_i at offset o_i of NAME_P; the
// colour is (sum_i P_i[(P_i[x mod N_i] + y mod N_i) mod N_i] mod N_j) mod C, as ColourHash::colour.
std::string colour_hash_glsl(const ColourHash& h, const std::string& name, GlslTables tables) {
  if (tables == GlslTables::Texture) return colour_hash_texture_glsl(h, name);
  const std::vector<std::int32_t> all = concatenated(h);
  std::string g;
  std::string (*at)(const std::string&, const std::string&);
  if (tables == GlslTables::Inline) {
    g += fmt::format("const int {}_P[{}] = int[{}](\n  {});\n", name, all.size(), all.size(), joined(all));
    at = [](const std::string& table, const std::string& i) { return fmt::format("{}[{}]", table, i); };
  } else {
    g += fmt::format("uniform ivec4 {}_P[{}];\n", name, (all.size() + 3) / 4);
    at = [](const std::string& table, const std::string& i) {
      return fmt::format("{0}[({1}) >> 2][({1}) & 3]", table, i);
    };
  }
  const std::string P = name + "_P";
  std::string one, four;
  std::uint32_t off = 0;
  for (const ColourHash::Component& c : h.components()) {
    const std::uint32_t n = c.n;
    auto p = [&](const std::string& i) { return at(P, fmt::format("{} + {}", off, i)); };
    one += fmt::format("  a = {}; s += {};\n", p(glsl_mod("p.x", n)),
                       p(fmt::format("(a + {}) % {}", glsl_mod("p.y", n), n)));
    four += fmt::format(
        "  a = {mx}; b = a + 1 == {n} ? 0 : a + 1;\n"
        "  ya = {my}; yb = ya + 1 == {n} ? 0 : ya + 1;\n"
        "  a = {pa}; b = {pb};\n"
        "  s += ivec4({q0}, {q1},\n             {q2}, {q3});\n",
        fmt::arg("n", n), fmt::arg("mx", glsl_mod("p.x", n)), fmt::arg("my", glsl_mod("p.y", n)),
        fmt::arg("pa", p("a")), fmt::arg("pb", p("b")), fmt::arg("q0", p(fmt::format("(a + ya) % {}", n))),
        fmt::arg("q1", p(fmt::format("(b + ya) % {}", n))), fmt::arg("q2", p(fmt::format("(a + yb) % {}", n))),
        fmt::arg("q3", p(fmt::format("(b + yb) % {}", n))));
    off += n;
  }
  g += fmt::format("int {}(ivec2 p) {{  // thesis eq. ({})\n  int s = 0, a;\n{}  return (s % {}) % {};\n}}\n", name,
                   h.components().size() == 1 ? "3.3" : "3.6", one, h.range(), h.colours());
  g += fmt::format("ivec4 {}4(ivec2 p) {{  // at p, p + (1,0), p + (0,1), p + (1,1)\n", name);
  g += "  ivec4 s = ivec4(0);\n  int a, b, ya, yb;\n" + four;
  g += fmt::format("  return (s % {}) % {};\n}}\n", h.range(), h.colours());
  return g;
}

std::string direct_tiling_glsl(const DirectTiling& t, GlslTables tables) {
  std::string g = fmt::format(
      "// direct stochastic tiling, {} hash, seed {}; x east, y south, tile (x, y) has its NW\n"
      "// corner at lattice point (x, y)\n",
      hash_kind_name(t.hash_kind()), t.seed());
  g += glsl_floor_mod();
  const auto hashes = t.hashes();
  for (std::size_t k = 0; k < hashes.size(); ++k)
    g += colour_hash_glsl(*hashes[k], fmt::format("tk_lattice{}", k), tables);
  const std::uint32_t c = t.colours();
  if (t.kind() == TileKind::Corner) {
    g += fmt::format(
        "int tk_virtual_tile(ivec2 p) {{  // corner tiles (thesis 3.3.1)\n"
        "  ivec4 h = tk_lattice04(p);  // NW, NE, SW, SE\n"
        "  return ((h.y * {0} + h.w) * {0} + h.z) * {0} + h.x;  // thesis eq. (2.5): ((NE C + SE) C + SW) C + NW\n"
        "}}\n",
        c);
  } else {
    g += fmt::format(
        "int tk_virtual_tile(ivec2 p) {{  // Wang tiles, two hashes (thesis 3.3.2.1)\n"
        "  ivec4 hh = tk_lattice04(p), hv = tk_lattice14(p);  // NW, NE, SW, SE\n"
        "  int n = (hh.x + hh.y) % {0}, e = (hv.y + hv.w) % {0};\n"
        "  int s = (hh.w + hh.z) % {0}, w = (hv.z + hv.x) % {0};\n"
        "  return ((n * {0} + e) * {0} + s) * {0} + w;  // thesis eq. (2.2)\n"
        "}}\n",
        c);
  }
  return g;
}

}  // namespace tilekit
