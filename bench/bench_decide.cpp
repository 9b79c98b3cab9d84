// Benchmarks of `aperiodic verify` by the transducer method (BENCHMARKS.md), one JSON
// line per case, the torus route measured in the same run as the baseline:
//   bench_decide collection [DIR] [LIMIT]  every set of DIR (default aperiodic/data) and the
//                                          published aperiodic sets: transducer route (median
//                                          of 3) against the torus route (max period 12), both
//                                          within LIMIT seconds (default 10)
//   bench_decide torus [LIMIT]             generated P x Q torus sets with decoys (aperiodic/
//                                          generate.hpp), up to 100 tiles, 3 seeds each
//   bench_decide time-limit                wall time of every route and of convert --verify
//                                          against --time-limit 1 and 3 on undecided sets
// Seconds are wall (steady clock); cpu_seconds are the process' user + system time.
#include <fmt/format.h>
#include <omp.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>
#include <tuple>
#include <vector>

#include "aperiodic/generate.hpp"
#include "aperiodic/requests.hpp"
#include "aperiodic/smallest.hpp"
#include "aperiodic/verify.hpp"
#include "tilesets/tile_set_io.hpp"

using namespace tilekit;

namespace {

double cpu_now() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct Timed {
  double wall = 0, cpu = 0;
};

// Median wall and CPU seconds of `runs` calls.
template <class F>
Timed median_of(int runs, F&& f) {
  std::vector<double> wall, cpu;
  for (int i = 0; i < runs; ++i) {
    const double c0 = cpu_now();
    const auto t0 = std::chrono::steady_clock::now();
    f();
    wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    cpu.push_back(cpu_now() - c0);
  }
  std::sort(wall.begin(), wall.end());
  std::sort(cpu.begin(), cpu.end());
  return {wall[wall.size() / 2], cpu[cpu.size() / 2]};
}

std::string period_json(const VerifyResult& r) {
  return r.period ? fmt::format("[{},{}]", r.period->first, r.period->second) : "null";
}

// One set: the transducer route (median of 3) and the torus route once, same time limit.
void compare_routes(const std::string& label, const TileSet& set, double limit, int max_period, int cores) {
  VerifyOptions t;
  t.route = "transducer";
  t.time_limit = limit;
  VerifyResult rt;
  Timed tt = median_of(3, [&] { rt = verify_tile_set(set, t); });
  VerifyOptions b;
  b.route = "torus";
  b.time_limit = limit;
  b.max_period = max_period;
  VerifyResult rb;
  Timed tb = median_of(1, [&] { rb = verify_tile_set(set, b); });
  fmt::print(
      R"({{"case":"decide","set":"{}","tiles":{},"verdict":"{}","k":{},"period":{},"witness_validated":{},"seconds":{:.4f},"cpu_seconds":{:.4f},"time_limit":{},"baseline":"torus route, max period {}","baseline_verdict":"{}","baseline_period":{},"baseline_seconds":{:.4f},"baseline_cpu_seconds":{:.4f},"cores":{}}})"
      "\n",
      label, set.size(), rt.verdict, rt.transducer ? rt.transducer->k : 0, period_json(rt), rt.witness_validated,
      tt.wall, tt.cpu, limit, max_period, rb.verdict, period_json(rb), tb.wall, tb.cpu, cores);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string what = argc > 1 ? argv[1] : "collection";
  const int cores = omp_get_num_procs();
  if (what == "collection") {
    const std::string dir = argc > 2 ? argv[2] : "aperiodic/data";
    const double limit = argc > 3 ? std::stod(argv[3]) : 10;
    std::vector<std::string> files;
    for (const auto& e : std::filesystem::directory_iterator(dir))
      if (e.path().extension() == ".tiles") files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
    for (const std::string& f : files)
      compare_routes(std::filesystem::path(f).stem().string(), read_tile_set_file(f), limit, 12, cores);
    for (const std::string& name : published_aperiodic_sets())
      compare_routes(name, resolve_tile_set(name), limit, 12, cores);
  } else if (what == "torus") {
    const double limit = argc > 2 ? std::stod(argv[2]) : 10;
    for (auto [p, q, d] : {std::tuple{7, 9, 20}, {7, 9, 37}, {5, 5, 75}, {3, 11, 67}, {10, 10, 0}, {4, 6, 76}})
      for (std::uint64_t seed = 1; seed <= 3; ++seed) {
        TileSet s = torus_with_decoys(p, q, d, seed);
        compare_routes(s.name() + fmt::format("/seed{}", seed), s, limit, std::max(p, q), cores);
      }
  } else if (what == "time-limit") {
    for (double limit : {1.0, 3.0}) {
      for (const char* route : {"transducer", "torus", "both", "auto"}) {
        VerifyOptions o;
        o.route = route;
        o.time_limit = limit;
        o.max_period = 64;
        VerifyResult r;
        Timed t = median_of(1, [&] { r = verify_tile_set(resolve_tile_set("jeandel-rao-11"), o); });
        fmt::print(
            R"({{"case":"time-limit","what":"verify --route {}","set":"jeandel-rao-11","time_limit":{},"verdict":"{}","seconds":{:.4f},"cpu_seconds":{:.4f},"over":{:.4f},"allowed_over":{},"cores":{}}})"
            "\n",
            route, limit, r.verdict, t.wall, t.cpu, t.wall - limit, std::max(1.0, 0.1 * limit), cores);
        std::fflush(stdout);
      }
      ConvertRequest c;
      c.set = "kari-14";
      c.spec.method = ConversionMethod::Vertical;
      c.verify = true;
      c.verify_options.time_limit = limit;
      c.verify_options.max_period = 64;
      ConvertReport rep;
      Timed t = median_of(1, [&] { rep = run_convert(c); });
      fmt::print(
          R"({{"case":"time-limit","what":"convert --verify","set":"vertical:kari-14","time_limit":{},"verdict":"{}","seconds":{:.4f},"cpu_seconds":{:.4f},"over":{:.4f},"allowed_over":{},"cores":{}}})"
          "\n",
          limit, rep.verify ? rep.verify->verdict : "", t.wall, t.cpu, t.wall - limit, std::max(1.0, 0.1 * limit),
          cores);
      std::fflush(stdout);
    }
  } else {
    fmt::print(stderr, "usage: bench_decide collection [DIR] [LIMIT] | torus [LIMIT] | time-limit\n");
    return 2;
  }
  return 0;
}
