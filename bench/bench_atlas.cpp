// Atlas benchmarks: `tilekit atlas lookup` wall time per available C, process start
// included, against `tilekit --version` (bare process start) in the same run; and the C=11
// corner construction in-process against validating the same packing.
// Usage: build/bench_atlas [path/to/tilekit] [runs]. One JSON line per case; times are medians.
#include <fmt/format.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fcntl.h>
#include <string>
#include <thread>
#include <vector>

#include "results/results_db.hpp"
#include "tilesets/constructions.hpp"
#include "tilesets/validator.hpp"

extern char** environ;

namespace {

using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct Timing {
  double wall_ms = -1, cpu_ms = -1;  // cpu: user + system time of the child
};

// Wall and CPU time of one process run (stdout/stderr to /dev/null), in milliseconds.
Timing run_once(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
  const auto t0 = Clock::now();
  pid_t pid = 0;
  if (posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), environ) != 0) return {};
  int status = 0;
  struct rusage ru {};
  wait4(pid, &status, 0, &ru);
  const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  posix_spawn_file_actions_destroy(&fa);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return {};
  auto tv = [](const timeval& t) { return t.tv_sec * 1e3 + t.tv_usec / 1e3; };
  return {ms, tv(ru.ru_utime) + tv(ru.ru_stime)};
}

Timing median_timing(const std::vector<std::string>& args, int runs) {
  std::vector<double> wall, cpu;
  for (int i = 0; i < runs; ++i) {
    Timing t = run_once(args);
    wall.push_back(t.wall_ms);
    cpu.push_back(t.cpu_ms);
  }
  return {median(wall), median(cpu)};
}

}  // namespace

int main(int argc, char** argv) {
  const std::string tk = argc > 1 ? argv[1] : "build/tilekit";
  const int runs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 11;
  const unsigned cores = std::thread::hardware_concurrency();
  const Timing start = median_timing({tk, "--version"}, runs);
  fmt::print("{{\"case\":\"process_start\",\"command\":\"tilekit --version\",\"median_ms\":{:.2f},\"cpu_ms\":{:.2f},"
             "\"runs\":{},\"cores\":{}}}\n",
             start.wall_ms, start.cpu_ms, runs, cores);
  for (const char* kind : {"corner", "wang"}) {
    for (std::uint32_t c : tilekit::constructible_colours(std::string(kind) == "wang" ? tilekit::TileKind::Wang
                                                                                     : tilekit::TileKind::Corner,
                                                          16)) {
      if (c < 2) continue;
      const Timing t =
          median_timing({tk, "atlas", "lookup", "--kind", kind, "--colors", std::to_string(c), "--no-db"}, runs);
      fmt::print("{{\"case\":\"atlas_lookup\",\"kind\":\"{}\",\"colors\":{},\"format\":\"json\",\"median_ms\":{:.2f},"
                 "\"cpu_ms\":{:.2f},\"baseline_ms\":{:.2f},\"ratio\":{:.2f},\"under_50ms\":{},\"runs\":{},"
                 "\"cores\":{}}}\n",
                 kind, c, t.wall_ms, t.cpu_ms, start.wall_ms, t.wall_ms / start.wall_ms,
                 t.wall_ms >= 0 && t.wall_ms < 50 ? "true" : "false", runs, cores);
    }
  }
  // The database-hit path: a stored C=6 corner packing (read-only open, independent validator).
  {
    char dir[] = "/tmp/bench-atlas-XXXXXX";
    if (!mkdtemp(dir)) return 1;
    const std::string db_path = std::string(dir) + "/r.sqlite";
    {
      tilekit::ResultsDb db(db_path);
      tilekit::SolutionRecord rec;
      rec.tiling = tilekit::construct_packing(tilekit::TileKind::Corner, 6)->tiling;
      rec.method = "construct";
      rec.validated = true;
      db.add_solution(rec);
    }
    const Timing t = median_timing({tk, "atlas", "lookup", "--kind", "corner", "--colors", "6", "--db", db_path}, runs);
    fmt::print("{{\"case\":\"atlas_lookup_db_hit\",\"kind\":\"corner\",\"colors\":6,\"median_ms\":{:.2f},\"cpu_ms\":{:.2f},"
               "\"baseline_ms\":{:.2f},\"ratio\":{:.2f},\"under_50ms\":{},\"runs\":{},\"cores\":{}}}\n",
               t.wall_ms, t.cpu_ms, start.wall_ms, t.wall_ms / start.wall_ms, t.wall_ms >= 0 && t.wall_ms < 50,
               runs, cores);
    std::filesystem::remove_all(dir);
  }
  // C=11 corner construction (14,641 tiles) in-process, against validating the result.
  std::vector<double> build, check;
  for (int i = 0; i < runs; ++i) {
    auto t0 = Clock::now();
    auto p = tilekit::construct_packing(tilekit::TileKind::Corner, 11);
    auto t1 = Clock::now();
    auto rep = tilekit::validate(p->tiling);
    auto t2 = Clock::now();
    if (!rep.packing) return 1;
    build.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    check.push_back(std::chrono::duration<double, std::milli>(t2 - t1).count());
  }
  const double b = median(build), v = median(check);
  fmt::print("{{\"case\":\"construct_corner_11\",\"tiles\":14641,\"median_ms\":{:.3f},\"baseline\":\"validate the same "
             "packing\",\"baseline_ms\":{:.3f},\"ratio\":{:.2f},\"under_100ms\":{},\"runs\":{},\"cores\":{}}}\n",
             b, v, b / v, b < 100 ? "true" : "false", runs, cores);
  return 0;
}
