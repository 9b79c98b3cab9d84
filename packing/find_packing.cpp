// find_packing: database, construction, search, in that order (find_packing.hpp), and the
// lookup's use of it.
#include "packing/find_packing.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <memory>

#include "base/error.hpp"
#include "results/results_db.hpp"
#include "tilesets/constructions.hpp"
#include "tilesets/tile_set.hpp"
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

FoundPacking find_lookup_packing(TileKind kind, std::uint32_t colours, const std::string& db_path) {
  check_complete_set_colours(colours);
  std::unique_ptr<ResultsDb> db = open_lookup_db(db_path);
  PackingSources src;
  src.db = db.get();
  // Every answer is checked by the independent validator: a stored packing here, a construction
  // too (proven, see tilesets/construct_*.cpp; a C=32 corner packing, 1024x1024 cells, validates
  // in about 0.1 s: BENCHMARKS.md).
  src.validate_construction = true;
  std::optional<FoundPacking> found = find_packing(kind, colours, src);
  if (!found) throw NotFound(unavailable_message(kind, colours, db.get(), db_path));
  return std::move(*found);
}

}  // namespace tilekit
