// Checkpoint files (checkpoints/checkpoint.hpp). The first byte picks the mode: the input as a
// whole file (header, length, checksum), or the input as a body wrapped in a valid header so
// that the fuzzer reaches the JSON and the structural checks past the checksum.
#include <fmt/format.h>

#include <cstdint>
#include <string>

#include "base/error.hpp"
#include "base/hash.hpp"
#include "checkpoints/checkpoint.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tilekit;
  if (size == 0) return 0;
  const std::string body(reinterpret_cast<const char*>(data) + 1, size - 1);
  const std::string file = data[0] & 1 ? body
                                       : fmt::format("TILEKIT-CHECKPOINT {}\nbytes {} fnv1a64 {:016x}\n{}",
                                                     kCheckpointVersion, body.size(), fnv1a64(body), body);
  try {
    const SearchState st = decode_checkpoint(file, "fuzz.ckpt");
    check_search_state(st);  // what the loader accepted is consistent
    const SearchState again = decode_checkpoint(encode_checkpoint(st), "again.ckpt");
    if (again.in_flight.size() != st.in_flight.size() || again.finished != st.finished) __builtin_trap();
  } catch (const InputError&) {
  }
  return 0;
}
