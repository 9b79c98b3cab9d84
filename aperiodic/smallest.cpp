#include "aperiodic/smallest.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "aperiodic/prune.hpp"
#include "base/error.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit {

namespace {

bool sound(Soundness s) { return s == Soundness::Conjugate || s == Soundness::Lifts; }

std::string section(ConversionMethod m) {
  switch (m) {
    case ConversionMethod::Diagonal: return "diagonal translation (thesis 8.3.1)";
    case ConversionMethod::Horizontal: return "horizontal translation (thesis 8.3.2)";
    case ConversionMethod::Vertical: return "vertical translation (thesis 8.3.2)";
    case ConversionMethod::Rotation: return "rotation with checkerboard tiles (thesis 8.3.3)";
    case ConversionMethod::Subdivision: return "subdivision (thesis 8.3.4)";
    case ConversionMethod::ToWang: return "pair colours (thesis 8.4)";
  }
  return "?";
}

}  // namespace

const std::vector<std::string>& published_aperiodic_sets() {
  static const std::vector<std::string> s = {"culik-13", "kari-14", "ammann-gs-16", "jeandel-rao-11", "labbe-19"};
  return s;
}

std::vector<Candidate> aperiodic_corner_candidates(int prune_radius) {
  std::vector<Candidate> out;
  const std::vector<std::pair<ConversionMethod, bool>> methods = {
      {ConversionMethod::Diagonal, false},    {ConversionMethod::Horizontal, false},
      {ConversionMethod::Vertical, false},    {ConversionMethod::Rotation, false},
      {ConversionMethod::Subdivision, false}, {ConversionMethod::Subdivision, true}};
  for (const std::string& name : published_aperiodic_sets()) {
    TileSet src = resolve_tile_set(name);
    ChainStep first{name, src.size(), src.colours(), "wang", "published", "aperiodic: " + src.source()};
    for (auto [m, merge] : methods) {
      Conversion c = convert(src, m, {merge, false});
      std::string method = method_name(m) + (merge ? "+merge-centres" : "");
      Candidate cand;
      cand.source = name;
      cand.method = method;
      cand.set = conversion_tile_set(c, fmt::format("{}-{}", name, method), fmt::format("{} of {}", method, name));
      cand.tiles = cand.set.size();
      cand.colours = cand.set.colours();
      cand.soundness = c.soundness;
      cand.chain = {first, {section(m) + (merge ? ", centre colours merged" : ""), c.size(), c.colours, "corner",
                            soundness_name(c.soundness), c.argument}};
      out.push_back(cand);
      if (prune_radius < 0) continue;
      PruneReport rep;
      Candidate pr = cand;
      pr.prune_radius = prune_radius;
      pr.set = prune(cand.set, prune_radius, &rep);
      if (rep.after == rep.before) continue;
      pr.set.set_name(fmt::format("{}-pruned{}", cand.set.name(), prune_radius));
      std::string why;
      pr.soundness = after_pruning(pruned_soundness(src.wang_tiles(), c, pr.set.corner_tiles(), &why), rep);
      pr.tiles = pr.set.size();
      pr.colours = pr.set.colours();
      pr.chain.push_back({fmt::format("prune R={}", prune_radius), pr.tiles, pr.colours, "corner", "prune",
                          fmt::format("{} -> {} tiles ({} not surroundable, {} outside transducer SCCs): surround pruning "
                                      "keeps every tiling, SCC pruning keeps tileability and periodic tilings{}",
                                      rep.before, rep.after, rep.removed_by_surround, rep.removed_by_scc,
                                      why.empty() ? "" : "; " + why)});
      out.push_back(pr);
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) {
    if (sound(a.soundness) != sound(b.soundness)) return sound(a.soundness);
    if (a.tiles != b.tiles) return a.tiles < b.tiles;
    return a.colours < b.colours;
  });
  return out;
}

Candidate smallest_aperiodic_corner_set(int prune_radius) {
  auto all = aperiodic_corner_candidates(prune_radius);
  if (all.empty() || !sound(all.front().soundness)) throw InputError("no sound aperiodic corner set candidate");
  return all.front();
}

}  // namespace tilekit
