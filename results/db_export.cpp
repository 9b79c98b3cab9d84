// Export of the results database: the whole store as one JSON document (streamed row by row,
// so 203,520 solutions do not need to fit in one JSON tree), or one table as CSV.
#include <fmt/format.h>

#include "results/db_rows.hpp"
#include "results/results_db.hpp"
#include "base/error.hpp"

namespace tilekit {

using sqlitedb::Statement;

void ResultsDb::export_json(std::ostream& out) const {
  // One read transaction: a consistent snapshot even while a writer appends (WAL).
  sqlitedb::exec(db_, "BEGIN");
  try {
    out << "{\"tilekit_results\":" << kSchemaVersion;
    auto section = [&](const char* name, const std::string& sql, auto&& row_json) {
      out << ",\n\"" << name << "\":[";
      Statement s(db_, sql);
      bool first = true;
      while (s.step()) {
        // U+FFFD for bytes that are not UTF-8 (text stored by older versions)
        out << (first ? "\n" : ",\n") << row_json(s).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
        first = false;
      }
      out << "]";
    };
    section("runs", std::string(dbrows::kSelectRun) + " ORDER BY id",
            [](const Statement& s) { return dbrows::to_json(dbrows::read_run(s)); });
    section("tilesets", std::string(dbrows::kSelectTileset) + " ORDER BY id",
            [](const Statement& s) { return dbrows::to_json(dbrows::read_tileset(s)); });
    section("conversions", std::string(dbrows::kSelectConversion) + " ORDER BY id",
            [](const Statement& s) { return dbrows::to_json(dbrows::read_conversion(s)); });
    section("solutions", std::string(dbrows::kSelectSolution) + " ORDER BY id",
            [](const Statement& s) { return dbrows::to_json(dbrows::read_solution(s, true), true); });
    out << "\n}\n";
  } catch (...) {
    sqlitedb::exec(db_, "ROLLBACK");
    throw;
  }
  sqlitedb::exec(db_, "COMMIT");
}

namespace {

std::string csv_field(const std::string& v) {
  if (v.find_first_of(",\"\n\r") == std::string::npos) return v;
  std::string q = "\"";
  for (char c : v) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + "\"";
}

}  // namespace

// CSV: the table's columns as SQLite stores them (cells and JSON columns as JSON text).
void ResultsDb::export_csv(std::ostream& out, const std::string& table) const {
  static const std::vector<std::string> tables = {"runs", "solutions", "tilesets", "conversions"};
  if (std::find(tables.begin(), tables.end(), table) == tables.end())
    throw InputError(fmt::format("unknown table '{}' (expected runs, solutions, tilesets or conversions)", table));
  sqlitedb::exec(db_, "BEGIN");
  try {
    Statement s(db_, fmt::format("SELECT * FROM {} ORDER BY id", table));
    sqlite3_stmt* raw = nullptr;
    // Column names come from a prepared statement of the same query.
    if (sqlite3_prepare_v2(db_, fmt::format("SELECT * FROM {}", table).c_str(), -1, &raw, nullptr) != SQLITE_OK)
      sqlitedb::fail(db_, sqlite3_errcode(db_), "cannot read the table's columns");
    const int n = sqlite3_column_count(raw);
    for (int i = 0; i < n; ++i) out << (i ? "," : "") << csv_field(sqlite3_column_name(raw, i));
    sqlite3_finalize(raw);
    out << "\n";
    while (s.step()) {
      for (int i = 0; i < n; ++i) out << (i ? "," : "") << (s.is_null(i) ? std::string() : csv_field(s.text(i)));
      out << "\n";
    }
  } catch (...) {
    sqlitedb::exec(db_, "ROLLBACK");
    throw;
  }
  sqlitedb::exec(db_, "COMMIT");
}

}  // namespace tilekit
