#include "aperiodic/conversion.hpp"

#include <fmt/format.h>

#include <cassert>

#include "base/error.hpp"

namespace tilekit {

std::string spec_name(const ConversionSpec& spec) {
  std::string name = method_name(spec.method);
  if (spec.method == ConversionMethod::Subdivision && spec.subdivision.merge_centres) name += "+merge-centres";
  if (spec.method == ConversionMethod::Subdivision && spec.subdivision.star_is_edge_colour) name += "+star-edge-colour";
  return name;
}

LabelledConversion build_conversion(const TileSet& source, const ConversionSpec& spec) {
  if (source.empty()) throw InputError(fmt::format("tile set '{}' has no tiles", source.name()));
  LabelledConversion c;
  c.spec = spec;
  c.conversion = convert(source, spec.method, spec.subdivision);
  const std::string name = fmt::format("{}-{}", source.name(), spec_name(spec));
  c.set = conversion_tile_set(c.conversion, name, fmt::format("{} of {} (thesis 8.3/8.4)", spec_name(spec), source.name()));
  assert(c.set.size() == c.conversion.size());
  c.soundness = c.conversion.soundness;
  c.argument = c.conversion.argument;
  if (spec.prune < 0) return c;
  PruneReport rep;
  c.set = prune(c.set, spec.prune, &rep, spec.prune_patch);
  c.set.set_name(fmt::format("{}-pruned{}", name, spec.prune));
  assert(rep.after == c.set.size() && rep.after <= rep.before);
  c.pruned = rep;
  // Translations: the pruned rows may lift even where the full set's do not (convert.hpp).
  std::string why;
  const bool translation = spec.method == ConversionMethod::Horizontal || spec.method == ConversionMethod::Vertical;
  Soundness s = translation ? pruned_soundness(source.wang_tiles(), c.conversion, c.set.corner_tiles(), &why)
                            : c.conversion.soundness;
  s = after_pruning(s, rep);
  if (s != c.soundness) {
    c.soundness = s;
    c.argument = why.empty() ? "pruning removed tiles outside the transducer SCCs: tilings still lift" : why;
  }
  c.prune_argument = fmt::format(
      "{} -> {} tiles ({} not surroundable, {} outside transducer SCCs): surround pruning keeps every tiling, "
      "SCC pruning keeps tileability and periodic tilings{}",
      rep.before, rep.after, rep.removed_by_surround, rep.removed_by_scc, why.empty() ? "" : "; " + why);
  return c;
}

void label_by_decision(LabelledConversion& c, const VerifyResult& v) {
  if (v.verdict != "periodic") return;
  assert(v.period);
  c.soundness = Soundness::Periodic;
  c.argument = fmt::format("a {}x{} torus tiling was found", v.period->first, v.period->second);
}

}  // namespace tilekit
