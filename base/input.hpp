#pragma once
// Reading what users and other programs hand us: whole files with a size bound, and the text
// encoding policy. Every file parser reads through read_input_file(), so a directory, a FIFO
// or a 50 GB file is one clear InputError (exit 2) instead of a hang or std::bad_alloc.
//
// Encoding policy: Tilekit reads text as UTF-8 and refuses anything else at input, naming
// file:line and the byte (README, "Bad input"). Everything it stores or prints is therefore
// valid UTF-8, so JSON output never fails on a stray Latin-1 byte in a comment.
#include <cstdint>
#include <string>
#include <string_view>

namespace tilekit {

// The largest input file any parser reads whole: 1 GiB. The largest real inputs are database
// exports (the 203,520 two-colour Wang packings export to ~80 MB) and tile sets of the
// aperiodic tables (1.2 M tiles, ~20 MB); parsed JSON takes ~10x its text in memory.
inline constexpr std::uint64_t kMaxInputFileBytes = std::uint64_t(1) << 30;

// The whole regular file at `path`. Throws InputError "PATH: problem" naming `what`
// ("tile-set file", "checkpoint", ...) when it is missing, not a regular file, unreadable or
// larger than `max_bytes`.
std::string read_input_file(const std::string& path, std::string_view what,
                            std::uint64_t max_bytes = kMaxInputFileBytes);

// Byte offset of the first byte that is not part of well-formed UTF-8 (RFC 3629: no overlong
// forms, no surrogates, nothing above U+10FFFF), or npos when all of `text` is UTF-8.
std::size_t invalid_utf8_offset(std::string_view text);

// `text` with every byte that is not part of well-formed UTF-8 replaced by '?': for names
// derived from file paths, which are bytes, not text.
std::string utf8_or_question_marks(std::string_view text);

// Throws InputError "ORIGIN:LINE: not UTF-8 text (byte 0xE9 at column 12); ..." unless `text`
// is UTF-8. Lines count from `first_line`.
void require_utf8(std::string_view text, const std::string& origin, int first_line = 1);

}  // namespace tilekit
