#include "base/resources.hpp"

#include <fmt/format.h>
#include <unistd.h>
#if defined(__linux__)
#include <sys/mman.h>
#endif

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "base/error.hpp"

namespace tilekit {

namespace {

// "12G", "512M", "1000000": bytes; 0 when malformed.
std::uint64_t parse_bytes(std::string_view text) {
  std::uint64_t v = 0;
  std::size_t i = 0;
  for (; i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])); ++i) {
    if (v > (UINT64_MAX - 9) / 10) return 0;
    v = v * 10 + std::uint64_t(text[i] - '0');
  }
  if (i == 0) return 0;
  int shift = 0;
  if (i < text.size()) {
    const char unit = char(std::toupper(static_cast<unsigned char>(text[i])));
    shift = unit == 'K' ? 10 : unit == 'M' ? 20 : unit == 'G' ? 30 : unit == 'T' ? 40 : -1;
    if (shift < 0 || i + 1 != text.size()) return 0;
  }
  if (shift && v > (UINT64_MAX >> shift)) return 0;
  return v << shift;
}

// What this process may use at most: physical memory, or the cgroup v2 limit when lower.
std::uint64_t available_memory() {
  const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGE_SIZE);
  std::uint64_t bytes = pages > 0 && size > 0 ? std::uint64_t(pages) * std::uint64_t(size) : std::uint64_t(4) << 30;
  std::ifstream cgroup("/sys/fs/cgroup/memory.max");
  std::string max;
  if (cgroup >> max && max != "max")
    if (const std::uint64_t limit = parse_bytes(max); limit > 0) bytes = std::min(bytes, limit);
  return bytes;
}

std::string gib(double bytes) { return fmt::format("{:.3g} GiB", bytes / double(1ull << 30)); }

}  // namespace

std::uint64_t memory_limit() {
  if (const char* env = std::getenv("TILEKIT_MEMORY"); env && *env) {
    const std::uint64_t v = parse_bytes(env);
    if (v == 0) throw InputError(fmt::format("TILEKIT_MEMORY={}: expected bytes, e.g. 8G, 512M or 1000000", env));
    return v;
  }
  return available_memory() / 2;
}

void require_memory(double bytes, std::string_view what) {
  const std::uint64_t limit = memory_limit();
  if (!(bytes <= double(limit)))
    throw InputError(fmt::format("{} needs about {} of memory, more than the limit of {} ({}; set TILEKIT_MEMORY, "
                                 "e.g. TILEKIT_MEMORY={}G, to raise it)",
                                 what, gib(bytes), gib(double(limit)),
                                 std::getenv("TILEKIT_MEMORY") ? "TILEKIT_MEMORY" : "half of this machine's memory",
                                 std::uint64_t(bytes / double(1ull << 30)) + 1));
}

void require_disk(const std::string& path, double bytes, std::string_view what) {
  const std::filesystem::path target(path);
  const std::filesystem::path dir = target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  const std::filesystem::space_info space = std::filesystem::space(dir, ec);
  if (ec) return;
  if (!(bytes <= double(space.available)))
    throw InputError(fmt::format("{} needs about {} on disk, more than the {} free in {}", what, gib(bytes),
                                 gib(double(space.available)), dir.string()));
}

void advise_huge_pages(void* p, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::size_t kMin = std::size_t(8) << 20;
  if (!p || bytes < kMin) return;
  const std::uintptr_t page = std::uintptr_t(sysconf(_SC_PAGESIZE));
  const std::uintptr_t begin = (std::uintptr_t(p) + page - 1) / page * page;
  const std::uintptr_t end = (std::uintptr_t(p) + bytes) / page * page;
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);  // advice only
#else
  (void)p, (void)bytes;
#endif
}

}  // namespace tilekit
