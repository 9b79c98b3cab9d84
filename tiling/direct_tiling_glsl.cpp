#include "tiling/direct_tiling_glsl.hpp"

#include <fmt/format.h>

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

// Component i of the hash is the permutation table P_i of size N_i at offset o_i of NAME_P; the
// colour is (sum_i P_i[(P_i[x mod N_i] + y mod N_i) mod N_i] mod N_j) mod C, as ColourHash::colour.
std::string colour_hash_glsl(const ColourHash& h, const std::string& name, GlslTables tables) {
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
    const std::uint32_t n = c.n, wrap = std::uint32_t((std::uint64_t(1) << 32) % n);
    auto p = [&](const std::string& i) { return at(P, fmt::format("{} + {}", off, i)); };
    one += fmt::format("  a = {}; s += {};\n", p(fmt::format("tk_mod(p.x, {}, {})", n, wrap)),
                       p(fmt::format("(a + tk_mod(p.y, {}, {})) % {}", n, wrap, n)));
    four += fmt::format(
        "  a = tk_mod(p.x, {n}, {w}); b = a + 1 == {n} ? 0 : a + 1;\n"
        "  ya = tk_mod(p.y, {n}, {w}); yb = ya + 1 == {n} ? 0 : ya + 1;\n"
        "  a = {pa}; b = {pb};\n"
        "  s += ivec4({q0}, {q1},\n             {q2}, {q3});\n",
        fmt::arg("n", n), fmt::arg("w", wrap), fmt::arg("pa", p("a")), fmt::arg("pb", p("b")),
        fmt::arg("q0", p(fmt::format("(a + ya) % {}", n))), fmt::arg("q1", p(fmt::format("(b + ya) % {}", n))),
        fmt::arg("q2", p(fmt::format("(a + yb) % {}", n))), fmt::arg("q3", p(fmt::format("(b + yb) % {}", n))));
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
