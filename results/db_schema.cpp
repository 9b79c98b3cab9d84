#include "results/db_schema.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <mutex>

#include "results/db_sqlite.hpp"

namespace tilekit::dbschema {

namespace {

// Version 0 -> 1: the first schema. Times are ISO 8601 UTC text; JSON columns are text that
// SQLite's json_* functions read (e.g. json_extract(params, '$.colors')).
constexpr std::string_view kSchemaV1 = R"SQL(
CREATE TABLE tilekit_meta (
  key   TEXT PRIMARY KEY,
  value TEXT NOT NULL
);
INSERT INTO tilekit_meta(key, value) VALUES ('application', 'tilekit results database');

CREATE TABLE runs (
  id          INTEGER PRIMARY KEY,
  uid         TEXT NOT NULL UNIQUE,
  command     TEXT NOT NULL,
  params      TEXT NOT NULL DEFAULT '{}',
  status      TEXT NOT NULL DEFAULT 'running',
  solutions   INTEGER NOT NULL DEFAULT 0,
  orbits      INTEGER,
  nodes       INTEGER NOT NULL DEFAULT 0,
  seconds     REAL NOT NULL DEFAULT 0,
  threads     INTEGER NOT NULL DEFAULT 1,
  host        TEXT NOT NULL DEFAULT '',
  version     TEXT NOT NULL DEFAULT '',
  started_at  TEXT NOT NULL,
  finished_at TEXT
);
CREATE INDEX runs_by_command ON runs(command, status);

CREATE TABLE solutions (
  id              INTEGER PRIMARY KEY,
  run_id          INTEGER REFERENCES runs(id) ON DELETE SET NULL,
  kind            TEXT NOT NULL CHECK (kind IN ('wang', 'corner')),
  colors          INTEGER NOT NULL,
  vertical_colors INTEGER NOT NULL DEFAULT 0,
  rows            INTEGER NOT NULL,
  cols            INTEGER NOT NULL,
  torus           INTEGER NOT NULL DEFAULT 1,
  cells           TEXT NOT NULL,
  method          TEXT NOT NULL DEFAULT '',
  solution_hash   TEXT NOT NULL UNIQUE,
  canonical_hash  TEXT NOT NULL DEFAULT '',
  orbit_size      INTEGER NOT NULL DEFAULT 0,
  validated       INTEGER NOT NULL DEFAULT 0,
  group_json      TEXT,
  created_at      TEXT NOT NULL
);
CREATE INDEX solutions_by_shape ON solutions(kind, colors, rows, cols, validated);
CREATE INDEX solutions_by_canonical ON solutions(canonical_hash);
CREATE INDEX solutions_by_run ON solutions(run_id);

CREATE TABLE tilesets (
  id           INTEGER PRIMARY KEY,
  name         TEXT NOT NULL,
  kind         TEXT NOT NULL CHECK (kind IN ('wang', 'corner')),
  tiles        INTEGER NOT NULL,
  colors       INTEGER NOT NULL,
  content_hash TEXT NOT NULL,
  source       TEXT NOT NULL DEFAULT '',
  text         TEXT NOT NULL DEFAULT '',
  created_at   TEXT NOT NULL,
  UNIQUE (name, content_hash)
);
CREATE INDEX tilesets_by_hash ON tilesets(content_hash);

CREATE TABLE conversions (
  id           INTEGER PRIMARY KEY,
  source_set   INTEGER NOT NULL REFERENCES tilesets(id),
  method       TEXT NOT NULL,
  result_set   INTEGER NOT NULL REFERENCES tilesets(id),
  tiles_before INTEGER NOT NULL,
  tiles_after  INTEGER NOT NULL,
  colors       INTEGER NOT NULL,
  soundness    TEXT NOT NULL DEFAULT 'unknown',
  details      TEXT NOT NULL DEFAULT '{}',
  created_at   TEXT NOT NULL,
  UNIQUE (source_set, method, result_set)
);
CREATE INDEX conversions_by_result ON conversions(result_set);
)SQL";

// Version 1 -> 2: window tori (de Bruijn tori, kind 'window') and their window size. SQLite
// cannot change a CHECK constraint in place, so the solutions table is rebuilt with every row.
constexpr std::string_view kSchemaV2 = R"SQL(
CREATE TABLE solutions_v2 (
  id              INTEGER PRIMARY KEY,
  run_id          INTEGER REFERENCES runs(id) ON DELETE SET NULL,
  kind            TEXT NOT NULL CHECK (kind IN ('wang', 'corner', 'window')),
  colors          INTEGER NOT NULL,
  vertical_colors INTEGER NOT NULL DEFAULT 0,
  rows            INTEGER NOT NULL,
  cols            INTEGER NOT NULL,
  torus           INTEGER NOT NULL DEFAULT 1,
  cells           TEXT NOT NULL,
  method          TEXT NOT NULL DEFAULT '',
  solution_hash   TEXT NOT NULL UNIQUE,
  canonical_hash  TEXT NOT NULL DEFAULT '',
  orbit_size      INTEGER NOT NULL DEFAULT 0,
  validated       INTEGER NOT NULL DEFAULT 0,
  group_json      TEXT,
  created_at      TEXT NOT NULL,
  window_rows     INTEGER NOT NULL DEFAULT 0,
  window_cols     INTEGER NOT NULL DEFAULT 0
);
INSERT INTO solutions_v2(id, run_id, kind, colors, vertical_colors, rows, cols, torus, cells, method, solution_hash,
                         canonical_hash, orbit_size, validated, group_json, created_at)
  SELECT id, run_id, kind, colors, vertical_colors, rows, cols, torus, cells, method, solution_hash, canonical_hash,
         orbit_size, validated, group_json, created_at FROM solutions;
DROP TABLE solutions;
ALTER TABLE solutions_v2 RENAME TO solutions;
CREATE INDEX solutions_by_shape ON solutions(kind, colors, rows, cols, validated);
CREATE INDEX solutions_by_canonical ON solutions(canonical_hash);
CREATE INDEX solutions_by_run ON solutions(run_id);
)SQL";

