// The shared flag parsers (base/parse.hpp): --size WxH, --shard I/N and bounded integers.
// Whatever parses is within its documented bounds.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "base/error.hpp"
#include "base/parse.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tilekit;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const ShardSpec s = parse_shard(text);
    if (s.count < 1 || s.count > kMaxShards || s.index < 0 || s.index >= s.count) std::abort();
  } catch (const InputError&) {
  }
  try {
    const Dimensions d = parse_dimensions(text, 65536, std::int64_t(1) << 24, "--size WxH");
    if (d.first < 1 || d.second < 1 || d.first > 65536 || d.second > 65536 || d.first * d.second > (1 << 24))
      std::abort();
  } catch (const InputError&) {
  }
  try {
    const std::int64_t v = parse_integer(text, -1000, 4096, "--threads");
    if (v < -1000 || v > 4096) std::abort();
  } catch (const InputError&) {
  }
  return 0;
}
