// tilekit aperiodic convert: the thesis ch. 8 constructions (aperiodic/conversion.hpp), and the
// registration of the `aperiodic` subcommands.
#include "cli/cmd_aperiodic.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "aperiodic/json.hpp"
#include "aperiodic/requests.hpp"
#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "cli/command.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit::cli {

void add_verify_flags(CLI::App* cmd, VerifyOptions& o, RunOptions& run, bool checkpoints) {
  // The time limit is checked by verify_tile_set (also for library callers): a negative or
  // non-finite limit is exit 2.
  run.time_limit = o.time_limit;
  run.checkpoint_every = o.decide.checkpoint_every;
  add_run_options(cmd,
                  checkpoints ? RunOptionFlags::Threads | RunOptionFlags::TimeLimit | RunOptionFlags::Checkpoint
                              : RunOptionFlags::Threads | RunOptionFlags::TimeLimit,
                  run);
  cmd->add_option("--route", o.route,
                  "auto (transducer, then torus if time is left) | transducer | torus | both (cross-checked)");
  cmd->add_option("--max-k", o.decide.max_k, "transducer: stop after T^k in each direction (default: no bound)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--no-merge", [&o](std::int64_t) { o.decide.merge = false; },
                "transducer: trim only, no bisimulation merges (for comparison)");
  cmd->add_option_function<std::string>(
      "--direction",
      [&o](const std::string& d) {
        if (d != "rows" && d != "columns" && d != "both") throw CLI::ValidationError("--direction", "rows, columns or both");
        o.decide.rows = d != "columns";
        o.decide.columns = d != "rows";
      },
      "transducer: strips of rows, of columns, or both (default)");
  cmd->add_option("--memory-limit", o.decide.memory_limit, "transducer: bytes for the transducers (default: half the RAM)");
  cmd->add_option("--max-period", o.max_period, "torus: largest period in each direction (default 8)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--max-square", o.max_square, "torus: also search an N x N square (0 = none)")
      ->check(CLI::NonNegativeNumber);
}

void apply_verify_run(const RunOptions& run, VerifyOptions& o) {
  run.check_seconds();
  o.threads = run.resolved_threads();
  o.time_limit = run.time_limit;
  o.decide.checkpoint_path = run.checkpoint;
  o.decide.checkpoint_every = run.checkpoint_every;
  o.decide.resume_path = run.resume;
}

std::string check_command(const LinkDerivation& d) {
  if (d.steps.empty()) return fmt::format("tilekit tileset show {} --json", d.source);
  return fmt::format("tilekit aperiodic link {} --steps {} --json", d.source, fmt::join(d.steps, ","));
}

std::string enumerate_command(const EnumerateOptions& o) {
  std::string cmd = "tilekit aperiodic enumerate";
  for (const std::string& s : o.sources) cmd += " --source " + s;
  cmd += fmt::format(" --max-depth {} --max-tiles {}", o.max_depth, o.max_tiles);
  const EnumerateOptions d;
  if (o.batch != d.batch) cmd += fmt::format(" --batch {}", o.batch);
  if (o.lead_max_k != d.lead_max_k) cmd += fmt::format(" --lead-max-k {}", o.lead_max_k);
  if (o.shard.count > 1) cmd += fmt::format(" --shard {}/{}", o.shard.index, o.shard.count);
  if (!o.operations.empty()) cmd += fmt::format(" --operations {}", fmt::join(o.operations, ","));
  return cmd;
}

std::string repeated_text(const std::vector<RepeatedTile>& r) {
  if (r.empty()) return {};
  std::vector<std::string> parts;
  for (std::size_t i = 0; i < r.size() && i < 5; ++i) parts.push_back(fmt::format("{} repeats tile {}", r[i].where, r[i].first + 1));
  if (r.size() > 5) parts.push_back("...");
  return fmt::format("{} repeated tile{} dropped ({})", r.size(), r.size() == 1 ? "" : "s", fmt::join(parts, ", "));
}

