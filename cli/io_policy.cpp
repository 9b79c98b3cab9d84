#include "cli/io_policy.hpp"

#include <fmt/format.h>

#include <array>
#include <exception>
#include <filesystem>
#include <optional>
#include <string_view>

#include "results/results_db.hpp"
#include "texture/texture_atlas.hpp"

namespace tilekit::cli {

namespace {

struct Rule {
  std::string_view command;  // "*": every command with the flag
  std::string_view name;     // the flag, or a positional's name
  PathRole role;
};

// The first matching rule wins: a command's own rules come before the "*" ones. A positional
// (a name without "--") with no rule is an input; a flag with no rule is no file.
constexpr std::array kRules = {
    // Folders replaced whole (base/atomic_file.hpp AtomicFolder) or made with their scripts.
    Rule{"texture tiles", "--out", PathRole::OutputFolder},
    Rule{"texture terrain", "--out", PathRole::OutputFolder},
    Rule{"texture terrain", "--tiled", PathRole::OutputFolder},
    Rule{"tiled tileset", "--out", PathRole::OutputFolder},
    Rule{"tiled map", "--out", PathRole::OutputFolder},
    Rule{"cluster submit", "--run-dir", PathRole::OutputFolder},
    Rule{"cluster status", "--run-dir", PathRole::Input},
    Rule{"cluster split", "--run-dir", PathRole::Input},  // the run directory, its units written inside
    Rule{"fill", "--tiled", PathRole::OutputFolder},
    Rule{"texture atlas", "--out", PathRole::OutputInNewFolder},  // its folder is made, as texture tiles' is
    // The record a run writes, and the records others read.
    Rule{"aperiodic enumerate", "--record", PathRole::Output},
    Rule{"*", "--record", PathRole::Input},
    // Databases stored into (their folder must take SQLite's journal), and `db merge OUT IN...`.
    Rule{"pack", "--db", PathRole::WrittenDatabase},
    Rule{"db add", "--db", PathRole::WrittenDatabase},
    Rule{"aperiodic convert", "--db", PathRole::WrittenDatabase},
    Rule{"aperiodic verify", "--db", PathRole::WrittenDatabase},
    Rule{"aperiodic enumerate", "--db", PathRole::WrittenDatabase},
    Rule{"points tiles", "--db", PathRole::WrittenDatabase},
    Rule{"points recursive", "--db", PathRole::WrittenDatabase},
    Rule{"db merge", "OUT", PathRole::WrittenDatabase},
    Rule{"*", "--db", PathRole::Database},
    Rule{"*", "--portfolio-stats", PathRole::Database},  // read and updated, like a database
    // Files written whole.
    Rule{"*", "--out", PathRole::Output},
    Rule{"*", "--checkpoint", PathRole::Output},
    Rule{"*", "--plot", PathRole::Output},
    Rule{"*", "--pegs-out", PathRole::Output},
    Rule{"*", "--trace", PathRole::Output},
    Rule{"*", "--picture", PathRole::Output},
    Rule{"*", "--zoneplate", PathRole::Output},
    Rule{"points analyze", "--spectrum", PathRole::Output},
    Rule{"points spectrum", "--image", PathRole::Output},
    Rule{"points objects", "--texture", PathRole::Output},
    Rule{"fill", "--png", PathRole::Output},
    Rule{"fill", "--map-json", PathRole::Output},
    Rule{"fill", "--cnf", PathRole::Output},
    // Files read.
    Rule{"*", "--resume", PathRole::Input},
    Rule{"*", "--set", PathRole::Input},
    Rule{"*", "--map", PathRole::Input},
    Rule{"*", "--tiles", PathRole::Input},
    Rule{"*", "--atlas", PathRole::Input},
    Rule{"*", "--exemplar", PathRole::Input},
    Rule{"*", "--density-image", PathRole::Input},
    Rule{"*", "--labels", PathRole::Input},
    Rule{"*", "--cells", PathRole::Input},
    // NAME=FILE[:tileable]: the FILE (declared_paths)
    Rule{"texture terrain", "--terrain", PathRole::Input},
};

std::optional<PathRole> role_of(const std::string& cmd, const std::string& name) {
  for (const Rule& r : kRules)
    if ((r.command == cmd || r.command == "*") && r.name == name) return r.role;
  if (!name.empty() && name[0] != '-') return PathRole::Input;
  return std::nullopt;
}

// The files a refused run is to remove again (set before the command runs).
std::vector<std::string>& created_databases() {
  static std::vector<std::string> paths;
  return paths;
}

// True if the database at `path`, which this run found missing, holds nothing anyone stored:
// another process may have made the same new file meanwhile and stored into it, and that stays.
bool holds_nothing(const std::string& path) {
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  if (ec) return false;  // not there (or not a file): nothing to remove
  try {
    const ResultsDb db(
        path, DbOpenOptions{.create = false, .read_only = true, .integrity_check = false, .busy_timeout_ms = 100});
    const DbStats s = db.stats();
    return s.runs == 0 && s.solutions == 0 && s.tilesets == 0 && s.conversions == 0;
  } catch (const std::exception&) {
    // Not a database, or one that is busy: removed only if it is no more than its first pages
    // (the header a full disk cut short).
    return bytes <= 8192;
  }
}

}  // namespace

std::vector<IoPath> declared_paths(const CLI::App& leaf, const std::string& cmd) {
  std::vector<IoPath> paths;
  for (const CLI::Option* opt : leaf.get_options()) {
    if (opt->count() == 0 || opt->get_type_size() == 0) continue;  // not given, or a switch
    const std::string name = opt->get_lnames().empty() ? opt->get_single_name() : "--" + opt->get_lnames().front();
    const std::optional<PathRole> role = role_of(cmd, name);
    if (!role) continue;
    for (const std::string& value : opt->results()) {
      if (value.empty()) continue;
      if (name == "--terrain") {  // NAME=FILE[:tileable] (cli/cmd_texture_terrain.cpp)
        std::string file = value.substr(std::min(value.size(), value.find('=') + 1));
        if (file.size() > 9 && file.ends_with(":tileable")) file.resize(file.size() - 9);
        if (!file.empty()) paths.push_back({name, file, *role, ""});
        continue;
      }
      // A checkpoint is read whole on --resume and written again in its place.
      paths.push_back({name, value, *role, name == "--checkpoint" ? "--resume" : ""});
      if (name == "--atlas" || (cmd == "texture atlas" && name == "--out")) {
        // The atlas's files beside its PNG (texture/texture_atlas.hpp): each is read, or written.
        const std::string stem = atlas_stem(value);
        for (const char* ext : {".png", ".json", ".h", ".glsl", ".ktx2", ".vk.glsl", ".hlsl", ".wgsl"})
          if (stem + ext != value) paths.push_back({name, stem + ext, *role, {}});
        for (int k = 1; k <= 16; ++k) paths.push_back({name, fmt::format("{}.mip{}.png", stem, k), *role, {}});
      }
    }
  }
  return paths;
}

void install_io_policy(CLI::App& app) {
  app.parse_complete_callback([&app] {
    const CLI::App* leaf = &app;
    std::string cmd;
    while (!leaf->get_subcommands().empty()) {
      leaf = leaf->get_subcommands().front();
      cmd += (cmd.empty() ? "" : " ") + leaf->get_name();
    }
    const std::vector<IoPath> paths = declared_paths(*leaf, cmd);
    check_io_paths(paths);
    created_databases() = databases_to_create(paths);
  });
}

void undo_created_databases() {
  std::vector<std::string> empty;
  for (const std::string& p : created_databases())
    if (holds_nothing(p)) empty.push_back(p);
  remove_created_files(empty);
  created_databases().clear();
}

}  // namespace tilekit::cli
