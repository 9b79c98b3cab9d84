// find_packing: database, construction, search, in that order (find_packing.hpp).
#include "packing/find_packing.hpp"

#include <fmt/format.h>

#include "base/error.hpp"
#include "results/results_db.hpp"
#include "tilesets/constructions.hpp"
#include "tilesets/validator.hpp"

namespace tilekit {

std::optional<FoundPacking> find_packing(TileKind kind, std::uint32_t colours, const PackingSources& sources) {
  if (colours < 1 || colours > 255)
    throw RequestError("colours", fmt::format("`colours` must be between 1 and 255, got {}", colours));
  const int n = int(colours * colours);
  if (sources.db) {
    if (auto s = sources.db->find_solution(kind, colours, n, n)) {
      // Stored data is re-checked by the independent validator: a row edited by hand or a
      // database from elsewhere never answers with a wrong packing.
      ValidationReport rep = validate(s->tiling);
      if (rep.packing && s->tiling.torus && s->tiling.rows == n && s->tiling.cols == n)
        return FoundPacking{s->tiling, "db", fmt::format("solution {} in {}", s->id, sources.db->path()), false, s->id};
    }
  }
  if (sources.construct) {
    if (auto p = construct_packing(kind, colours)) {
      if (sources.validate_construction && !validate(p->tiling).packing)
        throw std::logic_error(fmt::format("the {} construction for C={} is not a packing", p->how, colours));
      return FoundPacking{std::move(p->tiling), "construct", p->how, p->closed_form, 0};
    }
  }
  if (sources.search) return sources.search();
  return std::nullopt;
}

}  // namespace tilekit
