#include "results/db_schema.hpp"

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

}  // namespace

const std::vector<std::string_view>& migrations() {
  static const std::vector<std::string_view> list = {kSchemaV1, kSchemaV2};
  return list;
}

const std::vector<std::string_view>& required_tables() {
  static const std::vector<std::string_view> list = {"tilekit_meta", "runs", "solutions", "tilesets",
                                                     "conversions"};
  return list;
}

}  // namespace tilekit::dbschema
