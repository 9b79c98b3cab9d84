#pragma once
// The results database schema as a list of migrations (internal to results/).
// migrations()[v] takes a database at schema version v to v+1; PRAGMA user_version holds
// the version and PRAGMA application_id marks the file as Tilekit's. Documented for
// `sqlite3` users in README.md ("Results database").
#include <sqlite3.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace tilekit::dbschema {

const std::vector<std::string_view>& migrations();

// Tables every Tilekit database of the current version has (checked on open).
const std::vector<std::string_view>& required_tables();

// The first difference between the schema of `db` and the one the first `version` migrations()
// make (1 <= version <= migrations().size()), in words
// ("table 'runs' has no column 'params'", "it has a trigger 'x' of its own"); "" when they are
// the same. Tables, their columns (name, type, NOT NULL, default, key) and constraints, and
// indices must be exactly Tilekit's; triggers and views must not exist (a trigger could refuse
// or rewrite any write, a view hide a table). SQLite's own statistics tables (ANALYZE) are allowed.
std::string schema_difference(sqlite3* db, std::int64_t version);

// The first stored value whose SQLite type does not fit its column's declared type
// ("solutions row 7: column 'rows' holds text"), "" when every value fits. A full scan of every
// table: run with the integrity check, whose cost it shares.
std::string type_difference(sqlite3* db, std::int64_t version);

}  // namespace tilekit::dbschema
