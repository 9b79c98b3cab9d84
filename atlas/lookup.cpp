// Atlas lookup: a packing's positions (from any packing, or the constructed one) and the CPU
// reference of the shader mapping. The text formats are in lookup_formats.cpp; a packing from a
// results database comes through packing/find_packing.hpp.
#include "atlas/lookup.hpp"

#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <stdexcept>

#include "base/error.hpp"
#include "tilesets/constructions.hpp"
#include "tilesets/validator.hpp"

namespace tilekit {

AtlasLookup lookup_from_packing(const Tiling& t, std::string source, std::string how, bool closed_form,
                                bool run_validator) {
  const std::uint64_t n = std::uint64_t(t.colours) * t.colours;
  if (t.rows != int(n) || t.cols != int(n) || !t.torus || t.cv() != t.ch())
    throw InputError(fmt::format("a {}x{} grid is not a C^2 x C^2 torus packing for C={}", t.rows, t.cols, t.colours));
  if (run_validator) {
    ValidationReport rep = validate(t);
    if (!rep.packing)
      throw InputError(fmt::format("not a packing of the complete {} set over {} colours: {}", kind_name(t.kind),
                                   t.colours, rep.errors.empty() ? "tiles missing or repeated" : rep.errors.front()));
  }
  AtlasLookup a;
  a.kind = t.kind;
  a.colours = t.colours;
  a.rows = t.rows;
  a.cols = t.cols;
  a.cells = t.cells;
  a.positions.assign(t.cells.size(), {-1, -1});
  // Inverse; also the cheap half of the packing check: every tile exactly once.
  for (int r = 0; r < t.rows; ++r)
    for (int c = 0; c < t.cols; ++c) {
      const TileIndex tile = t.at(r, c);
      if (tile >= a.positions.size() || a.positions[tile].first >= 0)
        throw InputError(fmt::format("cell ({},{}): tile {} is out of range or repeated", r, c, tile));
      a.positions[tile] = {r, c};
    }
  a.source = std::move(source);
  a.how = std::move(how);
  a.closed_form = closed_form;
  return a;
}

AtlasLookup atlas_lookup(TileKind kind, std::uint32_t colours) {
  check_complete_set_colours(colours);
  std::optional<ConstructedPacking> p = construct_packing(kind, colours);
  if (!p) {
    std::string list;
    for (std::uint32_t c : constructible_colours(kind, 32)) list += (list.empty() ? "" : ", ") + std::to_string(c);
    throw NotFound(fmt::format(
        "no {} packing over {} colours is constructed or stored in Tilekit; constructed C up to 32: {}. Search for "
        "one with `tilekit pack` and `kind` {} `colours` {} `method` search `db` FILE, and name that database with "
        "`db`",
        kind_name(kind), colours, list, kind_name(kind), colours));
  }
  // Proven constructions (tilesets/construct_*.cpp), checked all the same: a C=32 corner packing,
  // 1024x1024 cells, validates in about 0.1 s (BENCHMARKS.md).
  if (!validate(p->tiling).packing)
    throw std::logic_error(fmt::format("the {} construction for C={} is not a packing", p->how, colours));
  return lookup_from_packing(p->tiling, "construct", p->how, p->closed_form, false);
}

void check_same_set(const AtlasLookup& a, const DirectTiling& tiling) {
  if (a.kind != tiling.kind() || a.colours != tiling.colours())
    throw InputError(fmt::format("a tiling of the {} set over {} colours does not index an atlas of the {} set over {}",
                                 kind_name(tiling.kind()), tiling.colours(), kind_name(a.kind), a.colours));
}

std::pair<double, double> virtual_to_atlas(const AtlasLookup& a, const DirectTiling& tiling, double u, double v) {
  check_same_set(a, tiling);
  const double fx = std::floor(u), fy = std::floor(v);
  const auto [row, col] = a.positions[tiling.tile(std::int64_t(fx), std::int64_t(fy))];
  return {(col + (u - fx)) / a.cols, (row + (v - fy)) / a.rows};  // thesis 5.4
}

}  // namespace tilekit
