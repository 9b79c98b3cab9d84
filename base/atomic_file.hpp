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

// A file written piece by piece (a point set too large to hold in memory) and then put in
// place whole: the pieces go to a temp file beside `path`; commit() syncs it and renames it over
// `path`. Destroyed before commit() (an error, a signal), it removes the temp file and `path`
// stays as it was. Every failure is an InputError naming the path and the system's reason.
class AtomicFileWriter {
 public:
  explicit AtomicFileWriter(std::string path);
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;
  ~AtomicFileWriter();
  void write(std::string_view bytes);
  void commit();
  // Syncs and closes the temp file and returns its name; its removal is then the caller's.
  std::string finish_temp();

 private:
  std::string path_, tmp_;
  int fd_ = -1;
};

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

// A folder of files that belong together (a texture tile set: tiles, sheet, labels, manifest),
// written into a temp folder `.NAME.tmpXXXXXX` beside `path` and put in place whole by
// commit(), which replaces an old folder at `path` entirely (no stale file of a larger old set
// stays). Destroyed before commit() (an error, a signal), it removes the temp folder and `path`
// stays as it was. Registered with TempFiles (base/temp_files.hpp) while it exists.
class AtomicFolder {
 public:
  explicit AtomicFolder(std::string path);
  AtomicFolder(const AtomicFolder&) = delete;
  AtomicFolder& operator=(const AtomicFolder&) = delete;
  ~AtomicFolder();
  const std::string& temp_path() const { return tmp_; }  // write the files here
  void commit();

 private:
  std::string path_, tmp_;
};

}  // namespace tilekit
