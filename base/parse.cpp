#include "base/parse.hpp"

#include <fmt/format.h>

#include <charconv>

#include "base/error.hpp"

namespace tilekit {

namespace {

// Strict decimal: an optional '-' (never '+'), then digits only, all of `text`.
bool strict_integer(std::string_view text, std::int64_t& v) {
  if (text.empty()) return false;
  const char* first = text.data();
  const char* last = first + text.size();
  if (*first != '-' && (*first < '0' || *first > '9')) return false;
  auto [p, ec] = std::from_chars(first, last, v);
  return ec == std::errc() && p == last;
}

// The shown value, shortened so that a 30 KB flag does not make a 30 KB message.
std::string shown(std::string_view text) {
  return text.size() > 40 ? fmt::format("{}...", text.substr(0, 37)) : std::string(text);
}

}  // namespace

std::int64_t parse_integer(std::string_view text, std::int64_t lo, std::int64_t hi, std::string_view what) {
  std::int64_t v = 0;
  if (!strict_integer(text, v) || v < lo || v > hi)
    throw_input_error(what,
                      fmt::format("{} must be an integer between {} and {}, got '{}'", what, lo, hi, shown(text)));
  return v;
}

Dimensions parse_dimensions(std::string_view text, std::int64_t max_side, std::int64_t max_area, std::string_view what) {
  const auto x = text.find_first_of("xX");
  Dimensions d;
  if (x == std::string_view::npos || !strict_integer(text.substr(0, x), d.first) ||
      !strict_integer(text.substr(x + 1), d.second))
    throw_input_error(what,
                      fmt::format("{}: expected two positive integers such as 16x16, got '{}'", what, shown(text)));
  if (d.first < 1 || d.second < 1 || d.first > max_side || d.second > max_side)
    throw_input_error(what,
                      fmt::format("{}: each side must be between 1 and {}, got '{}'", what, max_side, shown(text)));
  if (d.first * d.second > max_area)
    throw_input_error(what,
                      fmt::format("{}: {} cells is more than the limit of {}", what, d.first * d.second, max_area));
  return d;
}

ShardSpec parse_shard(std::string_view text, std::string_view what) {
  const auto slash = text.find('/');
  std::int64_t i = 0, n = 0;
  if (slash == std::string_view::npos || !strict_integer(text.substr(0, slash), i) ||
      !strict_integer(text.substr(slash + 1), n) || n < 1 || n > kMaxShards || i < 0 || i >= n)
    throw_input_error(what,
                      fmt::format("{} must be I/N with 0 <= I < N <= {}, got '{}'", what, kMaxShards, shown(text)));
  return {int(i), int(n)};
}

std::string shard_text(const ShardSpec& shard) {
  return fmt::format("{}/{}", shard.index, shard.count);
}

}  // namespace tilekit
