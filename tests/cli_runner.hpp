#pragma once
// Runs the built `tilekit` binary for end-to-end tests and captures exit code, stdout, stderr.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/build_paths.hpp"

namespace tilekit::test {

struct CliResult {
  int code = -1;
  std::string out, err;
  nlohmann::json json() const { return nlohmann::json::parse(out); }
};

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream b;
  b << in.rdbuf();
  return b.str();
}

// A JSON file the command wrote (a manifest, tiles.json, ...).
inline nlohmann::json read_json(const std::string& path) { return nlohmann::json::parse(slurp(path)); }

// A fresh temporary directory, removed when the object goes out of scope.
struct TempDir {
  std::filesystem::path path;
  TempDir() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "tilekit-test-XXXXXX").string();
    path = ::mkdtemp(tmpl.data());
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  std::string operator/(const std::string& name) const { return (path / name).string(); }
};

// `args` is appended to the binary path as-is (shell syntax; quote as needed); `prefix` goes before
// the binary (e.g. "env VAR=value ").
inline CliResult run_cli_prefixed(const std::string& prefix, const std::string& args) {
  TempDir d;
  std::string out = d / "out", err = d / "err";
  std::string cmd = prefix + std::string(TILEKIT_BINARY) + " " + args + " >" + out + " 2>" + err + " </dev/null";
  int status = std::system(cmd.c_str());
  CliResult r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

inline CliResult run_cli(const std::string& args) { return run_cli_prefixed("", args); }

// `s` in single quotes, for the shell (the paths of a TempDir hold no quote).
inline std::string q(const std::string& s) { return "'" + s + "'"; }

// The last write time of `path`; the earliest time there is when it does not exist.
inline std::filesystem::file_time_type mtime(const std::string& path) {
  std::error_code ec;
  auto t = std::filesystem::last_write_time(path, ec);
  return ec ? std::filesystem::file_time_type::min() : t;
}

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Starts `tilekit args...` in the background with stdin from /dev/null and stdout/stderr in
// files; returns its pid (-1 if it could not start). For tests that signal or kill a run.
inline pid_t spawn_tilekit(const std::vector<std::string>& args, const std::string& out, const std::string& err) {
  std::vector<std::string> all{TILEKIT_BINARY};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&fa, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  int rc = posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  return rc == 0 ? pid : -1;
}

// Waits until process `pid` has a handler for `sig` (its SigCgt mask in /proc/PID/status), at
// most `seconds`; false if it never had one. A signal sent before the program installs its
// handler ends the process instead of stopping it cleanly, and a sanitizer build can take longer
// than a fixed wait just to start.
inline bool wait_until_catching(pid_t pid, int sig, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  do {
    std::ifstream in("/proc/" + std::to_string(pid) + "/status");
    for (std::string line; std::getline(in, line);)
      if (line.rfind("SigCgt:", 0) == 0 && (std::stoull(line.substr(7), nullptr, 16) >> (sig - 1) & 1)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  } while (std::chrono::steady_clock::now() < end);
  return false;
}

// Waits for `pid`; its exit code, or 128 + the signal that ended it.
inline int wait_exit(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace tilekit::test
