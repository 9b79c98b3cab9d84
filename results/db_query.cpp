// Read queries of the results database: counts, one record by id, listings.
#include <fmt/format.h>

#include "results/db_rows.hpp"
#include "results/results_db.hpp"

namespace tilekit {

using sqlitedb::Statement;

DbStats ResultsDb::stats() const {
  // distinct_solutions counts orbits: rows sharing a canonical hash count once; a row
  // without one counts by itself.
  Statement s(db_,
              "SELECT (SELECT COUNT(*) FROM runs), (SELECT COUNT(*) FROM solutions), "
              "(SELECT COUNT(DISTINCT COALESCE(NULLIF(canonical_hash, ''), solution_hash)) FROM solutions), "
              "(SELECT COUNT(*) FROM tilesets), (SELECT COUNT(*) FROM conversions)");
  s.step();
  DbStats st;
  st.runs = std::uint64_t(s.int64(0));
  st.solutions = std::uint64_t(s.int64(1));
  st.distinct_solutions = std::uint64_t(s.int64(2));
  st.tilesets = std::uint64_t(s.int64(3));
  st.conversions = std::uint64_t(s.int64(4));
  return st;
}

std::optional<RunRecord> ResultsDb::run(std::int64_t id) const {
  Statement s(db_, std::string(dbrows::kSelectRun) + " WHERE id = ?1");
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  return dbrows::read_run(s);
}

std::optional<SolutionRecord> ResultsDb::solution(std::int64_t id) const {
  Statement s(db_, std::string(dbrows::kSelectSolution) + " WHERE id = ?1");
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  return dbrows::read_solution(s, true);
}

std::optional<TilesetRecord> ResultsDb::tileset(std::int64_t id) const {
  Statement s(db_, std::string(dbrows::kSelectTileset) + " WHERE id = ?1");
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  return dbrows::read_tileset(s);
}

std::optional<ConversionRecord> ResultsDb::conversion(std::int64_t id) const {
  Statement s(db_, std::string(dbrows::kSelectConversion) + " WHERE id = ?1");
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  return dbrows::read_conversion(s);
}

namespace {
std::string page(std::size_t limit, std::size_t offset) {
  return fmt::format(" LIMIT {} OFFSET {}", limit ? std::int64_t(limit) : std::int64_t(-1), offset);
}
}  // namespace

std::vector<RunRecord> ResultsDb::list_runs(std::size_t limit, std::size_t offset) const {
  Statement s(db_, std::string(dbrows::kSelectRun) + " ORDER BY id" + page(limit, offset));
  std::vector<RunRecord> out;
  while (s.step()) out.push_back(dbrows::read_run(s));
  return out;
}

std::vector<SolutionRecord> ResultsDb::list_solutions(const SolutionFilter& f, bool with_cells) const {
  std::string sql = with_cells ? dbrows::kSelectSolution : dbrows::kSelectSolutionNoCells;
  sql += " WHERE (?1 = '' OR kind = ?1) AND (?2 = 0 OR colors = ?2) AND (?3 = 0 OR run_id = ?3) ORDER BY id";
  sql += page(f.limit, f.offset);
  Statement s(db_, sql);
  s.bind(1, f.kind ? std::string(kind_name(*f.kind)) : std::string())
      .bind(2, std::int64_t(f.colours))
      .bind(3, f.run_id);
  std::vector<SolutionRecord> out;
  while (s.step()) out.push_back(dbrows::read_solution(s, with_cells));
  return out;
}

std::vector<TilesetRecord> ResultsDb::list_tilesets(std::size_t limit, std::size_t offset) const {
  Statement s(db_, std::string(dbrows::kSelectTileset) + " ORDER BY id" + page(limit, offset));
  std::vector<TilesetRecord> out;
  while (s.step()) out.push_back(dbrows::read_tileset(s));
  return out;
}

std::vector<ConversionRecord> ResultsDb::list_conversions(std::size_t limit, std::size_t offset) const {
  Statement s(db_, std::string(dbrows::kSelectConversion) + " ORDER BY id" + page(limit, offset));
  std::vector<ConversionRecord> out;
  while (s.step()) out.push_back(dbrows::read_conversion(s));
  return out;
}

}  // namespace tilekit
