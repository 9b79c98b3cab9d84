#include "base/checkpoint_envelope.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/hash.hpp"
#include "base/input.hpp"

namespace tilekit {

namespace {
constexpr std::string_view kMagic = "TILEKIT-CHECKPOINT";  // pack's, named as plain "checkpoint"
}  // namespace

std::string seal_checkpoint(std::string_view magic, int version, std::string_view body) {
  return fmt::format("{} {}\nbytes {} fnv1a64 {:016x}\n{}", magic, version, body.size(), fnv1a64(body), body);
}

std::string_view open_checkpoint(std::string_view text, std::string_view magic, int oldest, int newest,
                                 const std::string& origin, int* version_read) {
  auto bad = [&](const std::string& why) { return InputError(fmt::format("checkpoint {}: {}", origin, why)); };
  auto eol1 = text.find('\n');
  if (eol1 == std::string_view::npos || text.substr(0, magic.size()) != magic || text.size() <= magic.size() ||
      text[magic.size()] != ' ')
    throw bad("not a Tilekit checkpoint file" +
              (magic == kMagic ? std::string() : fmt::format(" of this kind ({})", magic)));
  std::string ver(text.substr(magic.size() + 1, eol1 - magic.size() - 1));
  int version = 0;
  auto [p, ec] = std::from_chars(ver.data(), ver.data() + ver.size(), version);
  if (ec != std::errc() || p != ver.data() + ver.size() || version < oldest || version > newest)
    throw bad(oldest == newest
                  ? fmt::format("format version {} is not supported (this build reads version {})", ver, newest)
                  : fmt::format("format version {} is not supported (this build reads versions {} to {})", ver, oldest,
                                newest));
  if (version_read) *version_read = version;
  auto eol2 = text.find('\n', eol1 + 1);
  if (eol2 == std::string_view::npos) throw bad("truncated (no header)");
  std::string header(text.substr(eol1 + 1, eol2 - eol1 - 1));
  // "bytes <decimal> fnv1a64 <16 hex digits>", exactly.
  std::uint64_t bytes = 0, sum = 0;
  auto field = [&](std::string_view& rest, std::string_view word, std::uint64_t& value, int base) {
    if (!rest.starts_with(word) || rest.size() <= word.size() || rest[word.size()] != ' ') return false;
    rest.remove_prefix(word.size() + 1);
    const auto space = std::min(rest.find(' '), rest.size());
    auto [end, ec] = std::from_chars(rest.data(), rest.data() + space, value, base);
    if (space == 0 || ec != std::errc() || end != rest.data() + space) return false;
    rest.remove_prefix(std::min(space + 1, rest.size()));
    return true;
  };
  std::string_view rest = header;
  if (!field(rest, "bytes", bytes, 10) || !field(rest, "fnv1a64", sum, 16) || !rest.empty() ||
      header.size() - header.rfind(' ') - 1 != 16)
    throw bad("corrupt header");
  std::string_view body = text.substr(eol2 + 1);
  if (body.size() < bytes) throw bad(fmt::format("truncated ({} of {} bytes)", body.size(), bytes));
  if (body.size() > bytes) throw bad(fmt::format("corrupt ({} bytes after the end)", body.size() - bytes));
  if (fnv1a64(body) != sum) throw bad("corrupt (checksum mismatch)");
  return body;
}

void write_checkpoint_envelope(const std::string& path, std::string_view magic, int version, std::string_view body) {
  write_file_atomic(path, seal_checkpoint(magic, version, body));
}

std::string read_checkpoint_envelope(const std::string& path, std::string_view magic, int oldest, int newest,
                                     int* version_read, std::uint64_t max_bytes) {
  const std::string text = read_input_file(path, "checkpoint", max_bytes);
  return std::string(open_checkpoint(text, magic, oldest, newest, path, version_read));
}

}  // namespace tilekit
