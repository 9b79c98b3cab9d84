#pragma once
// The envelope every Tilekit checkpoint file shares: a magic word naming the kind of file and a
// format version, the body's length and checksum, then the body:
//
//   MAGIC VERSION\n
//   bytes <n> fnv1a64 <16 hex>\n
//   <body: n bytes>
//
// Written atomically (temp file, fsync, rename: a kill at any moment leaves the old checkpoint or
// the new one); read through read_input_file() (base/input.hpp: a regular file, at most a bound),
// so a truncated, corrupt, oversized, foreign or future-version file is one InputError (exit 2)
// naming the file and the problem, never a hang or a wrong resume.
#include <cstdint>
#include <string>
#include <string_view>

namespace tilekit {

// The largest checkpoint any reader accepts (the largest real ones, an enumeration's every set
// and edge, are tens of megabytes).
inline constexpr std::uint64_t kMaxCheckpointBytes = std::uint64_t(1) << 30;

// `body` in the envelope.
std::string seal_checkpoint(std::string_view magic, int version, std::string_view body);

// The body of `text` after checking the magic, a version in [oldest, newest] (stored in
// *version_read), the length and the checksum; InputError "checkpoint ORIGIN: ..." otherwise.
std::string_view open_checkpoint(std::string_view text, std::string_view magic, int oldest, int newest,
                                 const std::string& origin, int* version_read = nullptr);

// write_file_atomic(path, seal_checkpoint(...)).
void write_checkpoint_envelope(const std::string& path, std::string_view magic, int version, std::string_view body);

// The body of the checkpoint file at `path` (read whole, at most `max_bytes`), checked as by
// open_checkpoint().
std::string read_checkpoint_envelope(const std::string& path, std::string_view magic, int oldest, int newest,
                                     int* version_read = nullptr, std::uint64_t max_bytes = kMaxCheckpointBytes);

}  // namespace tilekit
