// Search under imposed automorphisms (issue 7): time to the first packing per (kind, C, group),
// median over seeds, against the plain search (trivial group, same engine, same time limit) run
// in the same process. One JSON line per case on stdout.
//
//   build/bench_impose                       default cases (C=3..5, corner and Wang)
//   build/bench_impose --case corner:5:t=0,5:pi=1,2,3,4,0 --reps 5 --threads 1 --time-limit 60
//   build/bench_impose --no-baseline ...     skip the plain search
//   build/bench_impose --portfolio corner:6 --threads 1 --time-limit 3000 [--stats F]
//                                            the --method auto portfolio, one JSON line with every
//                                            candidate's tries, nodes and seconds
//   --sat (CNF + cadical instead of the DFS), --patterns MASK (bit k: size-k pattern counts, default 4), --static (no MCF), --luby-unit N
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "solver/impose_portfolio.hpp"
#include "solver/impose_solve.hpp"
#include "base/error.hpp"

using namespace tilekit;

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

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

nlohmann::json run_case(const Case& c, const std::string& spec, int reps, int threads, double limit, std::uint64_t seed0,
                        const SymmetricControl& ctl) {
  std::vector<double> secs, nodes;
  int found = 0;
  for (int r = 0; r < reps; ++r) {
    SearchOptions o;
    o.threads = threads;
    o.seed = seed0 + std::uint64_t(r);
    o.time_limit = limit;
    auto res = solve_symmetric(c.kind, c.colours, spec, o, ctl);
    secs.push_back(res.result.solutions ? res.result.seconds : limit);
    nodes.push_back(double(res.result.nodes));
    found += res.result.solutions ? 1 : 0;
  }
  return {{"spec", spec}, {"found", found}, {"runs", reps}, {"median_seconds", median(secs)},
          {"median_nodes", median(nodes)}, {"time_limit", limit}};
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
  SymmetricControl ctl;
  try {
    for (int i = 1; i < argc; ++i) {
      std::string a = argv[i];
      auto next = [&]() -> std::string {
        if (i + 1 >= argc) throw InputError(a + " needs a value");
        return argv[++i];
      };
      if (a == "--case") cases.push_back(parse_case(next()));
      else if (a == "--reps") reps = std::stoi(next());
      else if (a == "--threads") threads = std::stoi(next());
      else if (a == "--time-limit") limit = std::stod(next());
      else if (a == "--seed") seed = std::stoull(next());
      else if (a == "--no-baseline") baseline = false;
      else if (a == "--portfolio") portfolios.push_back(next());
      else if (a == "--stats") stats = next();
      else if (a == "--patterns") ctl.pattern_sizes = std::stoi(next());
      else if (a == "--static") ctl.most_constrained = false;
      else if (a == "--sat") ctl.sat = true;
      else if (a == "--luby-unit") ctl.luby_unit = std::stoull(next());
      else throw InputError("unknown argument " + a);
    }
    for (const auto& pf : portfolios) {
      Case c = parse_case(pf + ":");
      for (int r = 0; r < reps; ++r) {
        SearchOptions o;
        o.threads = threads;
        o.seed = seed + std::uint64_t(r);
        o.time_limit = limit;
        PortfolioOptions po;
        po.stats_path = stats;
        auto res = run_portfolio(c.kind, c.colours, o, po);
        std::cout << nlohmann::json({{"bench", "impose-portfolio"},
                                     {"kind", std::string(kind_name(c.kind))},
                                     {"colors", c.colours},
                                     {"threads", threads},
                                     {"cores", std::thread::hardware_concurrency()},
                                     {"seed", o.seed},
                                     {"found", res.found},
                                     {"group", res.spec},
                                     {"seconds", res.seconds},
                                     {"nodes", res.nodes},
                                     {"time_limit", limit},
                                     {"runs", res.runs}})
                         .dump()
                  << std::endl;
      }
    }
    if (!portfolios.empty() && cases.empty()) return 0;
    if (cases.empty()) {
      cases = {{TileKind::Corner, 3, "t=0,3:pi=1,2,0"},       {TileKind::Wang, 3, "t=0,3:pi=1,2,0"},
               {TileKind::Corner, 4, "t=0,4:pi=1,2,3,0"},     {TileKind::Wang, 4, "t=0,8:pi=1,0,3,2"},
               {TileKind::Corner, 5, "t=0,5:pi=1,2,3,4,0"},   {TileKind::Wang, 5, "t=0,5:pi=1,2,3,4,0"}};
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
