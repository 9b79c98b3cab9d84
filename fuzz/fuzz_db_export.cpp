// Database exports read by `db merge OUT export.json` (results/db_merge.cpp): every row is
// converted and checked before anything would be written.
#include <cstdint>
#include <string>

#include "base/error.hpp"
#include "results/results_db.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    tilekit::ResultsDb::check_export(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.json");
  } catch (const tilekit::InputError&) {
  }
  return 0;
}
