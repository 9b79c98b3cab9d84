// Recursive Wang tile files:
//   TILEKIT-RECURSIVE-TILES 1
//   points N / subdivision n / seed S / types 8 / relax_iterations I / relax_residual R
//   per type: "type T wang W", "rule t0 ... t(n^2-1)", N lines "x y" (rank order), one line
//   "ranks r0 ... r(n^2 N - 1)" (rank of sub-tile j's point i at j N + i)
//   end / fnv1a64 HEX
#include <fmt/format.h>

#include <limits>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/input.hpp"
#include "points/recursive_tiles.hpp"
#include "points/text_format.hpp"

namespace tilekit::points {

namespace {
constexpr const char* kMagic = "TILEKIT-RECURSIVE-TILES 1";

// Whitespace-separated counts of a line.
std::vector<std::uint64_t> counts(text::LineReader& in, std::string_view s) {
  std::vector<std::uint64_t> out;
  std::size_t pos = 0;
  while (pos < s.size()) {
    const std::size_t sp = std::min(s.find(' ', pos), s.size());
    out.push_back(in.count(s.substr(pos, sp - pos)));
    pos = sp + 1;
  }
  return out;
}
}  // namespace

std::string recursive_tiles_to_text(const RecursiveWangTiles& t) {
  std::string out =
      fmt::format("{}\npoints {}\nsubdivision {}\nseed {}\ntypes {}\nrelax_iterations {}\nrelax_residual {:.17g}\n",
                  kMagic, t.points, t.n, t.seed, t.types(), t.relax_iterations, t.relax_residual);
  for (std::size_t type = 0; type < t.types(); ++type) {
    out += fmt::format("type {} wang {}\nrule {}\n", type, t.wang[type], fmt::join(t.rule[type], " "));
    for (const Point2& p : t.base[type]) out += fmt::format("{:.17g} {:.17g}\n", p.x, p.y);
    out += fmt::format("ranks {}\n", fmt::join(t.rank[type], " "));
  }
  out += "end\n";
  return text::with_checksum(std::move(out));
}

RecursiveWangTiles recursive_tiles_from_text(const std::string& text, const std::string& source) {
  text::LineReader in(text, source);
  if (in.expect("the header") != kMagic) in.fail(fmt::format("not a recursive tile-set file (expected '{}')", kMagic));
  RecursiveWangTiles t;
  t.points = std::uint32_t(in.count(in.keyed("points"), 65536));
  t.n = int(in.count(in.keyed("subdivision"), 8));
  t.seed = in.count(in.keyed("seed"));
  const std::uint64_t types = in.count(in.keyed("types"), 8);
  t.relax_iterations = int(in.count(in.keyed("relax_iterations"), std::numeric_limits<int>::max()));
  t.relax_residual = in.number(in.keyed("relax_residual"));
  if (t.points < 1 || t.n < 2 || types != 8) in.fail("unsupported sizes");
  const std::size_t sub = std::size_t(t.n) * std::size_t(t.n);
  t.wang.resize(types);
  t.base.resize(types);
  t.rule.resize(types);
  t.rank.resize(types);
  for (std::size_t type = 0; type < types; ++type) {
    const std::string_view head = in.keyed("type");  // "T wang W"
    const std::size_t a = head.find(' '), b = head.rfind(' ');
    if (a == std::string_view::npos || head.substr(a, b - a + 1) != " wang " || in.count(head.substr(0, a)) != type)
      in.fail(fmt::format("expected 'type {} wang W'", type));
    const std::vector<std::uint64_t> parts = {type, in.count(head.substr(b + 1))};
    if (parts[1] >= 16) in.fail("a Wang tile index over 2 colours is below 16");
    t.wang[type] = std::uint32_t(parts[1]);
    for (auto r : counts(in, in.keyed("rule"))) {
      if (r >= types) in.fail("rule names an unknown type");
      t.rule[type].push_back(std::uint32_t(r));
    }
    if (t.rule[type].size() != sub) in.fail(fmt::format("a rule has {} sub-tiles", sub));
    for (std::uint32_t k = 0; k < t.points; ++k) {
      const std::string_view line = in.expect("a point");
      const std::size_t sp = line.find(' ');
      if (sp == std::string_view::npos) in.fail("expected 'x y'");
      const Point2 p{in.number(line.substr(0, sp)), in.number(line.substr(sp + 1))};
      if (!(p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1)) in.fail("tile coordinates must lie in [0, 1)");
      t.base[type].push_back(p);
    }
    for (auto r : counts(in, in.keyed("ranks"))) {
      if (r >= sub * t.points) in.fail("the ranks are not a permutation");
      t.rank[type].push_back(std::uint32_t(r));
    }
    if (t.rank[type].size() != sub * t.points) in.fail("wrong number of ranks");
    std::vector<char> seen(t.rank[type].size(), 0);
    for (auto r : t.rank[type]) {
      if (r >= seen.size() || seen[r]) in.fail("the ranks are not a permutation");
      seen[r] = 1;
    }
  }
  if (in.expect("end") != "end") in.fail("expected 'end'");
  in.checksum();
  for (std::size_t type = 0; type < types; ++type)
    if (t.type_of(t.wang[type]) != int(type)) throw InputError(fmt::format("{}: repeated Wang tile", source));
  return t;
}

void write_recursive_tiles(const std::string& path, const RecursiveWangTiles& t) {
  write_file_atomic(path, recursive_tiles_to_text(t));
}

RecursiveWangTiles read_recursive_tiles(const std::string& path) {
  return recursive_tiles_from_text(read_input_file(path, "recursive tile-set file"), path);
}

}  // namespace tilekit::points
