#include "base/temp_files.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <vector>

namespace tilekit {

namespace {
// The registry is process-wide by nature (one job per process), like the signal flag.
std::mutex g_mu;
std::vector<std::string>& registry() {
  static std::vector<std::string>* paths = new std::vector<std::string>;  // lives to the very end
  return *paths;
}

// The same paths once more, in static storage that a signal handler may read: a slot is
// published (kReady) only once its path is complete, and cleared before it is reused.
constexpr int kSlots = 64;
constexpr std::size_t kPathMax = 4096;
enum : int { kFree = 0, kBusy = 1, kReady = 2 };
std::atomic<int> g_state[kSlots];
char g_path[kSlots][kPathMax];
static_assert(std::atomic<int>::is_always_lock_free);

void publish(const std::string& path) {
  if (path.size() >= kPathMax) return;  // beyond PATH_MAX: the unwinding owner still removes it
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (g_state[i].compare_exchange_strong(expected, kBusy)) {
      std::memcpy(g_path[i], path.c_str(), path.size() + 1);
      g_state[i].store(kReady);
      return;
    }
  }
}

void unpublish(const std::string& path) {
  for (int i = 0; i < kSlots; ++i) {
    int expected = kReady;
    if (std::strcmp(g_path[i], path.c_str()) == 0 && g_state[i].compare_exchange_strong(expected, kBusy)) {
      g_path[i][0] = '\0';
      g_state[i].store(kFree);
      return;
    }
  }
}

// rm -r with system calls only (async-signal-safe): the temp folders hold files and one level of
// subfolders (a tile set's labels/); folders deeper than four levels are left.
void remove_tree(int parent, const char* name, int depth) {
  if (::unlinkat(parent, name, 0) == 0 || depth > 4) return;
  const int fd = ::openat(parent, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return;
  alignas(8) char buf[4096];
  for (int pass = 0; pass < 2; ++pass) {  // a second pass for entries a file system skipped
    ::lseek(fd, 0, SEEK_SET);
    for (long n; (n = ::syscall(SYS_getdents64, fd, buf, sizeof buf)) > 0;)
      for (long off = 0; off < n;) {
        const auto* d = reinterpret_cast<const struct dirent64*>(buf + off);
        off += d->d_reclen;
        if (std::strcmp(d->d_name, ".") != 0 && std::strcmp(d->d_name, "..") != 0)
          remove_tree(fd, d->d_name, depth + 1);
      }
  }
  ::close(fd);
  ::unlinkat(parent, name, AT_REMOVEDIR);
}
}  // namespace

void TempFiles::add(const std::string& path) {
  std::lock_guard lock(g_mu);
  registry().push_back(path);
  publish(path);
}

void TempFiles::forget(const std::string& path) {
  std::lock_guard lock(g_mu);
  auto& r = registry();
  if (auto it = std::find(r.begin(), r.end(), path); it != r.end()) {
    r.erase(it);
    unpublish(path);
  }
}

std::size_t TempFiles::remove_all() {
  std::lock_guard lock(g_mu);
  auto& r = registry();
  const std::size_t n = r.size();
  for (const std::string& p : r) {
    std::error_code ec;
    std::filesystem::remove_all(p, ec);
    unpublish(p);
  }
  r.clear();
  return n;
}

std::size_t TempFiles::count() {
  std::lock_guard lock(g_mu);
  return registry().size();
}

void TempFiles::remove_all_in_signal_handler() {
  for (int i = 0; i < kSlots; ++i)
    if (g_state[i].load() == kReady) remove_tree(AT_FDCWD, g_path[i], 0);
}

}  // namespace tilekit
