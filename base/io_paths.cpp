#include "base/io_paths.hpp"

#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <optional>

#include "base/error.hpp"

namespace tilekit {

namespace fs = std::filesystem;

namespace {

std::optional<struct stat> stat_of(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return std::nullopt;
  return st;
}

// The absolute path with every existing part resolved (links, "..", "."): what a path that does
// not exist yet will be once written.
fs::path resolved(const std::string& path) {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::absolute(path, ec), ec);
  if (ec) p = fs::absolute(path, ec).lexically_normal();
  return p;
}

fs::path folder_of(const std::string& path) {
  const fs::path p(path);
  return p.has_parent_path() ? p.parent_path() : fs::path(".");
}

bool is_output(PathRole r) {
  return r == PathRole::Output || r == PathRole::OutputFolder || r == PathRole::OutputInNewFolder ||
         r == PathRole::WrittenDatabase;
}

// "it is missing" and the like when `dir` cannot take a new file, else empty.
std::string unwritable_folder(const fs::path& dir) {
  const auto st = stat_of(dir.string());
  if (!st) return fmt::format("its folder {} does not exist", dir.string());
  if (!S_ISDIR(st->st_mode)) return fmt::format("{} is not a folder", dir.string());
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    return fmt::format("its folder {} is not writable ({})", dir.string(), std::strerror(errno));
  return {};
}

std::string why_unwritable(const IoPath& p) {
  if (p.role == PathRole::OutputFolder || p.role == PathRole::OutputInNewFolder) {
    // A folder output (or a file's folder) is made with its missing parents: the nearest
    // existing one must take it.
    fs::path dir = folder_of(resolved(p.path).string());
    std::error_code ec;
    while (!fs::exists(dir, ec) && dir.has_parent_path() && dir != dir.parent_path()) dir = dir.parent_path();
    if (const auto st = stat_of(p.path); st && (p.role == PathRole::OutputFolder) != S_ISDIR(st->st_mode))
      return p.role == PathRole::OutputFolder ? "it exists and is not a folder" : "it is a folder";
    return unwritable_folder(dir);
  }
  if (const auto st = stat_of(p.path); st && S_ISDIR(st->st_mode)) return "it is a folder";
  return unwritable_folder(folder_of(p.path));
}

// What names a file: its device and inode where it exists, else where it will be.
struct Identity {
  bool exists = false;
  dev_t dev{};
  ino_t ino{};
  fs::path where;
};

Identity identity_of(const std::string& path) {
  if (const auto st = stat_of(path)) return {true, st->st_dev, st->st_ino, {}};
  return {false, {}, {}, resolved(path)};
}

bool same_identity(const Identity& a, const Identity& b) {
  if (a.exists && b.exists) return a.dev == b.dev && a.ino == b.ino;
  return !a.exists && !b.exists && a.where == b.where;
}

}  // namespace

bool same_file(const std::string& a, const std::string& b) {
  return same_identity(identity_of(a), identity_of(b));
}

bool inside_folder(const std::string& path, const std::string& folder) {
  const fs::path p = resolved(path), f = resolved(folder);
  auto pi = p.begin();
  for (auto fi = f.begin(); fi != f.end(); ++fi, ++pi) {
    if (fi->empty()) continue;  // a trailing separator
    if (pi == p.end() || *pi != *fi) return false;
  }
  return true;
}

void check_io_paths(const std::vector<IoPath>& given) {
  std::vector<IoPath> paths = given;
  for (const IoPath& p : given) {
    std::error_code ec;
    if (p.role != PathRole::Input || !fs::is_directory(p.path, ec)) continue;
    for (const auto& e : fs::directory_iterator(p.path, ec))
      if (e.is_regular_file(ec)) paths.push_back({p.what + " " + p.path, e.path().string(), PathRole::Input, {}});
  }
  std::vector<Identity> ids;  // each path stated once (a folder of tiles may hold thousands)
  for (const IoPath& p : paths) ids.push_back(p.path.empty() ? Identity{} : identity_of(p.path));
  for (std::size_t i = 0; i < paths.size(); ++i) {
    const IoPath& out = paths[i];
    if (!is_output(out.role) || out.path.empty()) continue;
    for (std::size_t k = 0; k < paths.size(); ++k) {
      const IoPath& other = paths[k];
      if (k == i || other.path.empty() || (!out.may_replace.empty() && other.what == out.may_replace)) continue;
      // An output against an input or an earlier output (each pair once).
      if (is_output(other.role) && k > i) continue;
      if (same_identity(ids[i], ids[k])) {
        if (is_output(other.role))
          throw InputError(fmt::format("{} and {} name the same file ({}): refused, nothing was written", other.what,
                                       out.what, out.path));
        throw InputError(
            fmt::format("{} names the same file as {} ({}): writing it would destroy that input; "
                        "refused, nothing was written",
                        out.what, other.what, other.path));
      }
      if (out.role == PathRole::OutputFolder && !is_output(other.role) && ids[k].exists &&
          inside_folder(other.path, out.path))
        throw InputError(
            fmt::format("{} {} holds {} ({}), which replacing the folder would delete; refused, "
                        "nothing was written",
                        out.what, out.path, other.what, other.path));
    }
    if (const std::string why = why_unwritable(out); !why.empty())
      throw InputError(fmt::format("{} {}: cannot write: {}; refused before any work, nothing was changed", out.what,
                                   out.path, why));
  }
}

std::vector<std::string> databases_to_create(const std::vector<IoPath>& paths) {
  std::vector<std::string> out;
  for (const IoPath& p : paths) {
    struct stat st {};
    if (p.role == PathRole::WrittenDatabase && !p.path.empty() && ::lstat(p.path.c_str(), &st) != 0 && errno == ENOENT)
      out.push_back(p.path);
  }
  return out;
}

void remove_created_files(const std::vector<std::string>& paths) {
  for (const std::string& p : paths)
    for (const char* side : {"", "-journal", "-wal", "-shm"}) ::unlink((p + side).c_str());
}

}  // namespace tilekit
