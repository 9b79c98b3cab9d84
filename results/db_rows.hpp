#pragma once
// Row <-> record mapping for the results database (internal to results/): the column
// lists in one place, so queries, export and merge read and write rows the same way.
#include <nlohmann/json.hpp>
#include <string>

#include "base/json_input.hpp"
#include "results/db_sqlite.hpp"
#include "results/results_db.hpp"

namespace tilekit::dbrows {

// ?1 run_id, ?2 kind, ?3 colors, ?4 vertical_colors, ?5 rows, ?6 cols, ?7 torus, ?8 cells,
// ?9 method, ?10 solution_hash, ?11 canonical_hash, ?12 orbit_size, ?13 validated,
// ?14 group_json, ?15 created_at ('' = now). Ignores a duplicate solution_hash.
extern const char* const kInsertSolution;
void bind_solution(sqlitedb::Statement& s, const SolutionRecord& r, const std::string& hash);

// SELECT of every solutions column, in the order read_solution() expects; append WHERE/ORDER.
extern const char* const kSelectSolution;
// The same without the cells (listings).
extern const char* const kSelectSolutionNoCells;
SolutionRecord read_solution(const sqlitedb::Statement& s, bool with_cells);

extern const char* const kSelectRun;
// A "running" row whose process is gone reads as "killed" (on the host that ran it).
RunRecord read_run(const sqlitedb::Statement& s);
// The process `pid` that started at `start` (clock ticks after boot) no longer runs on `host`,
// which is this host (results_db.cpp).
bool process_gone(const std::string& host, std::int64_t pid, std::int64_t start);
extern const char* const kSelectTileset;
TilesetRecord read_tileset(const sqlitedb::Statement& s);
extern const char* const kSelectConversion;
ConversionRecord read_conversion(const sqlitedb::Statement& s);

// JSON forms (export, `db show`, `db list`), and back (merge of a JSON export).
nlohmann::json to_json(const RunRecord& r);
nlohmann::json to_json(const SolutionRecord& r, bool with_cells);
nlohmann::json to_json(const TilesetRecord& r);
nlohmann::json to_json(const ConversionRecord& r);
// Each throws InputError naming the file and the JSON path of a bad field.
RunRecord run_from_json(const JsonIn& j);
SolutionRecord solution_from_json(const JsonIn& j);
TilesetRecord tileset_from_json(const JsonIn& j);
ConversionRecord conversion_from_json(const JsonIn& j);

}  // namespace tilekit::dbrows
