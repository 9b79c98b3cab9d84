// Chain records (`aperiodic smallest --record FILE`, aperiodic/smallest.hpp): any input parses to
// a record or is an InputError; a parsed record's fields are within their documented bounds.
#include <cstdint>
#include <string>

#include "aperiodic/smallest.hpp"
#include "base/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tilekit;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const RecordedChain r = parse_smallest_record(text, "fuzz.json");
    if (r.steps.size() > 64 || r.source.size() > 256 || r.set.size() > 64) __builtin_trap();
  } catch (const InputError&) {
  }
  return 0;
}
