#pragma once
// The small parsers every command shares for flag values: bounded integers, sizes "WxH" and
// shards "I/N". Each is strict (decimal digits only, no sign unless the range allows one, no
// spaces, no trailing text, no overflow) and throws an InputError naming `what` and the value,
// so shard 4294967296/1 is refused instead of wrapping around to shard 0. `what` is what the
// caller calls the value: a field of a request between backquotes ("`shard`", base/error.hpp's
// RequestError, which the CLI words as its flag) or a flag.
#include <cstdint>
#include <string>
#include <string_view>

#include "base/run_control.hpp"  // ShardSpec

namespace tilekit {

// A decimal integer in [lo, hi]; `what` names it ("`seed`").
std::int64_t parse_integer(std::string_view text, std::int64_t lo, std::int64_t hi, std::string_view what);

// "AxB" (or "AXB") with 1 <= A, B <= max_side and A*B <= max_area; `what` names the value and
// its form ("`size` WxH").
struct Dimensions {
  std::int64_t first = 0, second = 0;
};
Dimensions parse_dimensions(std::string_view text, std::int64_t max_side, std::int64_t max_area, std::string_view what);

// "I/N" with 0 <= I < N <= kMaxShards.
ShardSpec parse_shard(std::string_view text, std::string_view what = "`shard`");
// "I/N", the text parse_shard() reads.
std::string shard_text(const ShardSpec& shard);

}  // namespace tilekit
