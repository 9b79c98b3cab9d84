// tilekit analyze neighbors --colors C --algo direct|halton --tilings N --max-size M --seed S
//   Table 1 of Schloemer & Deussen 2010: identically coloured 8-neighbours of each corner.
// tilekit analyze reduction [--max-colors C]
//   Table 2 of the same paper: tiles left when k disjoint colour pairs are excluded.
#include <fmt/format.h>

#include <chrono>
#include <cmath>

#include "cli/command.hpp"
#include "base/error.hpp"
#include "tiling/neighbour_statistics.hpp"
#include "tilesets/tile_set_reduction.hpp"

namespace tilekit::cli {

namespace {

struct NeighbourArgs {
  int colours = 0, tilings = 100, max_size = 4096;
  std::string algo = "halton", hash = "long-period";
  std::uint64_t seed = 1, samples = 0;
};

void run_neighbors(const NeighbourArgs& a, const Context& ctx) {
  const NeighbourAlgo algo = parse_neighbour_algo(a.algo);
  const HashKind hash = parse_hash_kind(a.hash);
  check_colour_count(a.colours, "--colors");
  const auto start = std::chrono::steady_clock::now();
  auto last = start;
  auto progress = [&](int done, int total) {
    const auto now = std::chrono::steady_clock::now();
    if (now - last > std::chrono::seconds(2) && done < total) {
      last = now;
      fmt::print(stderr, "analyze neighbors: {}/{} tilings\n", done, total);
    }
  };
  const NeighbourAnalysis r =
      analyze_neighbours(std::uint32_t(a.colours), algo, a.tilings, a.max_size, a.seed, hash, progress, a.samples);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double p = 1.0 / a.colours;
  nlohmann::json j = {{"colors", a.colours},
                      {"algo", a.algo},
                      {"tilings", a.tilings},
                      {"max_size", a.max_size},
                      {"seed", a.seed},
                      {"corners", r.stats.corners},
                      {"samples", a.samples},
                      {"mean", r.stats.mean()},
                      {"deviation", r.stats.deviation()},
                      {"binomial_mean", 8 * p},
                      {"binomial_deviation", std::sqrt(8 * p * (1 - p))},
                      {"seconds", seconds}};
  if (algo == NeighbourAlgo::Direct) j["hash"] = a.hash;
  if (auto row = paper_table1(std::uint32_t(a.colours))) {
    j["paper_mean"] = algo == NeighbourAlgo::Halton ? row->halton_mean : row->stochastic_mean;
    j["paper_deviation"] = algo == NeighbourAlgo::Halton ? row->halton_deviation : row->stochastic_deviation;
  }
  emit(ctx, j, [&] {
    fmt::print("{} colours, {} ({} tilings up to {}x{}, seed {}): {} corners\n", a.colours, a.algo, a.tilings,
               a.max_size, a.max_size, a.seed, r.stats.corners);
    fmt::print("  identically coloured neighbours: mean {:.4f}, deviation {:.4f}\n", r.stats.mean(),
               r.stats.deviation());
    if (j.contains("paper_mean"))
      fmt::print("  paper (Table 1):                 mean {:.4f}, deviation {:.4f}\n", j["paper_mean"].get<double>(),
                 j["paper_deviation"].get<double>());
    fmt::print("  Binomial(8, 1/C):                mean {:.4f}, deviation {:.4f}\n", 8 * p, std::sqrt(8 * p * (1 - p)));
  });
}

void add_neighbors(CLI::App* analyze, Context& ctx) {
  auto* cmd = analyze->add_subcommand(
      "neighbors", "Mean and RMS count of identically coloured 8-neighbours of each corner (Table 1 protocol)");
  auto a = std::make_shared<NeighbourArgs>();
  cmd->add_option("--colors", a->colours, "Number of corner colours C")->required();
  cmd->add_option("--algo", a->algo, "direct (stochastic hash) | halton (default)");
  cmd->add_option("--tilings", a->tilings, "Number of tilings of random resolution (default 100)");
  cmd->add_option("--max-size", a->max_size, "Resolutions T_x, T_y uniform in [1, M] (default 4096)");
  cmd->add_option("--seed", a->seed, "Seed for the resolutions and the hashes (default 1)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--hash", a->hash, "Hash of --algo direct: perm | long-period (default, as in the paper)");
  cmd->add_option("--samples", a->samples,
                  "Count only this many corners, drawn uniformly from all tilings (0 = every corner, default)")
      ->check(CLI::NonNegativeNumber);
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_neighbors(*a, ctx); });
}

struct ReductionArgs {
  int max_colours = 9;
};

void run_reduction(const ReductionArgs& a, const Context& ctx) {
  nlohmann::json rows = nlohmann::json::array();
  for (int c = 2; c <= a.max_colours; ++c)
    for (int k = 1; 2 * k <= c; ++k) {
      const std::int64_t closed = reduced_size_closed_form(c, k);
      const std::int64_t total = std::int64_t(c) * c * c * c;
      rows.push_back({{"colors", c},
                      {"k", k},
                      {"tiles", total},
                      {"closed_form", closed},
                      {"inclusion_exclusion", reduced_size_inclusion_exclusion(c, k)},
                      {"brute_force", reduced_size_brute_force(std::uint32_t(c), std::uint32_t(k))},
                      {"saving_percent", std::round(1000.0 * (1.0 - double(closed) / double(total))) / 10.0}});
    }
  emit(ctx, {{"rows", rows}}, [&] {
    fmt::print("{:>3} {:>2} {:>6} {:>12} {:>12} {:>12} {:>8}\n", "C", "k", "C^4", "closed form", "incl.-excl.",
               "brute force", "saving");
    for (const auto& r : rows)
      fmt::print("{:>3} {:>2} {:>6} {:>12} {:>12} {:>12} {:>7.1f}%\n", r["colors"].get<int>(), r["k"].get<int>(),
                 r["tiles"].get<std::int64_t>(), r["closed_form"].get<std::int64_t>(),
                 r["inclusion_exclusion"].get<std::int64_t>(), r["brute_force"].get<std::int64_t>(),
                 r["saving_percent"].get<double>());
  });
}

void add_reduction(CLI::App* analyze, Context& ctx) {
  auto* cmd = analyze->add_subcommand(
      "reduction",
      "Tiles left when k disjoint colour pairs are excluded: closed form, inclusion-exclusion, brute force");
  auto a = std::make_shared<ReductionArgs>();
  cmd->add_option("--max-colors", a->max_colours, "Largest C (default 9, as in the paper's Table 2)")
      ->check(CLI::Range(2, 16));
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_reduction(*a, ctx); });
}

}  // namespace

void add_analyze_commands(CLI::App& app, Context& ctx) {
  auto* analyze = app.add_subcommand("analyze", "Statistics of tilings and tile sets (Schloemer & Deussen 2010)");
  analyze->require_subcommand(1);
  add_neighbors(analyze, ctx);
  add_reduction(analyze, ctx);
}

}  // namespace tilekit::cli
