#include "base/atomic_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <pthread.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <utility>

#include "base/error.hpp"
#include "base/temp_files.hpp"

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
    TempFiles::forget(tmp);
    throw InputError(fmt::format("{}: cannot rename into place: {}", path, std::strerror(err)));
  }
  TempFiles::forget(tmp);
}

void remove_temp(const std::string& tmp) {
  ::unlink(tmp.c_str());
  TempFiles::forget(tmp);
}

// SIGTERM and SIGINT held back while a temp file is made and registered: a signal handler that
// removes the registered files (base/signals.hpp) never misses one that already exists.
class HoldStopSignals {
 public:
  HoldStopSignals() {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGTERM);
    sigaddset(&set, SIGINT);
    pthread_sigmask(SIG_BLOCK, &set, &old_);
  }
  ~HoldStopSignals() { pthread_sigmask(SIG_SETMASK, &old_, nullptr); }
  HoldStopSignals(const HoldStopSignals&) = delete;
  HoldStopSignals& operator=(const HoldStopSignals&) = delete;

 private:
  sigset_t old_;
};

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
  const HoldStopSignals hold;
  fd_ = ::mkstemp(tmp_.data());
  if (fd_ < 0) throw InputError(fmt::format("{}: cannot write: {}", path_, std::strerror(errno)));
  TempFiles::add(tmp_);
}

AtomicFileWriter::~AtomicFileWriter() {
  if (fd_ >= 0) ::close(fd_);
  if (!tmp_.empty()) remove_temp(tmp_);
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
    if (!tmp.empty()) remove_temp(tmp);
}

AtomicFolder::AtomicFolder(std::string path) : path_(std::move(path)) {
  std::error_code ec;
  // "out/", "./out" and "." name the folder itself: its temp sibling lives in its parent.
  path_ = std::filesystem::absolute(path_, ec).lexically_normal().string();
  while (path_.size() > 1 && path_.back() == '/') path_.pop_back();
  const std::filesystem::path target(path_);
  if (std::filesystem::exists(target, ec) && !std::filesystem::is_directory(target, ec))
    throw InputError(fmt::format("{}: cannot write: it exists and is not a folder", path_));
  std::filesystem::create_directories(directory_of(path_), ec);
  tmp_ = (directory_of(path_) / ("." + target.filename().string() + ".tmpXXXXXX")).string();
  const HoldStopSignals hold;
  if (!::mkdtemp(tmp_.data())) {
    const int err = errno;
    tmp_.clear();
    throw InputError(fmt::format("{}: cannot create the folder: {}", path_, std::strerror(err)));
  }
  TempFiles::add(tmp_);
}

AtomicFolder::~AtomicFolder() {
  if (tmp_.empty()) return;
  std::error_code ec;
  std::filesystem::remove_all(tmp_, ec);
  TempFiles::forget(tmp_);
}

void AtomicFolder::commit() {
  ::chmod(tmp_.c_str(), 0755);
  std::error_code ec;
  if (std::filesystem::is_directory(path_, ec)) {
    // Swap the old folder and the new one in one step; the old one, now at the temp name, goes.
    if (::renameat2(AT_FDCWD, tmp_.c_str(), AT_FDCWD, path_.c_str(), RENAME_EXCHANGE) != 0) {
      // No exchange on this file system: move the old one aside first.
      const std::string old = tmp_ + ".old";
      if (::rename(path_.c_str(), old.c_str()) != 0)
        throw InputError(fmt::format("{}: cannot replace the folder: {}", path_, std::strerror(errno)));
      if (::rename(tmp_.c_str(), path_.c_str()) != 0) {
        const int err = errno;
        ::rename(old.c_str(), path_.c_str());
        throw InputError(fmt::format("{}: cannot replace the folder: {}", path_, std::strerror(err)));
      }
      std::filesystem::remove_all(old, ec);
    } else {
      std::filesystem::remove_all(tmp_, ec);  // the old folder
    }
  } else if (::rename(tmp_.c_str(), path_.c_str()) != 0) {
    throw InputError(fmt::format("{}: cannot rename into place: {}", path_, std::strerror(errno)));
  }
  TempFiles::forget(tmp_);
  tmp_.clear();
  sync_directory(path_);
}

}  // namespace tilekit
