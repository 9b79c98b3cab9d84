#include "base/temp_files.hpp"

#include <algorithm>
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
}  // namespace

void TempFiles::add(const std::string& path) {
  std::lock_guard lock(g_mu);
  registry().push_back(path);
}

void TempFiles::forget(const std::string& path) {
  std::lock_guard lock(g_mu);
  auto& r = registry();
  if (auto it = std::find(r.begin(), r.end(), path); it != r.end()) r.erase(it);
}

std::size_t TempFiles::remove_all() {
  std::lock_guard lock(g_mu);
  auto& r = registry();
  const std::size_t n = r.size();
  for (const std::string& p : r) {
    std::error_code ec;
    std::filesystem::remove_all(p, ec);
  }
  r.clear();
  return n;
}

std::size_t TempFiles::count() {
  std::lock_guard lock(g_mu);
  return registry().size();
}

}  // namespace tilekit