// Version 2 -> 3: the process of a run (pid and its start time in clock ticks after boot, from
// /proc/PID/stat), so that a run whose process died without closing its row (SIGKILL, a crash,
// a node lost) is marked "killed" when the database is next opened on that host.
constexpr std::string_view kSchemaV3 = R"SQL(
ALTER TABLE runs ADD COLUMN pid INTEGER;
ALTER TABLE runs ADD COLUMN pid_start INTEGER;
)SQL";

}  // namespace

const std::vector<std::string_view>& migrations() {
  static const std::vector<std::string_view> list = {kSchemaV1, kSchemaV2, kSchemaV3};
  return list;
}

const std::vector<std::string_view>& required_tables() {
  static const std::vector<std::string_view> list = {"tilekit_meta", "runs", "solutions", "tilesets",
                                                     "conversions"};
  return list;
}

namespace {

using sqlitedb::Statement;

struct Object {
  std::string type, table, sql;  // sql: NULL for SQLite's automatic indices
};
// Every schema object but SQLite's statistics tables, by name.
std::map<std::string, Object> objects(sqlite3* db) {
  std::map<std::string, Object> out;
  Statement s(db, "SELECT type, name, tbl_name, COALESCE(sql, '') FROM sqlite_master WHERE name NOT LIKE 'sqlite_stat%'");
  while (s.step()) out[s.text(1)] = {s.text(0), s.text(2), s.text(3)};
  return out;
}

struct Column {
  std::string type, default_value;
  bool not_null = false;
  std::int64_t key = 0;
  friend bool operator==(const Column&, const Column&) = default;
};
std::vector<std::pair<std::string, Column>> columns(sqlite3* db, const std::string& table) {
  std::vector<std::pair<std::string, Column>> out;
  Statement s(db, "SELECT name, type, \"notnull\", COALESCE(dflt_value, ''), pk FROM pragma_table_xinfo(?1)");
  s.bind(1, table);
  while (s.step()) out.push_back({s.text(0), {s.text(1), s.text(3), s.int64(2) != 0, s.int64(4)}});
  return out;
}

using Columns = std::vector<std::pair<std::string, Column>>;

// The schema the first `version` migrations make: its objects and every table's columns, read
// from an in-memory database made by those migrations. Made once per version and process (a few
// milliseconds that every open of a database would otherwise pay, twice).
struct Reference {
  std::map<std::string, Object> objects;
  std::map<std::string, Columns> columns;  // by table
};
const Reference& reference(std::int64_t version) {
  static std::mutex mu;
  static std::map<std::int64_t, Reference> made;  // entries stay put when others are added
  std::lock_guard lock(mu);
  if (auto it = made.find(version); it != made.end()) return it->second;
  sqlite3* db = nullptr;
  if (sqlite3_open(":memory:", &db) != SQLITE_OK) {
    sqlite3_close(db);
    throw std::runtime_error("cannot open an in-memory database");
  }
  struct Closer {
    sqlite3* d;
    ~Closer() { sqlite3_close(d); }
  } closer{db};
  for (std::int64_t v = 0; v < version; ++v) sqlitedb::exec(db, std::string(migrations()[std::size_t(v)]).c_str());
  Reference r;
  r.objects = objects(db);
  for (const auto& [name, o] : r.objects)
    if (o.type == "table") r.columns[name] = columns(db, name);
  return made.emplace(version, std::move(r)).first->second;
}

std::string quoted(const std::string& name) { return "'" + name + "'"; }

std::string table_difference(sqlite3* db, const Columns& want, const std::string& table) {
  const auto have = columns(db, table);
  for (const auto& w : want) {  // (not a structured binding: clang 14 cannot use one in a lambda)
    const std::string& name = w.first;
    const auto& col = w.second;
    auto it = std::find_if(have.begin(), have.end(), [&](const auto& c) { return c.first == name; });
    if (it == have.end()) return fmt::format("table {} has no column {}", quoted(table), quoted(name));
    if (!(it->second == col))
      return fmt::format("column {} of table {} is declared differently ({}{}{}; Tilekit's: {}{}{})", quoted(name),
                         quoted(table), it->second.type, it->second.not_null ? " NOT NULL" : "",
                         it->second.default_value.empty() ? "" : " DEFAULT " + it->second.default_value, col.type,
                         col.not_null ? " NOT NULL" : "", col.default_value.empty() ? "" : " DEFAULT " + col.default_value);
  }
  for (const auto& h : have)
    if (std::none_of(want.begin(), want.end(), [&](const auto& c) { return c.first == h.first; }))
      return fmt::format("table {} has a column {} that Tilekit does not make", quoted(table), quoted(h.first));
  if (std::equal(have.begin(), have.end(), want.begin(), want.end())) return {};
  return fmt::format("the columns of table {} are in another order", quoted(table));
}

}  // namespace

