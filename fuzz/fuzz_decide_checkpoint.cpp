// Checkpoints of `aperiodic verify` (aperiodic/decide_checkpoint.hpp): transducer chains of
// Kari's 14 Wang tiles (aperiodic, so a run stays undecided and checkpoints its levels). Byte 0 picks the whole file (odd) or a body
// under a valid envelope and checksum (even), so that the fuzzer reaches the chain levels. What
// loads is re-encoded and must decode to the same chains; its fingerprint, JSON in a string, goes
// through fingerprint_difference like a resume's.
#include <fmt/format.h>

#include <cstdint>
#include <string>

#include "aperiodic/decide_checkpoint.hpp"
#include "base/error.hpp"
#include "base/hash.hpp"
#include "checkpoints/checkpoint.hpp"
#include "tilesets/tile_set.hpp"
#include "tilesets/tile_set_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tilekit;
  if (size == 0) return 0;
  static const std::vector<WangTile> tiles = resolve_tile_set("kari-14").wang_tiles();
  const std::string body(reinterpret_cast<const char*>(data) + 1, size - 1);
  const std::string file = data[0] & 1 ? body : seal_checkpoint("TILEKIT-DECIDE", kDecideCheckpointVersion, body);
  try {
    const DecideCheckpoint c = decode_decide_checkpoint(file, tiles, "fuzz.ckpt");
    fingerprint_difference(decide_fingerprint(tiles, DecideOptions{}), c.fingerprint);
    const DecideCheckpoint again = decode_decide_checkpoint(encode_decide_checkpoint(c), tiles, "again.ckpt");
    if (again.chains.size() != c.chains.size() || again.levels.size() != c.levels.size()) __builtin_trap();
    for (std::size_t i = 0; i < c.chains.size(); ++i)
      if (again.chains[i].k() != c.chains[i].k() ||
          again.chains[i].level(again.chains[i].k()).t.transitions != c.chains[i].level(c.chains[i].k()).t.transitions)
        __builtin_trap();
  } catch (const InputError&) {
  }
  return 0;
}
