// Benchmarks of the aperiodic engine (BENCHMARKS.md): one JSON line per case.
//   bench_aperiodic tables            Tables 8.1-8.7 recomputed (median of 3 runs)
//   bench_aperiodic verify SET P      verify --max-period P (median of 3 runs); SET may be
//                                     METHOD:NAME, e.g. diagonal:kari-14 (the converted set);
//                                     baselines: 1 thread, and the solver alone (no filter)
//   bench_aperiodic shapes SET P      per-formulation solve() time of the P x P torus
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include "aperiodic/verify.hpp"
#include "solver/solve.hpp"
#include "aperiodic/convert.hpp"
#include "aperiodic/table.hpp"
#include "tilesets/tile_set_io.hpp"

using namespace tilekit;

namespace {

template <class F>
double median_seconds(int runs, F&& f) {
  std::vector<double> t;
  for (int i = 0; i < runs; ++i) {
    auto t0 = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  std::string what = argc > 1 ? argv[1] : "tables";
  const int cores = omp_get_num_procs();
  if (what == "tables") {
    TableOptions one;
    one.levels = 1;  // baseline: Tables 8.1/8.2 only
    double base = median_seconds(3, [&] { compute_tables(one); });
    std::size_t largest = 0;
    double full = median_seconds(3, [&] { largest = compute_tables().largest; });
    fmt::print(R"({{"case":"tables-8.1-8.7","seconds":{:.4f},"baseline":"tables 8.1-8.2 only","baseline_seconds":{:.4f},"largest_set":{},"cores":{}}})"
               "\n",
               full, base, largest, cores);
  } else if (what == "verify" && argc > 3) {
    std::string name = argv[2];
    TileSet set;
    if (auto colon = name.find(':'); colon != std::string::npos) {
      TileSet src = resolve_tile_set(name.substr(colon + 1));
      set = conversion_tile_set(convert(src, parse_method(name.substr(0, colon))), name, "");
    } else {
      set = resolve_tile_set(name);
    }
    VerifyOptions o;
    o.max_period = std::stoi(argv[3]);
    VerifyResult r;
    double s = median_seconds(3, [&] { r = verify_tile_set(set, o); });
    VerifyOptions one = o;
    one.threads = 1;
    double s1 = median_seconds(3, [&] { verify_tile_set(set, one); });
    fmt::print(R"({{"case":"verify","set":"{}","tiles":{},"max_period":{},"verdict":"{}","nodes":{},"shapes_excluded":{},"seconds":{:.4f},"threads":{},"baseline":"1 thread","baseline_seconds":{:.4f},"cores":{}}})"
               "\n",
               name, set.size(), o.max_period, r.verdict, r.nodes, r.shapes_excluded, s, r.threads, s1, cores);
    if (argc > 4) {  // solver alone, up to this period (it grows fast: see BENCHMARKS.md)
      VerifyOptions nf = o;
      nf.max_period = std::stoi(argv[4]);
      nf.transducer_filter = false;
      VerifyOptions f = o;
      f.max_period = nf.max_period;
      VerifyResult rn, rf;
      double sn = median_seconds(1, [&] { rn = verify_tile_set(set, nf); });
      double sf = median_seconds(3, [&] { rf = verify_tile_set(set, f); });
      fmt::print(R"J({{"case":"verify-filter-vs-solver","set":"{}","max_period":{},"seconds":{:.4f},"verdict":"{}","baseline":"solver only (no transducer filter)","baseline_seconds":{:.4f},"baseline_nodes":{},"baseline_verdict":"{}","cores":{}}})J"
                 "\n",
                 name, nf.max_period, sf, rf.verdict, sn, rn.nodes, rn.verdict, cores);
    }
  } else if (what == "shapes" && argc > 3) {
    TileSet set = resolve_tile_set(argv[2]);
    int p = std::stoi(argv[3]);
    std::vector<std::pair<std::string, std::string>> forms = {{"cell", "static"}, {"cell", "mrv"}};
    forms.push_back({set.kind() == TileKind::Wang ? "edges" : "pegs", "static"});
    for (auto& [f, ord] : forms) {
      TilingProblem pr;
      pr.set = set;
      pr.rows = pr.cols = p;
      pr.torus = true;
      SearchOptions so;
      so.formulation = formulation_from_name(f).value();
      so.ordering = ord;
      so.restarts = 0;
      so.run.time_limit = 60;
      SearchResult r;
      double s = median_seconds(1, [&] { r = solve(pr, so); });
      fmt::print(R"({{"case":"torus","set":"{}","shape":{},"formulation":"{}","ordering":"{}","found":{},"complete":{},"nodes":{},"seconds":{:.4f}}})"
                 "\n",
                 argv[2], p, f, ord, !r.found.empty(), r.complete, r.nodes, s);
    }
  } else {
    fmt::print(stderr, "usage: bench_aperiodic tables | verify SET P | shapes SET P\n");
    return 2;
  }
  return 0;
}
