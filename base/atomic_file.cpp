#include "base/atomic_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "base/error.hpp"

namespace tilekit {

namespace {

std::filesystem::path directory_of(const std::string& path) {
  const std::filesystem::path target(path);
  return target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
}

// `text` in a new temp file beside `path`, synced; returns its name. On failure nothing is left.
std::string write_temp(const std::string& path, std::string_view text) {
  const std::filesystem::path target(path);
  std::string tmpl = (directory_of(path) / ("." + target.filename().string() + ".tmpXXXXXX")).string();
  int fd = ::mkstemp(tmpl.data());
  if (fd < 0) throw InputError(fmt::format("{}: cannot write: {}", path, std::strerror(errno)));
  std::size_t done = 0;
  while (done < text.size()) {
    ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      int err = errno;
      ::close(fd);
      ::unlink(tmpl.c_str());
      throw InputError(fmt::format("{}: cannot write: {}", path, std::strerror(err)));
    }
    done += std::size_t(n);
  }
  ::fchmod(fd, 0644);
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    ::unlink(tmpl.c_str());
    throw InputError(fmt::format("{}: cannot sync: {}", path, std::strerror(errno)));
  }
  return tmpl;
}

void rename_into_place(const std::string& tmp, const std::string& path) {
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    int err = errno;
    ::unlink(tmp.c_str());
    throw InputError(fmt::format("{}: cannot rename into place: {}", path, std::strerror(err)));
  }
}

// The rename itself survives a power cut only once the directory entry is on disk.
void sync_directory(const std::string& path) {
  int dfd = ::open(directory_of(path).c_str(), O_RDONLY | O_DIRECTORY);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

}  // namespace

void write_file_atomic(const std::string& path, std::string_view text) {
  rename_into_place(write_temp(path, text), path);
  sync_directory(path);
}

void AtomicFileSet::stage(const std::string& path, std::string_view text) {
  staged_.emplace_back(write_temp(path, text), path);
}

void AtomicFileSet::commit() {
  // A rename fails on a target that is a folder: found before the first file is replaced.
  for (const auto& [tmp, path] : staged_) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
      throw InputError(fmt::format("{}: cannot write: it is a folder (nothing of this output was written)", path));
  }
  for (auto& [tmp, path] : staged_) {
    rename_into_place(tmp, path);
    tmp.clear();
  }
  for (const auto& [tmp, path] : staged_) sync_directory(path);
  staged_.clear();
}

AtomicFileSet::~AtomicFileSet() {
  for (const auto& [tmp, path] : staged_)
    if (!tmp.empty()) ::unlink(tmp.c_str());
}

}  // namespace tilekit
