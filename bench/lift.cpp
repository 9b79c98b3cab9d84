// Colour-quotient lifts: time to the first packing by lift search (the engine's
// lattice or cell model, or the CNF with cadical), median over seeds, against the plain search of
// the same problem (no lift, same time limit) run in the same process; and the binary lift
// construction with the independent validator for the large powers of two. One JSON line per case.
//
//   build/bench_lift                                   default cases (below), 3 seeds each
//   build/bench_lift --case corner:8:4:sat --reps 5 --time-limit 60
//                                                      KIND:C:M:FORMULATION (auto, cell or sat)
//   build/bench_lift --seed 0 ...                      first seed (default 1; seed 0 keeps the natural
//                                                      value order of the first dive)
//   build/bench_lift --no-baseline --restart-base 20000 ...
// The plain search (no lift, --baseline-limit seconds, one seed) runs once per kind and C.
//   build/bench_lift --construct 8,16,32 --reps 5      construct_packing() + validate(), medians
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "base/error.hpp"
#include "solver/solve.hpp"
#include "tilesets/constructions.hpp"
#include "tilesets/validator.hpp"

using namespace tilekit;

namespace {

struct Case {
  TileKind kind = TileKind::Corner;
  std::uint32_t colours = 0;
  std::string lift, formulation = "auto";  // lift "" = the plain search
};

Case parse_case(const std::string& s) {
  std::vector<std::string> f;
  std::stringstream in(s);
  for (std::string x; std::getline(in, x, ':');) f.push_back(x);
  if (f.size() < 3 || f.size() > 4 || (f[0] != "corner" && f[0] != "wang"))
    throw InputError("--case KIND:C:M[:FORMULATION], e.g. corner:8:4:sat");
  Case c;
  c.kind = f[0] == "corner" ? TileKind::Corner : TileKind::Wang;
  c.colours = std::uint32_t(std::stoul(f[1]));
  c.lift = f[2];
  if (f.size() == 4) c.formulation = f[3];
  return c;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

nlohmann::json run_case(const Case& c, int reps, int threads, double limit, std::uint64_t seed0,
                        std::uint64_t restart_base) {
  std::vector<double> secs, nodes;
  int found = 0;
  SearchStats stats;  // every run, summed
  for (int r = 0; r < reps; ++r) {
    SearchOptions o;
    o.run.threads = threads;
    o.run.seed = seed0 + std::uint64_t(r);
    o.run.time_limit = limit;
    o.lift = c.lift;
    o.formulation = formulation_from_name(c.formulation).value();
    o.restart_base = restart_base;
    SearchResult res = solve(complete_packing_problem(c.kind, c.colours), o);
    const bool ok = !res.found.empty() && validate(res.found[0]).packing;  // the independent validator
    secs.push_back(ok ? res.seconds : limit);
    nodes.push_back(double(res.nodes));
    stats += res.stats;
    found += ok;
  }
  return {{"lift", c.lift.empty() ? nlohmann::json(nullptr) : nlohmann::json(c.lift)},
          {"formulation", c.formulation},
          {"found", found},
          {"runs", reps},
          {"seeds", fmt::format("{}..{}", seed0, seed0 + std::uint64_t(reps) - 1)},
          {"median_seconds", median(secs)},
          {"median_nodes", median(nodes)},
          {"time_limit", limit},
          {"stats", stats}};
}

void bench_construct(const std::vector<std::uint32_t>& colours, int reps) {
  for (std::uint32_t c : colours) {
    std::vector<double> build, check;
    bool packing = true;
    std::string how;
    for (int r = 0; r < reps; ++r) {
      auto t0 = std::chrono::steady_clock::now();
      auto p = construct_packing(TileKind::Corner, c);
      auto t1 = std::chrono::steady_clock::now();
      if (!p) throw InputError(fmt::format("no construction for C={}", c));
      packing = packing && validate(p->tiling).packing;
      auto t2 = std::chrono::steady_clock::now();
      build.push_back(std::chrono::duration<double>(t1 - t0).count());
      check.push_back(std::chrono::duration<double>(t2 - t1).count());
      how = p->how;
    }
    std::cout << nlohmann::json({{"bench", "lift-construct"},
                                 {"kind", "corner"},
                                 {"colors", c},
                                 {"side", c * c},
                                 {"how", how},
                                 {"packing", packing},
                                 {"median_construct_seconds", median(build)},
                                 {"median_validate_seconds", median(check)},
                                 {"runs", reps},
                                 {"cores", std::thread::hardware_concurrency()}})
                     .dump()
              << std::endl;
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<Case> cases;
  std::vector<std::uint32_t> construct;
  int reps = 3, threads = 1;
  double limit = 60, baseline_limit = 60;
  std::uint64_t restart_base = 0, seed0 = 1;
  bool baseline = true;
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
      else if (a == "--baseline-limit") baseline_limit = std::stod(next());
      else if (a == "--restart-base") restart_base = std::stoull(next());
      else if (a == "--seed") seed0 = std::stoull(next());
      else if (a == "--no-baseline") baseline = false;
      else if (a == "--construct") {
        std::stringstream in(next());
        for (std::string x; std::getline(in, x, ',');) construct.push_back(std::uint32_t(std::stoul(x)));
      } else throw InputError("unknown argument " + a);
    }
    if (!construct.empty()) {
      bench_construct(construct, reps);
      if (cases.empty()) return 0;
    }
    if (cases.empty())
      cases = {parse_case("corner:8:4:sat"), parse_case("corner:8:4:cell"), parse_case("corner:16:8:cell"),
               parse_case("wang:4:2:sat")};
    std::vector<std::pair<TileKind, std::uint32_t>> baselined;
    for (const Case& c : cases) {
      nlohmann::json line = {{"bench", "lift"},
                             {"kind", std::string(kind_name(c.kind))},
                             {"colors", c.colours},
                             {"threads", threads},
                             {"cores", std::thread::hardware_concurrency()}};
      line["lift"] = run_case(c, reps, threads, limit, seed0, restart_base);
      const std::pair<TileKind, std::uint32_t> key{c.kind, c.colours};
      if (baseline && std::find(baselined.begin(), baselined.end(), key) == baselined.end()) {
        baselined.push_back(key);
        Case plain = c;
        plain.lift.clear();
        plain.formulation = "auto";
        line["baseline_plain"] = run_case(plain, 1, threads, baseline_limit, 1, restart_base);
      }
      std::cout << line.dump() << std::endl;
    }
  } catch (const std::exception& e) {
    std::cerr << "bench_lift: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
