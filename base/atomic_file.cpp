#include "base/atomic_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <utility>

#include "base/error.hpp"

namespace tilekit {

namespace {

std::filesystem::path directory_of(const std::string& path) {
  const std::filesystem::path target(path);
  return target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
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

AtomicFileWriter::AtomicFileWriter(std::string path) : path_(std::move(path)) {
  const std::filesystem::path target(path_);
  tmp_ = (directory_of(path_) / ("." + target.filename().string() + ".tmpXXXXXX")).string();
  fd_ = ::mkstemp(tmp_.data());
  if (fd_ < 0) throw InputError(fmt::format("{}: cannot write: {}", path_, std::strerror(errno)));
}

AtomicFileWriter::~AtomicFileWriter() {
  if (fd_ >= 0) ::close(fd_);
  if (!tmp_.empty()) ::unlink(tmp_.c_str());
}

void AtomicFileWriter::write(std::string_view bytes) {
  if (fd_ < 0) throw InputError(fmt::format("{}: cannot write: the file is already finished", path_));
  std::size_t done = 0;
  while (done < bytes.size()) {
    ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw InputError(fmt::format("{}: cannot write: {}", path_, std::strerror(errno)));
    }
    done += std::size_t(n);
  }
}

std::string AtomicFileWriter::finish_temp() {
  if (fd_ < 0) throw InputError(fmt::format("{}: cannot write: the file is already finished", path_));
  ::fchmod(fd_, 0644);
  const int fd = fd_;
  fd_ = -1;
  int err = ::fsync(fd) != 0 ? errno : 0;
  if (::close(fd) != 0 && err == 0) err = errno;
  if (err != 0) throw InputError(fmt::format("{}: cannot sync: {}", path_, std::strerror(err)));  // the destructor unlinks
  return std::exchange(tmp_, std::string());
}

void AtomicFileWriter::commit() {
  rename_into_place(finish_temp(), path_);
  sync_directory(path_);
}

void write_file_atomic(const std::string& path, std::string_view text) {
  AtomicFileWriter out(path);
  out.write(text);
  out.commit();
}

void AtomicFileSet::stage(const std::string& path, std::string_view text) {
  AtomicFileWriter out(path);
  out.write(text);
  staged_.emplace_back(out.finish_temp(), path);
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
