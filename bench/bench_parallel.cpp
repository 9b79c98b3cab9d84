// Parallel efficiency of the one engine: a count under an imposed group (or the plain
// search) on 1 and on 2 threads, alternating, several times. A count's node count does not
// depend on the thread count, so CPU seconds per run compare the same work: the goal is
// cpu(2 threads) <= 1.10 x cpu(1 thread). Also the wall-clock speed-up and the machine's load
// (loadavg before and after each run), since on a shared machine the wall time says little.
// One JSON line per case.
//
//   build/bench_bench_parallel                                     default case, 3 reps
//   build/bench_bench_parallel --case 'wang:3:t=0,3:pi=1,2,0' --reps 3 [--threads 2]
//   build/bench_bench_parallel --case 'corner:3:t=3,3:pi=1,2,0' --shard 0/4 --reps 3
//                                   one shard of a larger count (a count of >= 10 s on one thread)
//   (SPEC "plain" = no group)
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "base/error.hpp"
#include "bench/bench_common.hpp"
#include "solver/solve.hpp"

using namespace tilekit;
using tilekit::bench::cpu_seconds;
using tilekit::bench::loadavg;
using tilekit::bench::median;

namespace {

struct Run {
  double cpu = 0, wall = 0, load_before = 0, load_after = 0;
  std::uint64_t nodes = 0, solutions = 0;
  SearchStats stats;
};

Run run_count(const TilingProblem& p, const std::string& spec, int threads, int shard, int shards) {
  SearchOptions o;
  o.run.shard = {shard, shards};
  o.mode = SearchMode::Count;
  o.run.threads = threads;
  o.count_orbits = false;
  if (spec != "plain") o.impose = spec;
  Run r;
  r.load_before = loadavg();
  const double c0 = cpu_seconds();
  const auto t0 = std::chrono::steady_clock::now();
  SearchResult res = solve(p, o);
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.cpu = cpu_seconds() - c0;
  r.load_after = loadavg();
  if (!res.complete) throw std::runtime_error("the count did not complete");
  r.nodes = res.nodes;
  r.solutions = res.solutions;
  r.stats = res.stats;
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  std::string kcase = "wang:3:t=0,3:pih=1,2,0;t=3,0:piv=1,2,0";
  int reps = 3, threads = 2, shard = 0, shards = 1;
  try {
    for (int i = 1; i < argc; ++i) {
      std::string a = argv[i];
      auto next = [&]() -> std::string {
        if (i + 1 >= argc) throw InputError(a + " needs a value");
        return argv[++i];
      };
      if (a == "--case")
        kcase = next();
      else if (a == "--reps")
        reps = std::stoi(next());
      else if (a == "--threads")
        threads = std::stoi(next());
      else if (a == "--shard") {
        const std::string v = next();
        const auto slash = v.find('/');
        if (slash == std::string::npos) throw InputError("--shard I/N");
        shard = std::stoi(v.substr(0, slash));
        shards = std::stoi(v.substr(slash + 1));
      } else
        throw InputError("unknown argument " + a);
    }
    auto c1 = kcase.find(':'), c2 = kcase.find(':', c1 + 1);
    if (c1 == std::string::npos || c2 == std::string::npos) throw InputError("--case KIND:C:SPEC");
    const TileKind kind = kcase.substr(0, c1) == "wang" ? TileKind::Wang : TileKind::Corner;
    const auto colours = std::uint32_t(std::stoul(kcase.substr(c1 + 1, c2 - c1 - 1)));
    const std::string spec = kcase.substr(c2 + 1);
    const TilingProblem p = complete_packing_problem(kind, colours);
    std::vector<Run> one, many;
    for (int r = 0; r < reps; ++r) {  // alternating, so both see the same load on average
      one.push_back(run_count(p, spec, 1, shard, shards));
      many.push_back(run_count(p, spec, threads, shard, shards));
      if (many.back().nodes != one.back().nodes || many.back().solutions != one.back().solutions)
        throw std::runtime_error("the count or node count depends on the thread count");
    }
    auto field = [](const std::vector<Run>& v, double Run::*f) {
      std::vector<double> x;
      for (const Run& r : v) x.push_back(r.*f);
      return x;
    };
    const double cpu1 = median(field(one, &Run::cpu)), cpuN = median(field(many, &Run::cpu));
    const double wall1 = median(field(one, &Run::wall)), wallN = median(field(many, &Run::wall));
    std::vector<double> loads = field(one, &Run::load_before);
    for (const Run& r : many) loads.push_back(r.load_after);
    nlohmann::json j = {{"bench", "parallel"},
                        {"case", kcase},
                        {"cores", std::thread::hardware_concurrency()},
                        {"threads", threads},
                        {"shard", std::to_string(shard) + "/" + std::to_string(shards)},
                        {"reps", reps},
                        {"nodes", one.front().nodes},
                        {"solutions", one.front().solutions},
                        {"stats", one.front().stats},  // the engine's counters (a count: the same every run)
                        {"cpu_seconds_1", field(one, &Run::cpu)},
                        {"cpu_seconds_n", field(many, &Run::cpu)},
                        {"wall_seconds_1", field(one, &Run::wall)},
                        {"wall_seconds_n", field(many, &Run::wall)},
                        {"median_cpu_1", cpu1},
                        {"median_cpu_n", cpuN},
                        {"cpu_ratio", cpuN / cpu1},
                        {"wall_speedup", wall1 / wallN},
                        {"loadavg_min", *std::min_element(loads.begin(), loads.end())},
                        {"loadavg_max", *std::max_element(loads.begin(), loads.end())}};
    std::cout << j.dump() << std::endl;
  } catch (const std::exception& e) {
    std::cerr << "bench_parallel: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
