#pragma once
// Internal to points/: reading the line-based text files of points/ (point tile sets, recursive
// tile sets): "key value" lines, numbers, and a closing "fnv1a64 HEX" checksum line over every
// byte before it. Every problem is an InputError naming the source and line.
#include <cstdint>
#include <string>
#include <string_view>

namespace tilekit::points::text {

class LineReader {
 public:
  LineReader(const std::string& text, std::string source) : text_(text), source_(std::move(source)) {}
  bool next(std::string_view& line);
  std::string_view expect(const char* what);  // the next line, failing at the end
  [[noreturn]] void fail(const std::string& what) const;
  std::size_t offset() const { return pos_; }  // bytes consumed so far

  // "key value" -> value, failing unless the next line starts with `key`.
  std::string_view keyed(const char* key);
  double number(std::string_view s);
  // A decimal count up to `max` (so that a narrower field never wraps a larger value around).
  std::uint64_t count(std::string_view s, std::uint64_t max = UINT64_MAX);
  // Checks that the next line is "fnv1a64 HEX" of every byte before it.
  void checksum();

 private:
  const std::string& text_;
  std::string source_;
  std::size_t pos_ = 0;
  int line_ = 0;
};

// Appends "fnv1a64 HEX\n" of `body` to it.
std::string with_checksum(std::string body);

}  // namespace tilekit::points::text
