#pragma once
// The results database schema as a list of migrations (internal to results/).
// migrations()[v] takes a database at schema version v to v+1; PRAGMA user_version holds
// the version and PRAGMA application_id marks the file as Tilekit's. Documented for
// `sqlite3` users in README.md ("Results database").
#include <string_view>
#include <vector>

namespace tilekit::dbschema {

const std::vector<std::string_view>& migrations();

// Tables every Tilekit database of the current version has (checked on open).
const std::vector<std::string_view>& required_tables();

}  // namespace tilekit::dbschema
