// tilekit aperiodic verify SET [--max-period P] [--max-square N]: periodic / square search.
#include <fmt/format.h>

#include <optional>

#include "aperiodic/store.hpp"
#include "aperiodic/verify.hpp"
#include "cli/cmd_aperiodic.hpp"
#include "base/error.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit::cli {

nlohmann::json verify_json(const VerifyResult& r) {
  nlohmann::json j = {{"verdict", r.verdict},
                      {"period", r.period ? nlohmann::json::array({r.period->first, r.period->second}) : nlohmann::json()},
                      {"witness", r.witness},
                      {"largest_square", r.largest_square},
                      {"nodes", r.nodes},
                      {"shapes_searched", r.shapes_searched},
                      {"shapes_incomplete", r.shapes_incomplete},
                      {"shapes_excluded", r.shapes_excluded},
                      {"periodic_rows", r.periodic_rows},
                      {"periodic_cols", r.periodic_cols},
                      {"excluded_row_periods", r.excluded_rows},
                      {"excluded_col_periods", r.excluded_cols},
                      {"threads", r.threads},
                      {"seconds", r.seconds}};
  return j;
}

namespace {

struct VerifyArgs {
  std::string set, db;
  VerifyOptions opts;
  int prune = -1;
};

void run_verify(const Context& ctx, const VerifyArgs& a) {
  TileSet set = resolve_tile_set(a.set);
  if (set.empty()) throw InputError(fmt::format("tile set '{}' has no tiles", a.set));
  nlohmann::json pruned;
  if (a.prune >= 0) {
    PruneReport rep;
    std::string name = set.name();
    set = prune(set, a.prune, &rep);
    set.set_name(fmt::format("{}-pruned{}", name, a.prune));
    pruned = prune_json(rep, a.prune);
  }
  VerifyResult r;
  if (set.empty()) {
    // Surround pruning keeps every tiling of the plane and SCC pruning keeps tileability:
    // nothing left means the set does not tile the plane.
    r.verdict = "cannot-tile";
    r.threads = 0;
  } else {
    r = verify_tile_set(set, a.opts);
  }
  nlohmann::json j = verify_json(r);
  j["set"] = set.name();
  j["kind"] = std::string(kind_name(set.kind()));
  j["tiles"] = set.size();
  j["colors"] = set.colours();
  j["max_period"] = a.opts.max_period;
  j["max_square"] = a.opts.max_square;
  if (!pruned.is_null()) j["pruned"] = pruned;
  if (!a.db.empty()) {
    ResultsDb db(a.db);
    j["run_id"] = store_verify(db, set, r,
                               {{"max_period", a.opts.max_period}, {"max_square", a.opts.max_square}, {"prune", a.prune}});
    j["db"] = a.db;
  }
  emit(ctx, j, [&] {
    fmt::print("{} ({} {} tiles, {} colours): {}\n", set.name(), set.size(), kind_name(set.kind()), set.colours(),
               r.verdict);
    if (r.period) {
      fmt::print("witness: {} x {} torus (tile numbers as in `tileset show`):\n", r.period->first, r.period->second);
      for (auto& row : r.witness) fmt::print("  {}\n", fmt::join(row, " "));
    }
    if (r.largest_square >= 0) fmt::print("largest tileable square searched: {} x {}\n", r.largest_square, r.largest_square);
    fmt::print("{} torus shapes ruled out by the transducer filter (no horizontal period in [{}], no vertical "
               "period in [{}])\n",
               r.shapes_excluded, fmt::join(r.excluded_cols, ","), fmt::join(r.excluded_rows, ","));
    fmt::print("{} torus shapes searched ({} incomplete), {} nodes, {} threads, {:.2f} s\n", r.shapes_searched,
               r.shapes_incomplete, r.nodes, r.threads, r.seconds);
  });
}

}  // namespace

void add_aperiodic_verify_command(CLI::App* ap, Context& ctx) {
  auto* cmd = ap->add_subcommand("verify", "Search for a periodic tiling (torus p x q) and for an n x n square tiling");
  static VerifyArgs va;
  cmd->add_option("SET", va.set, "Built-in name or tile-set file (Wang or corner)")->required();
  cmd->add_option("--max-period", va.opts.max_period, "Largest torus period in each direction (default 8)");
  cmd->add_option("--max-square", va.opts.max_square, "Also search an N x N square (bounded); 0 = no square search");
  cmd->add_option("--threads", va.opts.threads, "Threads (default: all)");
  cmd->add_option("--time-limit", va.opts.time_limit, "Seconds for the whole verification (0 = none; verdict inconclusive if hit)");
  cmd->add_option("--prune", va.prune, "Verify the set pruned to radius R (aperiodic/prune.hpp)");
  cmd->add_option("--db", va.db, "Store the run, the tile set and the witness in this results database");
  cmd->add_flag("--progress", va.opts.progress, "Progress on stderr");
  cmd->add_flag("--no-filter", [](std::int64_t) { va.opts.transducer_filter = false; },
                "Send every torus shape to the solver (no transducer filter; for comparison)");
  add_json_flag(cmd, ctx);
  cmd->callback([&ctx] { run_verify(ctx, va); });
}

}  // namespace tilekit::cli
