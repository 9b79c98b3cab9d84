// Solver benchmarks (the targets in BENCHMARKS.md, "Solver"). One JSON line per case on stdout;
// every case that has a baseline times it in the same run. Machines are shared: medians of
// several repetitions, wall and CPU seconds, and the core count are reported.
//
//   build/bench_solver            all cases except the long ones
//   build/bench_solver --speedup  also the 2-thread speed-up on a count of >= 10 s
//   build/bench_solver --c4 SEC   also plain search for C=4 corner and Wang packings, SEC each
//   build/bench_solver --only NAME one group: c2, c3, formulations, knuth, checkpoint, speedup, c4
// (the CMake target is bench_bench_solver: build/bench_bench_solver)
// Over 400 lines on purpose: bench/ has one executable per file, and these issue-3 cases share
// the timing, median and problem helpers at the top; the groups are selected with --only.
#include <fmt/format.h>
#include <omp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "bench/bench_common.hpp"
#include "checkpoints/checkpoint.hpp"
#include "solver/cell_model.hpp"
#include "solver/knuth_estimate.hpp"
#include "solver/lattice_model.hpp"
#include "solver/solve.hpp"
#include "tilesets/tile_set_io.hpp"
#include "tilesets/validator.hpp"

using namespace tilekit;
using tilekit::bench::cpu_seconds;

