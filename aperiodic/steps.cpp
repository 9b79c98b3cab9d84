#include "aperiodic/steps.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "aperiodic/canonical.hpp"
#include "aperiodic/colour_merge.hpp"
#include "aperiodic/conversion.hpp"
#include "aperiodic/prune.hpp"
#include "base/error.hpp"

namespace tilekit {

namespace {

std::string label_of(Soundness s) {
  return soundness_name(s);
}

// Horizontal dominoes (a b, a.e == b.w) as tiles: north colour the pair (a.n, b.n), south
// (a.s, b.s), west a.w, east b.e, pairs numbered densely. Why `lifts`: a tiling by dominoes is
// cut into a tiling by the source's tiles (the middle edge of each domino matches by
// construction, the outer edges by the domino's colours), a periodic one into a periodic one;
// and a source tiling is cut into dominoes along every other column. Dominoes that differ only
// in their middle colour become one tile, which changes neither argument.
TileSet fuse(const std::vector<WangTile>& w) {
  std::map<std::pair<Colour, Colour>, Colour> pair;
  std::vector<std::array<Colour, 6>> dominoes;  // a.n b.n a.s b.s a.w b.e
  for (const WangTile& a : w)
    for (const WangTile& b : w)
      if (a.e == b.w) {
        dominoes.push_back({a.n, b.n, a.s, b.s, a.w, b.e});
        pair.emplace(std::pair{a.n, b.n}, 0);
        pair.emplace(std::pair{a.s, b.s}, 0);
      }
  Colour next = 0;
  for (auto& [p, c] : pair) c = next++;
  std::vector<WangTile> out;
  for (const auto& d : dominoes) out.push_back({pair[{d[0], d[1]}], d[5], pair[{d[2], d[3]}], d[4]});
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return TileSet::wang(std::move(out));
}

// The Wang tiles as pegs: corner tile (a, b / c, d) for every 2x2 block of tiles whose four inner
// edges match. Why `conjugate`: a colouring of the pegs all of whose 2x2 windows are such blocks
// is a Wang tiling (each pair of neighbours lies in some window), a Wang tiling gives such a
// colouring, cell for peg, and both maps commute with translations. Nullopt past max_tiles.
std::optional<TileSet> blocks(const std::vector<WangTile>& w, std::size_t max_tiles = 100000) {
  std::vector<CornerTile> out;
  for (Colour a = 0; a < w.size(); ++a)
    for (Colour b = 0; b < w.size(); ++b) {
      if (w[a].e != w[b].w) continue;
      for (Colour c = 0; c < w.size(); ++c) {
        if (w[a].s != w[c].n) continue;
        for (Colour d = 0; d < w.size(); ++d)
          if (w[c].e == w[d].w && w[b].s == w[d].n) {
            if (out.size() == max_tiles) return std::nullopt;
            out.push_back({b, d, c, a});
          }
      }
    }
  if (out.empty()) return std::nullopt;
  return TileSet::corner(std::move(out));
}

std::optional<StepResult> operation(const TileSet& set, const std::string& op) {
  const bool wang = set.kind() == TileKind::Wang;
  auto convert_with = [&](ConversionSpec spec) -> std::optional<StepResult> {
    if (!wang) return std::nullopt;
    LabelledConversion c = build_conversion(set, spec);
    if (c.set.empty()) return std::nullopt;
    std::string why = c.argument;
    if (!c.prune_argument.empty()) why += "; " + c.prune_argument;
    return StepResult{c.set, label_of(c.soundness), why};
  };
  if (op == "diagonal") return convert_with({ConversionMethod::Diagonal, {}, -1});
  if (op == "horizontal") return convert_with({ConversionMethod::Horizontal, {}, -1});
  if (op == "horizontal+prune") return convert_with({ConversionMethod::Horizontal, {}, 3});
  if (op == "horizontal+prune5") return convert_with({ConversionMethod::Horizontal, {}, 3, 2});
  if (op == "rotation") return convert_with({ConversionMethod::Rotation, {}, -1});
  if (op == "subdivision") return convert_with({ConversionMethod::Subdivision, {}, -1});
  if (op == "subdivision+merge-centres") return convert_with({ConversionMethod::Subdivision, {true, false}, -1});
  if (op == "blocks") {
    if (!wang) return std::nullopt;
    std::optional<TileSet> b = blocks(set.wang_tiles());
    if (!b) return std::nullopt;
    return StepResult{*b, "conjugate",
                      "pegs are the Wang tiles, corner tiles the 2x2 blocks whose inner edges match: a colouring "
                      "by such blocks is a Wang tiling, cell for peg"};
  }
  if (op == "to-wang") {
    if (wang) return std::nullopt;
    LabelledConversion c = build_conversion(set, {ConversionMethod::ToWang, {}, -1});
    return StepResult{c.set, label_of(c.soundness), c.argument};
  }
  if (op == "fuse") {
    if (!wang) return std::nullopt;
    return StepResult{fuse(set.wang_tiles()), "lifts",
                      "dominoes as tiles: a tiling by them cuts into one of the source, periodic into periodic"};
  }
  if (op == "merge-colours" || op == "merge-colours-lifts" || op == "merge-colours2") {
    if (wang) return std::nullopt;
    const int radius = op == "merge-colours2" ? 2 : 1;
    const MergeSearch m = least_colour_merge(set.corner_tiles(), op == "merge-colours-lifts", radius, 1);
    if (m.merges.empty()) return std::nullopt;
    return StepResult{TileSet::corner(m.tiles, set.name(), set.source()), m.conjugate ? "conjugate" : "lifts",
                      m.argument()};
  }
  if (op == "prune" || op == "prune-strips" || op == "prune5") {
    PruneReport rep;
    const bool strips = op == "prune-strips";
    TileSet out = strips ? prune_strips(set, 3, &rep) : prune(set, 3, &rep, op == "prune5" ? 2 : 1);
    if (rep.after == rep.before || out.empty()) return std::nullopt;
    return StepResult{out, "prune",
                      fmt::format("{} -> {} tiles ({} by surround, {} outside the strongly connected components of "
                                  "{}): keeps tileability and every periodic tiling",
                                  rep.before, rep.after, rep.removed_by_surround, rep.removed_by_scc,
                                  strips ? "the strip transducers, k <= 3" : "the row/column transducers")};
  }
  throw InputError(
      fmt::format("unknown step operation '{}' (expected one of: {})", op, fmt::join(all_step_operations(), ", ")));
}

}  // namespace

const std::vector<std::string>& stronger_step_operations() {
  static const std::vector<std::string> ops = {"prune5", "horizontal+prune5", "merge-colours2"};
  return ops;
}

const std::vector<std::string>& all_step_operations() {
  static const std::vector<std::string> ops = [] {
    std::vector<std::string> all = step_operations();
    for (const std::string& op : stronger_step_operations()) all.push_back(op);
    return all;
  }();
  return ops;
}

const std::vector<std::string>& step_operations() {
  static const std::vector<std::string> ops = {"prune",
                                               "prune-strips",
                                               "to-wang",
                                               "horizontal",
                                               "horizontal+prune",
                                               "rotation",
                                               "blocks",
                                               "diagonal",
                                               "subdivision",
                                               "subdivision+merge-centres",
                                               "fuse",
                                               "merge-colours",
                                               "merge-colours-lifts"};
  return ops;
}

std::vector<std::string> symmetries_for(const std::string& op) {
  if (op == "horizontal" || op == "horizontal+prune" || op == "horizontal+prune5" || op == "fuse")
    return {"id", "rot90"};
  if (op == "subdivision+merge-centres") {
    std::vector<std::string> all;
    for (const Dihedral& g : Dihedral::all()) all.push_back(g.name());
    return all;
  }
  return {"id"};
}

std::optional<StepResult> apply_step(const TileSet& set, const std::string& step) {
  const auto colon = step.find(':');
  const Dihedral g = colon == std::string::npos ? Dihedral{} : Dihedral::parse(step.substr(0, colon));
  const std::string op = colon == std::string::npos ? step : step.substr(colon + 1);
  const auto& ops = all_step_operations();
  if (std::find(ops.begin(), ops.end(), op) == ops.end())
    throw InputError(fmt::format("unknown step operation '{}' (expected one of: {})", op, fmt::join(ops, ", ")));
  try {
    return operation(g.name() == "id" ? set : transform(set, g), op);
  } catch (const InputError&) {
    // A known operation on a valid set fails only at the tile-index limits (results over
    // thousands of colours): such sets are outside the search.
    return std::nullopt;
  }
}

bool sound_label(const std::string& label) {
  return label == "published" || label == "conjugate" || label == "lifts" || label == "prune";
}

}  // namespace tilekit
