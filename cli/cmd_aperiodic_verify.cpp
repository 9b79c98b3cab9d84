// tilekit aperiodic verify SET: periodic, finite or unknown (aperiodic/verify.hpp), by the
// transducer method and the torus search.
#include <fmt/format.h>

#include "aperiodic/json.hpp"
#include "aperiodic/requests.hpp"
#include "base/error.hpp"
#include "base/signals.hpp"
#include "cli/cmd_aperiodic.hpp"

namespace tilekit::cli {

namespace {

struct VerifyArgs {
  VerifyRequest req;
  RunOptions run;
  bool quiet = false;
  bool stats = false;  // --stats: the torus searches' engine counters
};

void print_verify(const VerifyReport& rep) {
  const VerifyResult& r = rep.result;
  const TileSet& set = rep.set;
  if (!rep.repeated.empty()) fmt::print("{}\n", repeated_text(rep.repeated));
  fmt::print("{} ({} {} tiles, {} colours): {}{}\n", set.name(), set.size(), kind_name(set.kind()), set.colours(), r.verdict,
             r.route.empty() ? "" : fmt::format(" (by the {} route)", r.route));
  if (r.period) {
    fmt::print("witness: {} x {} torus (tile numbers as in `tileset show`){}:\n", r.period->first, r.period->second,
               r.witness_validated ? ", checked by the validator" : ", checked edge by edge (indices overflow)");
    if (r.period->first * r.period->second <= 400)
      for (auto& row : r.witness) fmt::print("  {}\n", fmt::join(row, " "));
    else
      fmt::print("  ({} cells; --json prints them)\n", r.period->first * r.period->second);
  }
  if (const auto& d = r.transducer) {
    if (d->verdict == "finite") {
      fmt::print("proof: T^{} of the {} is empty (no infinite strip of {} {}), so no square larger than {} is tileable\n",
                 d->k, d->direction, d->k, d->direction,
                 d->square_bound ? fmt::format("{}", *d->square_bound)
                                 : fmt::format("about 10^{:.1f} (the bound overflows 64 bits)", d->square_bound_log10));
    } else if (d->verdict == "periodic") {
      fmt::print("found at k = {} ({}), strips stacked with shift {}\n", d->k, d->direction, d->shift);
    } else {
      fmt::print("transducer: unknown at k = {} (rows) / {} (columns), stopped by {}: no periodic tiling has a vertical "
                 "period <= {} or a horizontal period <= {}\n",
                 d->k_rows, d->k_columns, d->stopped_by.empty() ? "nothing" : d->stopped_by, d->k_rows, d->k_columns);
    }
    if (!d->levels.empty()) {
      fmt::print("levels (k, direction: states / transitions, seconds):");
      for (std::size_t i = 0; i < d->levels.size(); ++i)
        fmt::print("{}{} {}: {}/{} {:.3f}s", i % 4 == 0 ? "\n  " : ", ", d->levels[i].k, d->levels[i].direction,
                   d->levels[i].states, d->levels[i].transitions, d->levels[i].seconds);
      fmt::print("\n");
    }
    if (d->checkpoints > 0) fmt::print("{} checkpoint(s) written\n", d->checkpoints);
  }
  if (!r.torus_verdict.empty()) {
    if (r.largest_square >= 0) fmt::print("largest tileable square searched: {} x {}\n", r.largest_square, r.largest_square);
    fmt::print("torus: {}; {} shapes ruled out by the row filter, {} searched ({} incomplete), {} nodes, {} threads\n",
               r.torus_verdict, r.shapes_excluded, r.shapes_searched, r.shapes_incomplete, r.nodes, r.threads);
  }
  fmt::print("{:.2f} s\n", r.seconds);
}

void run_verify_command(const VerifyArgs& a, const Context& ctx) {
  VerifyRequest req = a.req;
  if (req.options.route == "torus" && (!a.run.checkpoint.empty() || !a.run.resume.empty()))
    throw InputError("--checkpoint and --resume belong to the transducer route; the torus route keeps no checkpoint");
  apply_verify_run(a.run, req.options);
  req.options.progress = !a.quiet;
  req.options.decide.catch_signals = true;
  VerifyReport rep = run_verify(req);
  const VerifyResult& r = rep.result;
  nlohmann::json j = verify_json(r);
  j["set"] = rep.set.name();
  j["kind"] = std::string(kind_name(rep.set.kind()));
  j["tiles"] = rep.set.size();
  j["colors"] = rep.set.colours();
  j["time_limit"] = req.options.time_limit;
  j["max_period"] = req.options.max_period;
  j["max_square"] = req.options.max_square;
  if (!rep.repeated.empty()) {
    nlohmann::json rj = nlohmann::json::array();
    for (const RepeatedTile& t : rep.repeated) rj.push_back({{"where", t.where}, {"repeats", t.first}, {"colours", t.colours}});
    j["repeated_tiles"] = rj;
  }
  if (rep.pruned) j["pruned"] = prune_json(*rep.pruned, req.prune);
  if (!req.db.empty()) j["run_id"] = rep.run_id, j["db"] = req.db;
  if (a.stats) j["stats"] = r.stats;
  emit(ctx, j, [&] { print_verify(rep); });
  if (a.stats && !ctx.json) fmt::print(stderr, "{}", stats_table(r.stats));
  if (r.interrupted) {
    const std::string& ck = req.options.decide.checkpoint_path;
    const bool kept = r.transducer && r.transducer->checkpoints > 0;
    throw Interrupted(interrupted_message(
        r.signal, kept ? "checkpoint written to " + ck + " (continue with --resume " + ck + ")"
                       : std::string(ck.empty() ? "nothing kept (use --checkpoint F to resume the transducer route)"
                                                : "nothing kept (no checkpoint had been written yet)")));
  }
}

}  // namespace

void add_aperiodic_verify_command(CLI::App* ap, Context& ctx) {
  auto* cmd = ap->add_subcommand(
      "verify", "Decide a tile set: periodic (validated witness), finite (no large square), or unknown at the k reached");
  auto a = std::make_shared<VerifyArgs>();
  cmd->add_option("SET", a->req.set, "Built-in name or tile-set file (Wang or corner; repeated tiles are dropped)")
      ->required();
  add_verify_flags(cmd, a->req.options, a->run, true);  // checkpoints: the transducer route's
  cmd->add_option("--prune", a->req.prune, "Verify the set pruned to radius R (aperiodic/prune.hpp)");
  cmd->add_option("--db", a->req.db, "Store the run, the tile set and the witness in this results database");
  cmd->add_flag("--quiet", a->quiet, "No progress output on stderr");
  cmd->add_flag("--stats", a->stats,
                "Print the torus searches' engine statistics (nodes, decisions, propagations, prunes per rule, time "
                "per phase): a table on stderr, or a \"stats\" object with --json");
  add_json_flag(cmd, ctx);
  cmd->footer(
      "Exit codes: 0 ok (whatever the verdict), 2 bad input or checkpoint, 3 interrupted (checkpoint written with "
      "--checkpoint).");
  cmd->callback([a, &ctx] { run_verify_command(*a, ctx); });
}

}  // namespace tilekit::cli
