#pragma once
// Files that are either wholly written or not at all: a crash, a kill or a full disk never
// leaves a half-written result, checkpoint or picture behind.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tilekit {

// Writes `text` to `path` atomically: a temp file in the same directory, fsync, rename, then
// fsync of the directory. Throws InputError naming the path and the system's reason; the
// temp file is removed on failure and an existing `path` stays as it was.
void write_file_atomic(const std::string& path, std::string_view text);

// Files that belong together (an atlas, its mip levels, manifest, header and shader): each is
// written and synced to a temp file beside its target as it is staged, and only commit()
// renames them into place, in the order staged (stage the file that marks the set complete
// last). A set destroyed before commit() (an error, a refused input) removes its temp files
// and leaves every target as it was.
class AtomicFileSet {
 public:
  AtomicFileSet() = default;
  AtomicFileSet(const AtomicFileSet&) = delete;
  AtomicFileSet& operator=(const AtomicFileSet&) = delete;
  ~AtomicFileSet();
  void stage(const std::string& path, std::string_view text);  // InputError naming the path
  void commit();

 private:
  std::vector<std::pair<std::string, std::string>> staged_;  // (temp file, target)
};

}  // namespace tilekit