namespace {

struct ConvertArgs {
  std::string set, method, out, db;
  int prune = -1;
  int verify = 0;
  bool merge_centres = false, star_edge = false, list = false;
  VerifyOptions vo;
  RunOptions run;
};

void run_convert_command(const ConvertArgs& a, const Context& ctx) {
  ConvertRequest req;
  req.set = a.set;
  req.spec = {parse_method(a.method), {a.merge_centres, a.star_edge}, a.prune};
  req.verify = a.verify > 0;
  req.verify_options = a.vo;
  apply_verify_run(a.run, req.verify_options);
  if (a.verify > 0) req.verify_options.max_period = a.verify;
  req.db = a.db;
  // The tile-set file first, the database last (cli/io_policy.hpp).
  if (!a.out.empty())
    req.before_store = [&a](const ConvertReport& r) {
      write_file_atomic(a.out, format_tile_set_text(r.conversion.set));
    };
  ConvertReport rep = run_convert(req);
  const LabelledConversion& c = rep.conversion;
  nlohmann::json j = conversion_json(c, rep.source.name());
  if (rep.verify) j["verify"] = verify_json(*rep.verify);
  if (!rep.repeated.empty()) j["repeated_tiles"] = rep.repeated.size();
  if (a.list) {
    nlohmann::json list = nlohmann::json::array();
    for (std::size_t k = 0; k < c.set.size(); ++k) list.push_back(c.set.file_colours(k));
    j["list"] = list;
  }
  if (!a.out.empty()) j["out"] = a.out;
  if (!a.db.empty()) j["conversion_id"] = rep.conversion_id, j["db"] = a.db;
  emit(ctx, j, [&] {
    if (!rep.repeated.empty()) fmt::print("{}\n", repeated_text(rep.repeated));
    fmt::print("{} of {}: {} {} tiles, {} colours", a.method, rep.source.name(), c.set.size(), kind_name(c.set.kind()),
               c.set.colours());
    if (c.spec.method == ConversionMethod::Rotation) fmt::print(" ({} white + {} black)", c.conversion.white, c.conversion.black);
    fmt::print("\nsoundness: {} ({})\n", soundness_name(c.soundness), c.argument);
    if (c.pruned)
      fmt::print("pruned (radius {}): {} -> {} tiles ({} by surround, {} by transducer SCC)\n", a.prune, c.pruned->before,
                 c.pruned->after, c.pruned->removed_by_surround, c.pruned->removed_by_scc);
    if (rep.verify) fmt::print("verify: {} (route {})\n", rep.verify->verdict, rep.verify->route.empty() ? "none" : rep.verify->route);
    if (!a.out.empty()) fmt::print("written to {}\n", a.out);
    if (a.list) fmt::print("{}", format_tile_set_text(c.set));
  });
}

}  // namespace

void add_aperiodic_commands(CLI::App& app, Context& ctx) {
  auto* ap = app.add_subcommand("aperiodic", "Aperiodic tile sets: thesis ch. 8 conversions, tables, verification");
  ap->require_subcommand(1);

  auto* conv = ap->add_subcommand("convert", "Convert a Wang set to a corner set (or back) by a thesis ch. 8 method");
  auto a = std::make_shared<ConvertArgs>();
  conv->add_option("SET", a->set, "Built-in name or tile-set file")->required();
  conv->add_option(
          "--method", a->method,
          "diagonal (8.3.1) | horizontal | vertical (8.3.2) | rotation (8.3.3) | subdivision (8.3.4) | to-wang (8.4)")
      ->required();
  conv->add_option("--prune", a->prune, "Prune the result: surround radius R, then transducer SCCs (R >= 0)");
  conv->add_flag("--merge-centres", a->merge_centres, "subdivision: merge centre colours where provably sound");
  conv->add_flag("--star-edge-colour", a->star_edge, "subdivision: reuse an edge colour as the star (unverified)");
  conv->add_flag("--list", a->list, "Include the result's tiles");
  conv->add_option("--out", a->out, "Write the result as a tile-set file (atomically)");
  conv->add_option("--verify", a->verify,
                   "Also verify the result (label periodic if a witness turns up); the value is the torus route's "
                   "--max-period")
      ->check(CLI::PositiveNumber);
  add_verify_flags(conv, a->vo, a->run, false);
  conv->add_option("--db", a->db, "Store source, result and conversion in this results database");
  add_json_flag(conv, ctx);
  conv->callback([a, &ctx] { run_convert_command(*a, ctx); });

  add_aperiodic_table_command(ap, ctx);
  add_aperiodic_verify_command(ap, ctx);
  add_aperiodic_enumerate_commands(ap, ctx);
  add_aperiodic_certificate_commands(ap, ctx);
}

}  // namespace tilekit::cli
