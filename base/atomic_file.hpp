#pragma once
// Files that are either wholly written or not at all: a crash, a kill or a full disk never
// leaves a half-written result, checkpoint or picture behind.
#include <string>
#include <string_view>

namespace tilekit {

// Writes `text` to `path` atomically: a temp file in the same directory, fsync, rename, then
// fsync of the directory. Throws InputError naming the path and the system's reason; the
// temp file is removed on failure and an existing `path` stays as it was.
void write_file_atomic(const std::string& path, std::string_view text);

}  // namespace tilekit
