// Checkpoint files (checkpoints/checkpoint.hpp), version 3, single searches and portfolios. The first byte picks
// the mode: the input as a whole file (header, length, checksum), or the input as a body wrapped in a valid header so
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
    const CheckpointFile f = decode_checkpoint_file(file, "fuzz.ckpt");
    if (f.search) check_search_state(*f.search);  // what the loader accepted is consistent
    const CheckpointFile again = decode_checkpoint_file(encode_checkpoint(f), "again.ckpt");
    if (again.search.has_value() != f.search.has_value() || again.request != f.request) __builtin_trap();
    if (f.search &&
        (again.search->in_flight.size() != f.search->in_flight.size() || again.search->finished != f.search->finished))
      __builtin_trap();
    if (f.portfolio && again.portfolio->candidates.size() != f.portfolio->candidates.size()) __builtin_trap();
  } catch (const InputError&) {
  }
  return 0;
}
