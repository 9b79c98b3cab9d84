#include "points/text_format.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

#include "base/error.hpp"
#include "base/hash.hpp"

namespace tilekit::points::text {

bool LineReader::next(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  const std::size_t end = text_.find('\n', pos_);
  line = std::string_view(text_).substr(pos_, (end == std::string::npos ? text_.size() : end) - pos_);
  pos_ = end == std::string::npos ? text_.size() : end + 1;
  ++line_;
  return true;
}

std::string_view LineReader::expect(const char* what) {
  std::string_view line;
  if (!next(line)) fail(fmt::format("ends before {}", what));
  return line;
}

void LineReader::fail(const std::string& what) const {
  throw InputError(fmt::format("{}:{}: {}", source_, line_, what));
}

std::string_view LineReader::keyed(const char* key) {
  const std::string_view line = expect(key), k(key);
  if (line.size() <= k.size() + 1 || line.substr(0, k.size()) != k || line[k.size()] != ' ')
    fail(fmt::format("expected '{} ...', got '{}'", key, line.substr(0, 60)));
  return line.substr(k.size() + 1);
}

double LineReader::number(std::string_view s) {
  double v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(v))
    fail(fmt::format("'{}' is not a number", s.substr(0, 40)));
  return v;
}

std::uint64_t LineReader::count(std::string_view s, std::uint64_t max) {
  std::uint64_t v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size()) fail(fmt::format("'{}' is not a count", s.substr(0, 40)));
  if (v > max) fail(fmt::format("{} is more than {}", v, max));
  return v;
}

void LineReader::checksum() {
  const std::size_t body = pos_;
  const std::string_view sum = keyed("fnv1a64");
  if (sum != fmt::format("{:016x}", fnv1a64(std::string_view(text_).substr(0, body))))
    fail("checksum mismatch: the file is damaged or was edited");
}

std::string with_checksum(std::string body) {
  body += fmt::format("fnv1a64 {:016x}\n", fnv1a64(body));
  return body;
}

}  // namespace tilekit::points::text
