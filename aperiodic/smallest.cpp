#include "aperiodic/smallest.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "aperiodic/conversion.hpp"
#include "base/error.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit {

namespace {

bool sound(Soundness s) {
  return s == Soundness::Conjugate || s == Soundness::Lifts;
}

std::string section(ConversionMethod m) {
  switch (m) {
    case ConversionMethod::Diagonal:
      return "diagonal translation (thesis 8.3.1)";
    case ConversionMethod::Horizontal:
      return "horizontal translation (thesis 8.3.2)";
    case ConversionMethod::Vertical:
      return "vertical translation (thesis 8.3.2)";
    case ConversionMethod::Rotation:
      return "rotation with checkerboard tiles (thesis 8.3.3)";
    case ConversionMethod::Subdivision:
      return "subdivision (thesis 8.3.4)";
    case ConversionMethod::ToWang:
      return "pair colours (thesis 8.4)";
  }
  return "?";
}

}  // namespace

const std::vector<std::string>& published_aperiodic_sets() {
  static const std::vector<std::string> s = {"culik-13", "kari-14", "ammann-gs-16", "jeandel-rao-11", "labbe-19"};
  return s;
}

std::vector<CornerSetCandidate> aperiodic_corner_candidates(int prune_radius) {
  std::vector<CornerSetCandidate> out;
  const std::vector<std::pair<ConversionMethod, bool>> methods = {
      {ConversionMethod::Diagonal, false},    {ConversionMethod::Horizontal, false},
      {ConversionMethod::Vertical, false},    {ConversionMethod::Rotation, false},
      {ConversionMethod::Subdivision, false}, {ConversionMethod::Subdivision, true}};
  for (const std::string& name : published_aperiodic_sets()) {
    TileSet src = resolve_tile_set(name);
    ChainStep first{name,
                    src.size(),
                    src.colours(),
                    "wang",
                    "published",
                    "aperiodic: " + src.source(),
                    fmt::format("tilekit tileset show {} --json", name)};
    for (auto [m, merge] : methods) {
      ConversionSpec spec{m, {merge, false}, -1};
      LabelledConversion c = build_conversion(src, spec);
      CornerSetCandidate cand;
      cand.source = name;
      cand.method = spec_name(spec);
      cand.set = c.set;
      cand.tiles = cand.set.size();
      cand.colours = cand.set.colours();
      cand.soundness = c.soundness;
      const std::string convert_cmd = fmt::format("tilekit aperiodic convert {} --method {}{}", name, method_name(m),
                                                  merge ? " --merge-centres" : "");
      cand.chain = {first,
                    {section(m) + (merge ? ", centre colours merged" : ""), c.conversion.size(), c.conversion.colours,
                     "corner", soundness_name(c.soundness), c.argument, convert_cmd + " --json"}};
      out.push_back(cand);
      if (prune_radius < 0) continue;
      spec.prune = prune_radius;
      LabelledConversion p = build_conversion(src, spec);
      if (p.pruned->after == p.pruned->before) continue;
      CornerSetCandidate pr = cand;
      pr.prune_radius = prune_radius;
      pr.set = p.set;
      pr.soundness = p.soundness;
      pr.tiles = pr.set.size();
      pr.colours = pr.set.colours();
      pr.chain.push_back({fmt::format("prune R={}", prune_radius), pr.tiles, pr.colours, "corner", "prune",
                          p.prune_argument, fmt::format("{} --prune {} --json", convert_cmd, prune_radius)});
      out.push_back(pr);
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const CornerSetCandidate& a, const CornerSetCandidate& b) {
    if (sound(a.soundness) != sound(b.soundness)) return sound(a.soundness);
    if (a.tiles != b.tiles) return a.tiles < b.tiles;
    return a.colours < b.colours;
  });
  return out;
}

CornerSetCandidate smallest_aperiodic_corner_set(int prune_radius) {
  auto all = aperiodic_corner_candidates(prune_radius);
  if (all.empty() || !sound(all.front().soundness)) throw InputError("no sound aperiodic corner set candidate");
  return all.front();
}

}  // namespace tilekit