std::string schema_difference(sqlite3* db, std::int64_t version) {
  const Reference& ref = reference(version);
  const auto have = objects(db);
  const auto& want = ref.objects;
  // What the file has of its own first: triggers and views are the dangerous part.
  for (const char* type : {"trigger", "view", "table", "index"})
    for (const auto& [name, o] : have)
      if (o.type == type && !want.count(name))
        return o.type == "trigger" ? fmt::format("it has a trigger {} of its own (on {})", quoted(name), quoted(o.table))
               : o.type == "view"  ? fmt::format("it has a view {} of its own", quoted(name))
               : o.type == "table" ? fmt::format("it has a table {} that Tilekit does not make", quoted(name))
                                   : fmt::format("it has an index {} on {} that Tilekit does not make", quoted(name),
                                                 quoted(o.table));
  for (const auto& [name, o] : want) {
    auto it = have.find(name);
    if (it == have.end()) return fmt::format("{} {} is missing", o.type, quoted(name));
    if (it->second.type != o.type || it->second.table != o.table)
      return fmt::format("{} is a {} on {}, not a {} on {}", quoted(name), it->second.type, quoted(it->second.table),
                         o.type, quoted(o.table));
    if (it->second.sql == o.sql) continue;
    if (o.type == "table") {
      std::string d = table_difference(db, ref.columns.at(name), name);
      return d.empty() ? fmt::format("table {} has other constraints than Tilekit's", quoted(name)) : d;
    }
    return fmt::format("{} {} is defined differently", o.type, quoted(name));
  }
  return {};
}

std::string type_difference(sqlite3* db, std::int64_t version) {
  const Reference& ref = reference(version);
  for (std::string_view t : required_tables()) {
    const std::string table(t);
    // One scan per table: the first row with a value whose type does not fit, and which column.
    const auto want = ref.columns.find(table);
    if (want == ref.columns.end()) continue;  // not made at this version
    std::string cases;
    for (const auto& [name, col] : want->second) {
      std::string allowed = col.type == "INTEGER" ? "'integer'" : col.type == "REAL" ? "'real', 'integer'" : "'text'";
      if (!col.not_null && col.key == 0) allowed += ", 'null'";
      cases += fmt::format(" WHEN typeof(\"{0}\") NOT IN ({1}) THEN '{0}'", name, allowed);
    }
    Statement s(db, fmt::format("SELECT rowid, bad FROM (SELECT rowid, CASE{} END AS bad FROM \"{}\") "
                                "WHERE bad IS NOT NULL LIMIT 1",
                                cases, table));
    if (s.step()) {
      Statement v(db, fmt::format("SELECT typeof(\"{}\") FROM \"{}\" WHERE rowid = ?1", s.text(1), table));
      v.bind(1, s.int64(0));
      const std::string type = v.step() ? v.text(0) : "?";
      return fmt::format("{} row {}: column {} holds {} (a value of the wrong type)", table, s.int64(0),
                         quoted(s.text(1)), type == "null" ? "NULL" : type);
    }
  }
  return {};
}

}  // namespace tilekit::dbschema
