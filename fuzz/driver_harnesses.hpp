#pragma once
// The harnesses of fuzz/ as fuzz_driver (fuzz/driver.cpp) calls them: each file's
// LLVMFuzzerTestOneInput under its own name. The list is written by the build (fuzz/CMakeLists.txt),
// one entry per harness of TILEKIT_FUZZ_HARNESSES.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tilekit::fuzz {

struct Harness {
  const char* name;  // "tile_set" for fuzz_tile_set.cpp
  int (*run)(const std::uint8_t* data, std::size_t size);
};

const std::vector<Harness>& driver_harnesses();

}  // namespace tilekit::fuzz
