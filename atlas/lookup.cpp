// Atlas lookup: where a packing comes from (packing/find_packing.hpp: database, then
// construction) and the CPU reference of the shader mapping. The text formats are in
// lookup_formats.cpp.
#include "atlas/lookup.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <memory>

#include "base/error.hpp"
#include "packing/find_packing.hpp"
#include "results/results_db.hpp"
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

namespace {

std::unique_ptr<ResultsDb> open_lookup_db(const std::string& path) {
  std::error_code ec;
  if (path.empty() || !std::filesystem::exists(path, ec)) return nullptr;  // a lookup never creates one
  // Read-only and without the O(size) integrity check: a lookup must answer in milliseconds;
  // the packing read is re-checked by the validator instead.
  return std::make_unique<ResultsDb>(path, DbOpenOptions{.create = false, .read_only = true});
}

std::string unavailable_message(TileKind kind, std::uint32_t colours, ResultsDb* db, const std::string& db_path) {
  std::vector<std::uint32_t> avail = constructible_colours(kind, 32);
  if (db)
    for (std::uint32_t c = 1; c <= 32; ++c)
      if (db->find_solution(kind, c, int(c * c), int(c * c)) && std::find(avail.begin(), avail.end(), c) == avail.end())
        avail.push_back(c);
  std::sort(avail.begin(), avail.end());
  std::string list;
  for (std::uint32_t c : avail) list += (list.empty() ? "" : ", ") + std::to_string(c);
  return fmt::format(
      "no {} packing over {} colours is available (no construction, none stored{}); available C up to 32: {}. "
      "Search for one with `tilekit pack` and `kind` {} `colours` {} `method` search `db` {} (it is stored there "
      "and `tilekit atlas lookup` finds it next time)",
      kind_name(kind), colours, db ? " in " + db->path() : "", list, kind_name(kind), colours,
      db_path.empty() ? "FILE" : db_path);
}

}  // namespace

AtlasLookup atlas_lookup(TileKind kind, std::uint32_t colours, const LookupOptions& options) {
  check_complete_set_colours(colours);
  std::unique_ptr<ResultsDb> db = open_lookup_db(options.db_path);
  PackingSources src;
  src.db = db.get();
  // Every answer is checked by the independent validator: a stored packing in find_packing, a
  // construction there too (proven, see tilesets/construct_*.cpp; a C=32 corner packing,
  // 1024x1024 cells, validates in about 0.1 s: BENCHMARKS.md).
  src.validate_construction = true;
  std::optional<FoundPacking> found = find_packing(kind, colours, src);
  if (!found) throw NotFound(unavailable_message(kind, colours, db.get(), options.db_path));
  AtlasLookup a = lookup_from_packing(found->tiling, found->source, found->how, found->closed_form, false);
  a.solution_id = found->solution_id;
  return a;
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