namespace {

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct Timing {
  double wall = 0, cpu = 0;
};

// Median wall and CPU seconds of `reps` runs of f.
Timing median_time(int reps, const std::function<void()>& f) {
  std::vector<double> w, c;
  for (int i = 0; i < reps; ++i) {
    double t0 = now(), c0 = cpu_seconds();
    f();
    w.push_back(now() - t0);
    c.push_back(cpu_seconds() - c0);
  }
  std::sort(w.begin(), w.end());
  std::sort(c.begin(), c.end());
  return {w[w.size() / 2], c[c.size() / 2]};
}

void line(nlohmann::json j) {
  j["cores"] = std::thread::hardware_concurrency();
  fmt::print("{}\n", j.dump());
  std::fflush(stdout);
}

// ---- The baseline: a plain tile-per-cell DFS (~30 lines). Scanline order, every tile tried in
// every cell against its placed neighbours (torus wrap at the last row/column), a used flag
// per tile; no symmetry breaking, no bitsets, no forward checking, no restarts.
struct PlainDfs {
  std::vector<std::array<int, 4>> lab;  // tile -> N E S W edge labels (corner: colour pairs)
  int n = 0, T = 0;
  std::vector<int> grid;
  std::vector<char> used;
  std::uint64_t nodes = 0, limit = 0;
  bool first = false, stop = false;
  explicit PlainDfs(const TileSet& s, int side)
      : n(side), T(int(s.size())), grid(std::size_t(side * side), -1), used(s.size()) {
    for (std::size_t k = 0; k < s.size(); ++k) {
      if (s.kind() == TileKind::Wang) {
        auto t = s.wang_tiles()[k];
        lab.push_back({int(t.n), int(t.e), int(t.s), int(t.w)});
      } else {
        auto t = s.corner_tiles()[k];
        int C = int(s.horizontal_radix());
        lab.push_back({int(t.nw * C + t.ne), int(t.ne * C + t.se), int(t.sw * C + t.se), int(t.nw * C + t.sw)});
      }
    }
  }
  std::uint64_t dfs(int pos) {
    ++nodes;
    if (pos == n * n) return 1;
    if (limit && nodes > limit) return stop = true, 0;
    int r = pos / n, c = pos % n;
    std::uint64_t count = 0;
    for (int t = 0; t < T && !stop; ++t) {
      if (used[std::size_t(t)]) continue;
      const auto& l = lab[std::size_t(t)];
      if (c > 0 && l[3] != lab[std::size_t(grid[std::size_t(pos - 1)])][1]) continue;
      if (r > 0 && l[0] != lab[std::size_t(grid[std::size_t(pos - n)])][2]) continue;
      if (c == n - 1 && l[1] != lab[std::size_t(grid[std::size_t(pos - c)])][3]) continue;
      if (r == n - 1 && l[2] != lab[std::size_t(grid[std::size_t(c)])][0]) continue;
      used[std::size_t(t)] = 1, grid[std::size_t(pos)] = t;
      count += dfs(pos + 1);
      used[std::size_t(t)] = 0;
      if (first && count) return stop = true, count;
    }
    return count;
  }
};

SearchResult run(const TilingProblem& p, SearchMode mode, int threads, const std::string& formulation = "auto",
                 std::uint64_t seed = 0, double time_limit = 0) {
  SearchOptions o;
  o.mode = mode;
  o.run.threads = threads;
  o.formulation = formulation_from_name(formulation).value();
  o.run.seed = seed;
  o.run.time_limit = time_limit;
  return solve(p, o);
}

TilingProblem tilings(const std::string& set, int rows, int cols) {
  TilingProblem p;
  p.set = resolve_tile_set(set);
  p.rows = rows, p.cols = cols, p.torus = true;
  return p;
}

void bench_two_colour_counts() {
  for (TileKind k : {TileKind::Wang, TileKind::Corner}) {
    TilingProblem p = complete_packing_problem(k, 2);
    std::uint64_t base_count = 0, base_nodes = 0, count = 0, nodes = 0;
    SearchStats stats;  // of the last timed run (every run counts the same)
    Timing base = median_time(5, [&] {
      PlainDfs d(p.set, 4);
      base_count = d.dfs(0);
      base_nodes = d.nodes;
    });
    for (std::string f : {"cell", k == TileKind::Wang ? "edges" : "pegs"}) {
      Timing t = median_time(7, [&] {
        SearchResult r = run(p, SearchMode::Count, 1, f);
        count = r.solutions, nodes = r.nodes, stats = r.stats;
      });
      line({{"case", "c2_count"},
            {"kind", kind_name(k)},
            {"formulation", f},
            {"threads", 1},
            {"solutions", count},
            {"baseline_solutions", base_count},
            {"seconds", t.wall},
            {"cpu_seconds", t.cpu},
            {"baseline_seconds", base.wall},
            {"baseline_cpu_seconds", base.cpu},
            {"speedup_vs_baseline_cpu", base.cpu / std::max(t.cpu, 1e-9)},
            {"nodes", nodes},
            {"nodes_per_cpu_s", double(nodes) / std::max(t.cpu, 1e-9)},
            {"baseline_nodes", base_nodes},
            {"stats", stats}});
    }
  }
}

void bench_three_colour_first() {
  for (TileKind k : {TileKind::Corner, TileKind::Wang}) {
    TilingProblem p = complete_packing_problem(k, 3);
    for (std::string f : {"cell", k == TileKind::Wang ? "edges" : "pegs"}) {
      std::vector<double> wall, cpu;
      std::uint64_t nodes = 0, found = 0;
      SearchStats stats;                                 // the five seeded runs, summed
      for (std::uint64_t seed = 1; seed <= 5; ++seed) {  // seed 0 (natural order first) is timed below
        double t0 = now(), c0 = cpu_seconds();
        SearchResult r = run(p, SearchMode::First, 1, f, seed, 30);
        wall.push_back(now() - t0);
        cpu.push_back(cpu_seconds() - c0);
        nodes += r.nodes;
        stats += r.stats;
        found += !r.found.empty() && validate(r.found[0], &p.set).packing;
      }
      std::sort(wall.begin(), wall.end());
      std::sort(cpu.begin(), cpu.end());
      double n0 = now(), nc0 = cpu_seconds();
      SearchResult natural = run(p, SearchMode::First, 1, f, 0, 30);
      double natural_wall = now() - n0, natural_cpu = cpu_seconds() - nc0;
      // The baseline on the same problem, capped at 5e7 nodes.
      PlainDfs d(p.set, 9);
      d.first = true, d.limit = 50000000;
      double t0 = now(), c0 = cpu_seconds();
      std::uint64_t bfound = d.dfs(0);
      line({{"case", "c3_first"},
            {"kind", kind_name(k)},
            {"formulation", f},
            {"threads", 1},
            {"runs", 5},
            {"validated", found},
            {"median_seconds", wall[2]},
            {"max_seconds", wall[4]},
            {"median_cpu_seconds", cpu[2]},
            {"max_cpu_seconds", cpu[4]},
            {"mean_nodes", nodes / 5},
            {"seed0_seconds", natural_wall},
            {"seed0_cpu_seconds", natural_cpu},
            {"seed0_found", !natural.found.empty()},
            {"baseline_found", bfound > 0},
            {"baseline_nodes", d.nodes},
            {"baseline_seconds", now() - t0},
            {"baseline_cpu_seconds", cpu_seconds() - c0},
            {"stats", stats}});
    }
  }
}

void bench_formulation_counts() {
  struct Case {
    std::string set;
    int rows, cols;
    std::string lattice;
  };
  for (const Case& c : {Case{"complete-corner-2", 4, 5, "pegs"}, Case{"complete-wang-2", 2, 5, "edges"},
                        Case{"compact-corner-2", 4, 4, "pegs"}}) {
    TilingProblem p = tilings(c.set, c.rows, c.cols);
    for (std::string f : {std::string("cell"), c.lattice}) {
      SearchResult r;
      Timing t = median_time(3, [&] { r = run(p, SearchMode::Count, 1, f); });
      line({{"case", "formulation_count"},
            {"set", c.set},
            {"grid", fmt::format("{}x{} torus", c.rows, c.cols)},
            {"formulation", f},
            {"solutions", r.solutions},
            {"nodes", r.nodes},
            {"seconds", t.wall},
            {"cpu_seconds", t.cpu},
            {"nodes_per_cpu_s", double(r.nodes) / std::max(t.cpu, 1e-9)},
            {"stats", r.stats}});
    }
  }
}

template <class M>
void knuth_line(const std::string& name, const M& root, std::uint64_t exact) {
  for (std::uint64_t probes : {100, 1000, 10000}) {
    double t0 = now();
    TreeEstimate e = knuth_estimate(root, probes, 1);
    line({{"case", "knuth_estimate"},
          {"problem", name},
          {"probes", probes},
          {"estimate", e.nodes},
          {"exact", exact},
          {"relative_error", (e.nodes - double(exact)) / double(exact)},
          {"seconds", now() - t0}});
  }
}

void bench_knuth() {
  {
    TilingProblem p = complete_packing_problem(TileKind::Wang, 2);
    SearchOptions o;
    o.mode = SearchMode::Count;
    o.subproblems = 1;  // a single subtree: the node count is the tree size
    knuth_line("wang C=2 packings (cell)", CellModel(p, true, CellModel::Ordering::Static), solve(p, o).nodes);
  }
  {
    TilingProblem p = tilings("complete-corner-2", 4, 5);
    SearchOptions o;
    o.mode = SearchMode::Count;
    o.subproblems = 1;
    o.ordering = "static";
    knuth_line("corner C=2 tilings of the 4x5 torus (cell, static)", CellModel(p, true, CellModel::Ordering::Static),
               solve(p, o).nodes);
  }
  {
    TilingProblem p = tilings("kari-14", 6, 6);
    SearchOptions o;
    o.mode = SearchMode::Count;
    o.subproblems = 1;
    o.ordering = "static";
    knuth_line("kari-14 tilings of the 6x6 torus (none exist; cell, static)",
               CellModel(p, true, CellModel::Ordering::Static), solve(p, o).nodes);
  }
  {
    TilingProblem p = complete_packing_problem(TileKind::Corner, 3);
    CellModel m(p, true, CellModel::Ordering::Static);
    double t0 = now();
    TreeEstimate e = knuth_estimate(m, 10000, 1);
    line({{"case", "knuth_estimate"},
          {"problem", "corner C=3 packings (cell), tree size unknown"},
          {"probes", 10000},
          {"estimate", e.nodes},
          {"estimated_solutions", e.leaves * 81},
          {"seconds", now() - t0}});
  }
}

void bench_checkpoint_cost() {
  // Corner C=2 tilings of the 5x5 torus (2^25), pegs, 1 thread, 4 s runs, alternating: no
  // checkpoints versus a checkpoint every second. Reported: throughput (nodes per CPU second,
  // medians of 5) and the time spent encoding and writing checkpoints (which runs on the
  // monitor thread, not the workers) as a fraction of the run.
  TilingProblem p = tilings("complete-corner-2", 5, 5);
  std::string path = (std::filesystem::temp_directory_path() / fmt::format("bench-ckpt-{}", ::getpid())).string();
  std::vector<double> plain, ckpt, fraction;
  std::size_t written = 0;
  for (int rep = 0; rep < 5; ++rep)
    for (double every : {0.0, 1.0}) {
      SearchOptions o;
      o.mode = SearchMode::Count;
      o.formulation = Formulation::Pegs;
      o.run.time_limit = 4;
      double in_ckpt = 0;
      if (every > 0) {
        o.run.checkpoint_every = every;
        o.save_checkpoint = [&](const SearchState& st) {
          double t0 = now();
          write_checkpoint(path, st);
          in_ckpt += now() - t0;
        };
      }
      double c0 = cpu_seconds(), t0 = now();
      SearchResult r = solve(p, o);
      double rate = double(r.nodes) / std::max(cpu_seconds() - c0, 1e-9);
      (every > 0 ? ckpt : plain).push_back(rate);
      if (every > 0) written += r.checkpoints, fraction.push_back(in_ckpt / (now() - t0));
    }
  std::filesystem::remove(path);
  std::sort(plain.begin(), plain.end());
  std::sort(ckpt.begin(), ckpt.end());
  std::sort(fraction.begin(), fraction.end());
  line({{"case", "checkpoint_cost"},
        {"problem", "corner C=2 tilings 5x5 torus, pegs, 1 thread, 4 s runs x5"},
        {"checkpoint_every", 1.0},
        {"checkpoints_written", written},
        {"nodes_per_cpu_s_without", plain[2]},
        {"nodes_per_cpu_s_with", ckpt[2]},
        {"throughput_cost", 1 - ckpt[2] / plain[2]},
        {"checkpoint_time_fraction", fraction[2]}});
}

void bench_speedup() {
  // Corner C=2 tilings of the 5x5 torus: exactly 2^25 solutions; the cell model with static
  // order visits 267M nodes (about 10 CPU seconds).
  TilingProblem p = tilings("complete-corner-2", 5, 5);
  for (std::string f : {"cell"}) {
    double base = 0;
    for (int threads : {1, 2}) {
      SearchOptions o;
      o.mode = SearchMode::Count;
      o.run.threads = threads;
      o.formulation = formulation_from_name(f).value();
      o.ordering = "static";
      double t0 = now(), c0 = cpu_seconds();
      SearchResult r = solve(p, o);
      double wall = now() - t0;
      if (threads == 1) base = wall;
      line({{"case", "parallel_speedup"},
            {"problem", "corner C=2 tilings 5x5 torus"},
            {"formulation", f},
            {"threads", threads},
            {"solutions", r.solutions},
            {"seconds", wall},
            {"cpu_seconds", cpu_seconds() - c0},
            {"speedup", base / wall},
            {"stats", r.stats},
            {"load_average_1min", [] {
               double l[1];
               return getloadavg(l, 1) == 1 ? l[0] : -1;
             }()}});
    }
  }
}

void bench_c4(double seconds) {
  for (TileKind k : {TileKind::Corner, TileKind::Wang})
    for (std::string f : {"cell", k == TileKind::Wang ? "edges" : "pegs"}) {
      TilingProblem p = complete_packing_problem(k, 4);
      double c0 = cpu_seconds();
      SearchResult r = run(p, SearchMode::First, 2, f, 1, seconds);
      bool ok = !r.found.empty() && validate(r.found[0], &p.set).packing;
      line({{"case", "c4_first_plain_search"},
            {"kind", kind_name(k)},
            {"formulation", f},
            {"threads", 2},
            {"time_limit", seconds},
            {"found", ok},
            {"seconds", r.seconds},
            {"cpu_seconds", cpu_seconds() - c0},
            {"nodes", r.nodes},
            {"restarts", r.restarts},
            {"stats", r.stats}});
    }
}

}  // namespace

int main(int argc, char** argv) {
  bool speedup = false;
  double c4 = 0;
  std::string only;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--speedup"))
      speedup = true;
    else if (!std::strcmp(argv[i], "--c4") && i + 1 < argc)
      c4 = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--only") && i + 1 < argc)
      only = argv[++i];
    else {
      fmt::print(
          stderr,
          "usage: bench_solver [--speedup] [--c4 SECONDS] [--only c2|c3|formulations|knuth|checkpoint|speedup|c4]\n");
      return 2;
    }
  }
  auto want = [&](const char* name) { return only.empty() || only == name; };
  if (want("c2")) bench_two_colour_counts();
  if (want("c3")) bench_three_colour_first();
  if (want("formulations")) bench_formulation_counts();
  if (want("knuth")) bench_knuth();
  if (want("checkpoint")) bench_checkpoint_cost();
  if ((speedup && only.empty()) || only == "speedup") bench_speedup();
  if (c4 > 0 && (only.empty() || only == "c4")) bench_c4(c4);
}
