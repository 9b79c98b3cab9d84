#include "base/input.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "base/error.hpp"

namespace tilekit {

// The file is opened first (O_NONBLOCK: opening a FIFO never waits for a writer) and checked
// on the open descriptor (fstat), so a FIFO, a device or a link to /dev/urandom swapped in
// after a check by name is still refused, and at most max_bytes + 1 bytes are ever read, so a
// file that grows while it is read is refused too.
std::string read_input_file(const std::string& path, std::string_view what, std::uint64_t max_bytes) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    if (errno == ENOENT || errno == ENOTDIR) throw InputError(fmt::format("{}: no such {}", path, what));
    throw InputError(fmt::format("{}: cannot open the {} ({})", path, what, std::strerror(errno)));
  }
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0)
    throw InputError(fmt::format("{}: cannot read the {} ({})", path, what, std::strerror(errno)));
  if (!S_ISREG(st.st_mode)) throw InputError(fmt::format("{}: not a regular file (expected a {})", path, what));
  const std::uint64_t size = std::uint64_t(st.st_size);
  if (size > max_bytes)
    throw InputError(fmt::format("{}: the {} is {} bytes, more than the limit of {} bytes", path, what, size, max_bytes));
  std::string text(std::size_t(size), '\0');
  std::size_t got = 0;
  for (;;) {
    if (got == text.size()) text.resize(got + 1);  // one byte more: does it end where it said?
    const ssize_t n = ::read(fd, text.data() + got, text.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputError(fmt::format("{}: cannot read the {} ({})", path, what, std::strerror(errno)));
    if (n == 0) break;
    got += std::size_t(n);
    if (got > size) throw InputError(fmt::format("{}: cannot read the {} (it changed while being read)", path, what));
  }
  if (got != size) throw InputError(fmt::format("{}: cannot read the {} (it changed while being read)", path, what));
  text.resize(got);
  return text;
}

std::size_t invalid_utf8_offset(std::string_view s) {
  const auto* p = reinterpret_cast<const unsigned char*>(s.data());
  const std::size_t n = s.size();
  std::size_t i = 0;
  while (i < n) {
    const unsigned char c = p[i];
    if (c < 0x80) {
      ++i;
      continue;
    }
    int len = 0;
    unsigned char lo = 0x80, hi = 0xBF;  // bounds of the second byte (RFC 3629, sec. 4)
    if (c >= 0xC2 && c <= 0xDF) len = 2;
    else if (c == 0xE0) len = 3, lo = 0xA0;
    else if (c == 0xED) len = 3, hi = 0x9F;  // no UTF-16 surrogates
    else if (c >= 0xE1 && c <= 0xEF) len = 3;
    else if (c == 0xF0) len = 4, lo = 0x90;
    else if (c == 0xF4) len = 4, hi = 0x8F;  // nothing above U+10FFFF
    else if (c >= 0xF1 && c <= 0xF3) len = 4;
    else return i;
    if (i + std::size_t(len) > n || p[i + 1] < lo || p[i + 1] > hi) return i;
    for (int k = 2; k < len; ++k)
      if ((p[i + std::size_t(k)] & 0xC0) != 0x80) return i;
    i += std::size_t(len);
  }
  return std::string_view::npos;
}

std::string utf8_or_question_marks(std::string_view text) {
  std::string out;
  for (;;) {
    const std::size_t bad = invalid_utf8_offset(text);
    if (bad == std::string_view::npos) return out.append(text);
    out.append(text.substr(0, bad)).push_back('?');
    text.remove_prefix(bad + 1);
  }
}

void require_utf8(std::string_view text, const std::string& origin, int first_line) {
  const std::size_t bad = invalid_utf8_offset(text);
  if (bad == std::string_view::npos) return;
  const std::string_view before = text.substr(0, bad);
  const auto line = first_line + std::count(before.begin(), before.end(), '\n');
  const auto eol = before.rfind('\n');
  const std::size_t column = bad - (eol == std::string_view::npos ? 0 : eol + 1) + 1;
  throw InputError(fmt::format("{}:{}: not UTF-8 text (byte {:#04x} at column {}); Tilekit reads UTF-8 only: "
                               "convert the file (e.g. `iconv -f latin1 -t utf-8`)",
                               origin, line, static_cast<unsigned char>(text[bad]), column));
}

}  // namespace tilekit
