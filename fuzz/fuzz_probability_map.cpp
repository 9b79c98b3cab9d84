// Colour probability maps of `tile --algo controlled --map FILE` (tiling/controlled_tiling.hpp).
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "base/error.hpp"
#include "base/json_input.hpp"
#include "tiling/controlled_tiling.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tilekit;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const ProbabilityMap m = probability_map_from_json(parse_json_input(text, "fuzz.json"), "fuzz.json");
    for (double p : m.p)
      if (!(p >= 0 && p <= 1)) std::abort();  // what loads is a distribution per pixel
    probability_map_to_json(m).dump();
  } catch (const InputError&) {
  }
  return 0;
}
