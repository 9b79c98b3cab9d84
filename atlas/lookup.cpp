// Atlas lookup: where a packing comes from (packing/find_packing.hpp: database, then
// construction) and the CPU reference of the shader mapping. The text formats are in
// lookup_formats.cpp.
#include "atlas/lookup.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <memory>

#include "base/error.hpp"
#include "results/results_db.hpp"
#include "packing/find_packing.hpp"
#include "tilesets/constructions.hpp"
#include "tilesets/validator.hpp"
#include "tiling/lattice_hash.hpp"

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
      "Search for one with `tilekit pack --kind {} --colors {} --method search --db {}` (it is stored there and "
      "`tilekit atlas lookup` finds it next time)",
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

// The project's permutation table (thesis 3.4.1, tiling/lattice_hash.hpp) of size 256, so the
// shader's `& 255` is the table's modulo.
std::vector<int> hash_permutation(std::uint64_t seed) {
  const PermutationHash h(256, seed);
  return std::vector<int>(h.table().begin(), h.table().end());
}

namespace {

int hash2(const std::vector<int>& P, std::int64_t x, std::int64_t y) {  // thesis eq. (3.3), N = 256
  return P[std::size_t((P[std::size_t(x & 255)] + y) & 255)];
}
int hash3(const std::vector<int>& P, std::int64_t x, std::int64_t y, std::int64_t z) {  // thesis eq. (3.4)
  return P[std::size_t((hash2(P, x, y) + z) & 255)];
}

}  // namespace

TileIndex virtual_tile(const AtlasLookup& a, const std::vector<int>& P, std::int64_t x, std::int64_t y) {
  const std::uint32_t C = a.colours;
  if (a.kind == TileKind::Corner) {
    // thesis 3.3.1: NE = h(x+1,y+1), SE = h(x+1,y), SW = h(x,y), NW = h(x,y+1)
    auto h = [&](std::int64_t px, std::int64_t py) { return Colour(hash2(P, px, py)) % C; };
    CornerTile t{h(x + 1, y + 1), h(x + 1, y), h(x, y), h(x, y + 1)};
    return corner_index(t, C);  // thesis eq. (2.5)
  }
  // thesis 3.3.2.1: two hashes (here h(x,y,0) and h(x,y,1)); each edge is the sum mod C of
  // the colours at its two end points.
  auto hh = [&](std::int64_t px, std::int64_t py) { return Colour(hash3(P, px, py, 0)) % C; };
  auto hv = [&](std::int64_t px, std::int64_t py) { return Colour(hash3(P, px, py, 1)) % C; };
  WangTile t;
  t.n = (hh(x, y + 1) + hh(x + 1, y + 1)) % C;
  t.e = (hv(x + 1, y + 1) + hv(x + 1, y)) % C;
  t.s = (hh(x + 1, y) + hh(x, y)) % C;
  t.w = (hv(x, y) + hv(x, y + 1)) % C;
  return wang_index(t, C);  // thesis eq. (2.2)
}

std::pair<double, double> virtual_to_atlas(const AtlasLookup& a, const std::vector<int>& perm, double u, double v) {
  const double fx = std::floor(u), fy = std::floor(v);
  const TileIndex t = virtual_tile(a, perm, std::int64_t(fx), std::int64_t(fy));
  const auto [row, col] = a.positions[t];
  // thesis 5.4: the tile's place in the packing plus the position inside the tile; atlas
  // rows run downwards, the virtual texture's y upwards.
  return {(col + (u - fx)) / a.cols, (row + (1.0 - (v - fy))) / a.rows};
}

}  // namespace tilekit
