// Search under imposed automorphisms: time to the first packing per (kind, C,
// group), median over seeds, against the plain search (trivial group, same engine, same time
// limit) run in the same process. CPU seconds (getrusage, the whole process) next to wall
// seconds. One JSON line per case on stdout.
//
//   build/bench_bench_impose                     default cases (C=3..5, corner and Wang)
//   build/bench_bench_impose --case corner:5:t=0,5:pi=1,2,3,4,0 --reps 5 --threads 1 --time-limit 60
//   build/bench_bench_impose --no-baseline ...   skip the plain search
//   build/bench_bench_impose --portfolio corner:6 --threads 1 --time-limit 3000 [--stats F]
//                                            the portfolio, one JSON line with every candidate's
//                                            slices, nodes and seconds
//   --sat (CNF + cadical instead of the DFS), --patterns MASK (bit k: size-k pattern counts,
//   default 4), --static (scan order, no MCF), --luby-unit N (nodes per Luby unit)
#include <fmt/format.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "base/error.hpp"
#include "bench/bench_common.hpp"
#include "solver/portfolio.hpp"
#include "solver/solve.hpp"

using namespace tilekit;
using tilekit::bench::cpu_seconds;
using tilekit::bench::median;

namespace {

struct Case {
  TileKind kind;
  std::uint32_t colours;
  std::string spec;
};

Case parse_case(const std::string& s) {
  auto a = s.find(':');
  auto b = s.find(':', a + 1);
  if (a == std::string::npos || b == std::string::npos) throw InputError("--case KIND:C:SPEC");
  Case c;
  std::string kind = s.substr(0, a);
  if (kind != "corner" && kind != "wang") throw InputError("--case: kind is corner or wang");
  c.kind = kind == "corner" ? TileKind::Corner : TileKind::Wang;
  c.colours = std::uint32_t(std::stoul(s.substr(a + 1, b - a - 1)));
  c.spec = s.substr(b + 1);
  return c;
}

// The engine knobs a case runs with (SearchOptions fields).
struct Knobs {
  unsigned patterns = 4;
  bool static_order = false, sat = false;
  std::uint64_t luby_unit = 0;
};

SearchResult run_one(const Case& c, const std::string& spec, int threads, double limit, std::uint64_t seed,
                     const Knobs& k, double& cpu) {
  SearchOptions o;
  o.run.threads = threads;
  o.run.seed = seed;
  o.run.time_limit = limit;
  o.impose = spec;
  o.impose_patterns = k.patterns;
  o.ordering = k.static_order ? "static" : "auto";
  o.formulation = k.sat ? Formulation::Sat : Formulation::Auto;
  o.restart_base = k.luby_unit;
  const double cpu0 = cpu_seconds();
  SearchResult r = solve(complete_packing_problem(c.kind, c.colours), o);
  cpu = cpu_seconds() - cpu0;
  return r;
}

nlohmann::json run_case(const Case& c, const std::string& spec, int reps, int threads, double limit,
                        std::uint64_t seed0, const Knobs& k) {
  std::vector<double> secs, cpus, nodes;
  int found = 0;
  SearchStats stats;  // every run, summed
  for (int r = 0; r < reps; ++r) {
    double cpu = 0;
    const auto t0 = std::chrono::steady_clock::now();
    SearchResult res = run_one(c, spec, threads, limit, seed0 + std::uint64_t(r), k, cpu);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    secs.push_back(wall);
    cpus.push_back(cpu);
    nodes.push_back(double(res.nodes));
    stats += res.stats;
    found += res.solutions ? 1 : 0;
  }
  return {{"spec", spec},
          {"found", found},
          {"runs", reps},
          {"median_seconds", median(secs)},
          {"median_cpu_seconds", median(cpus)},
          {"cpu_seconds", cpus},
          {"median_nodes", median(nodes)},
          {"nodes", nodes},
          {"time_limit", limit},
          {"stats", stats}};
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<Case> cases;
  int reps = 5, threads = 1;
  double limit = 30;
  std::uint64_t seed = 1;
  bool baseline = true;
  std::vector<std::string> portfolios;
  std::string stats = "-";
  Knobs ctl;
  try {
    for (int i = 1; i < argc; ++i) {
      std::string a = argv[i];
      auto next = [&]() -> std::string {
        if (i + 1 >= argc) throw InputError(a + " needs a value");
        return argv[++i];
      };
      if (a == "--case")
        cases.push_back(parse_case(next()));
      else if (a == "--reps")
        reps = std::stoi(next());
      else if (a == "--threads")
        threads = std::stoi(next());
      else if (a == "--time-limit")
        limit = std::stod(next());
      else if (a == "--seed")
        seed = std::stoull(next());
      else if (a == "--no-baseline")
        baseline = false;
      else if (a == "--portfolio")
        portfolios.push_back(next());
      else if (a == "--stats")
        stats = next();
      else if (a == "--patterns")
        ctl.patterns = unsigned(std::stoi(next()));
      else if (a == "--static")
        ctl.static_order = true;
      else if (a == "--sat")
        ctl.sat = true;
      else if (a == "--luby-unit")
        ctl.luby_unit = std::stoull(next());
      else
        throw InputError("unknown argument " + a);
    }
    for (const auto& pf : portfolios) {
      Case c = parse_case(pf + ":");
      for (int r = 0; r < reps; ++r) {
        SearchOptions o;
        o.run.threads = threads;
        o.run.seed = seed + std::uint64_t(r);
        o.run.time_limit = limit;
        PortfolioOptions po;
        po.stats_path = stats;
        const double cpu0 = cpu_seconds();
        auto res = run_portfolio(complete_packing_problem(c.kind, c.colours), o, po);
        const double cpu = cpu_seconds() - cpu0;
        std::cout << nlohmann::json({{"bench", "impose-portfolio"},
                                     {"kind", std::string(kind_name(c.kind))},
                                     {"colors", c.colours},
                                     {"threads", threads},
                                     {"cores", std::thread::hardware_concurrency()},
                                     {"seed", o.run.seed},
                                     {"found", res.found},
                                     {"group", res.winner},
                                     {"seconds", res.seconds},
                                     {"cpu_seconds", cpu},
                                     {"nodes", res.nodes},
                                     {"time_limit", limit},
                                     {"runs", res.runs}})
                         .dump()
                  << std::endl;
      }
    }
    if (!portfolios.empty() && cases.empty()) return 0;
    if (cases.empty()) {
      cases = {{TileKind::Corner, 3, "t=0,3:pi=1,2,0"},     {TileKind::Wang, 3, "t=0,3:pi=1,2,0"},
               {TileKind::Corner, 4, "t=0,4:pi=1,2,3,0"},   {TileKind::Wang, 4, "t=0,8:pi=1,0,3,2"},
               {TileKind::Corner, 5, "t=0,5:pi=1,2,3,4,0"}, {TileKind::Wang, 5, "t=0,5:pi=1,2,3,4,0"}};
    }
    for (const auto& c : cases) {
      nlohmann::json line = {{"bench", "impose"},
                             {"kind", std::string(kind_name(c.kind))},
                             {"colors", c.colours},
                             {"threads", threads},
                             {"cores", std::thread::hardware_concurrency()}};
      line["imposed"] = run_case(c, c.spec, reps, threads, limit, seed, ctl);
      if (baseline) line["baseline_plain"] = run_case(c, "t=0,0", std::max(1, reps / 2), threads, limit, seed, ctl);
      std::cout << line.dump() << std::endl;
    }
  } catch (const std::exception& e) {
    std::cerr << "bench_impose: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
