// tilekit fill --set SET [--size WxH] [--torus] [--subset S] [--cells F|MAP.tmx] [--weight T=W ...] [run options]
//              [--png F] [--map-json F] [--tiled DIR]
// A W x H map filled from any tile set with adjacency rules (a Tilekit set, a Tiled Wang set,
// a WFC simple tiled model) by the engine's fill model (tilemap/fill_job.hpp).
#include <fmt/format.h>

#include <memory>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "base/hash.hpp"
#include "base/parse.hpp"
#include "base/signals.hpp"
#include "cli/command.hpp"
#include "cli/run_options.hpp"
#include "tilemap/fill_job.hpp"

namespace tilekit::cli {

namespace {

struct FillArgs {
  std::string set, subset, wangset, size, cells, png, map_json, tiled;
  std::vector<std::string> weights;
  bool torus = false, cover = false, sat = false;
  std::string cnf, order = "auto";
  int block = 0, tile_px = 16;
  std::uint64_t dives = 64;
  RunOptions run;
};

std::vector<std::pair<std::string, double>> parse_weights(const std::vector<std::string>& ws) {
  std::vector<std::pair<std::string, double>> out;
  for (const std::string& w : ws) {
    const auto eq = w.rfind('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError(fmt::format("--weight \"{}\" is not TILE=W", w.substr(0, 32)));
    const std::string num = w.substr(eq + 1);
    double v = -1;
    try {
      std::size_t used = 0;
      v = std::stod(num, &used);
      if (used != num.size()) v = -1;
    } catch (const std::exception&) {
      v = -1;
    }
    if (!(v > 0) || v > 1e12) throw InputError(fmt::format("--weight {}: a weight is a number > 0", w.substr(0, 32)));
    out.emplace_back(w.substr(0, eq), v);
  }
  return out;
}

std::string window_text(const FillWindow& w) {
  return fmt::format("{}x{} cells at column {}, row {}", w.cols, w.rows, w.col, w.row);
}

nlohmann::json fill_json(const FillArgs& a, const tilemap::FillJobOutcome& o) {
  const FillMapOutcome& f = o.fill;
  nlohmann::json j = {{"set", a.set},          {"source", o.source},      {"subset", a.subset},
                      {"found", f.found},      {"valid", o.valid},        {"torus", a.torus},
                      {"size", fmt::format("{}x{}", o.cols, o.rows)},        {"seed", a.run.seed},      {"tiles", o.names.size()},
                      {"fixed", o.fixed},      {"blocks", f.blocks},      {"grown", f.grown},
                      {"nodes", f.nodes},      {"restarts", f.restarts},  {"seconds", f.seconds},
                      {"resumed", f.resumed},  {"checkpoints", f.checkpoints},
                      {"interrupted", f.interrupted}, {"timed_out", f.timed_out},
                      {"method", a.sat ? "sat" : "search"}, {"order", a.order}};
  if (!f.found)
    j["region"] = {{"row", f.window.row}, {"col", f.window.col}, {"rows", f.window.rows}, {"cols", f.window.cols},
                   {"proved", f.proved_impossible}};
  if (f.found) {
    StableHash h;  // the map's identity: equal maps, equal hashes (a resumed run against a whole one)
    for (int t : f.map) h.add(std::uint64_t(t), 4);
    j["map_hash"] = fmt::format("{:016x}", h.mixed());
    nlohmann::json freq = nlohmann::json::array();
    for (std::size_t t = 0; t < o.names.size(); ++t)
      freq.push_back({{"tile", o.names[t]}, {"weight", o.weights[t]}, {"cells", o.counts[t]}});
    j["frequencies"] = std::move(freq);
  }
  for (auto [key, path] : {std::pair{"png", o.png}, {"map_json", o.json}, {"tmx", o.tmx}, {"tsx", o.tsx}})
    if (!path.empty()) j[key] = path;
  return j;
}

void run_fill_cmd(const FillArgs& a, const CLI::App& cmd, const Context& ctx) {
  tilemap::FillJobRequest req;
  if (!a.size.empty()) {  // else the painted map's size (the library refuses a cells file without --size)
    const Dimensions d = parse_dimensions(a.size, 1 << 15, std::int64_t(1) << 28, "--size WxH");
    req.width = int(d.first), req.height = int(d.second);
  }
  req.set = a.set, req.subset = a.subset, req.wangset = a.wangset;
  req.torus = a.torus;
  req.cells = a.cells, req.weights = parse_weights(a.weights);
  req.cover = a.cover;
  req.sat = a.sat, req.out_cnf = a.cnf;
  req.order = a.order == "entropy" ? FillOrder::Entropy : a.order == "scanline" ? FillOrder::Scanline : FillOrder::Auto;
  req.block = a.block, req.dives = a.dives, req.tile_px = a.tile_px;
  req.out_png = a.png, req.out_json = a.map_json, req.out_tiled = a.tiled;
  a.run.apply(req.run, cmd);
  req.run.catch_signals = true;
  req.run.progress = !ctx.quiet && !ctx.json;
  const tilemap::FillJobOutcome o = tilemap::run_fill(req);
  if (!o.cnf.empty()) {
    emit(ctx, nlohmann::json{{"set", a.set}, {"size", fmt::format("{}x{}", o.cols, o.rows)}, {"cnf", o.cnf},
                             {"variables", o.cnf_variables}, {"clauses", o.cnf_clauses}, {"fixed", o.fixed}},
         [&] { fmt::print("CNF of the {}x{} fill: {} variables, {} clauses -> {}\n", o.cols, o.rows, o.cnf_variables, o.cnf_clauses, o.cnf); });
    return;
  }
  const FillMapOutcome& f = o.fill;
  emit(ctx, fill_json(a, o), [&] {
    if (f.found)
      fmt::print("{}x{} map of {} ({} tiles), {} fixed cells: filled and valid in {:.3f} s ({} blocks, {} nodes, {} restarts)\n",
                 o.cols, o.rows, a.set, o.names.size(), o.fixed, f.seconds, f.blocks, f.nodes, f.restarts);
    for (const std::string& p : {o.png, o.json, o.tmx})
      if (!p.empty()) fmt::print("  -> {}\n", p);
  });
  if (f.interrupted)
    throw Interrupted(interrupted_message(
        f.signal, a.run.checkpoint.empty() ? std::string("nothing kept (use --checkpoint F to resume later)")
                                           : "checkpoint written to " + a.run.checkpoint + " (continue with --resume " +
                                                 a.run.checkpoint + ")"));
  if (f.found) return;
  if (f.timed_out) throw NotFound(fmt::format("no fill found within --time-limit {} s", a.run.time_limit));
  if (f.proved_impossible)
    throw NotFound("no fill exists: the " + window_text(f.window) + " cannot be completed " +
                   (a.cover ? "holding every tile" : "around its fixed cells") + (a.sat ? " (cadical: UNSATISFIABLE)" : ""));
  throw NotFound("no fill found: the " + window_text(f.window) + " could not be completed (not proved impossible)");
}

}  // namespace

void add_fill_command(CLI::App& app, Context& ctx) {
  auto* cmd = app.add_subcommand("fill",
                                 "Fill a W x H map (torus or bounded) from a tile set with adjacency rules: a Tilekit "
                                 "set, a Tiled Wang set (.tsx) or a WFC simple tiled model (.xml), around fixed cells");
  auto a = std::make_shared<FillArgs>();
  a->run.threads = 1;
  a->run.seed = 1;
  a->run.checkpoint_every = 60;
  cmd->add_option("--set", a->set,
                  "Tile set: a name (complete-corner-3, compact-wang-3, blob-47, ...), a tile-set file, a Tiled .tsx with a "
                  "Wang set, or a WFC .xml (its tile images in the folder of the same name beside it)")
      ->required();
  cmd->add_option("--subset", a->subset, "WFC only: the subset of the .xml to use");
  cmd->add_option("--wangset", a->wangset, "Tiled only: the Wang set to read (default: the first)");
  cmd->add_option("--size", a->size, "Width x height in cells, e.g. 64x48 (default with --cells MAP.tmx: the map's)");
  cmd->add_flag("--torus", a->torus, "Wrap around: the map tiles the plane periodically");
  cmd->add_flag("--cover", a->cover,
                "Every tile of the set at least once (a sheet of the whole set; with --torus and no --cells, tile 0 "
                "sits at the top left); exit 1 with the whole map when none exists");
  cmd->add_option("--cells", a->cells,
                  "Fixed cells: a map painted in Tiled (.tmx; empty cells are filled, painted ones kept), or a text "
                  "file: one line per row, one token per cell, '.' free, else the tile's number or (WFC) its name, "
                  "e.g. corner or corner:1");
  cmd->add_option("--weight", a->weights, "TILE=W: the tile's weight (repeatable; WFC sets take theirs from the XML)");
  cmd->add_option("--block", a->block, "Block side for large maps (0: one block up to 128x128 cells, else 64)")
      ->check(CLI::Range(0, 1 << 15))
      ->capture_default_str();
  cmd->add_option("--dives", a->dives, "Restarts of a block before it grows into its neighbours")
      ->check(CLI::Range(1, 1 << 30))
      ->capture_default_str();
  cmd->add_option("--order", a->order,
                  "Which cell the search fills next: entropy (least entropy of the weights left on the growing "
                  "region's frontier, ties by seeded noise, as WFC: frequencies close to the weights), scanline (fewest "
                  "tiles left, ties in scanline order: faster on large maps), or auto (entropy for a map searched in "
                  "one block, scanline for a map filled in blocks)")
      ->check(CLI::IsMember({"auto", "scanline", "entropy"}))
      ->capture_default_str();
  cmd->add_flag("--sat", a->sat,
                "Decide the whole map with the SAT solver cadical (one run; an UNSAT answer refutes every map of the "
                "request) instead of the fill model's search");
  cmd->add_option("--cnf", a->cnf,
                  "Write the request as DIMACS CNF (variable 1 + cell * tiles + tile) for any SAT solver, and search "
                  "nothing");
  add_run_options(cmd, RunOptionFlags::Threads | RunOptionFlags::Seed | RunOptionFlags::TimeLimit |
                           RunOptionFlags::Checkpoint,
                  a->run);
  cmd->add_option("--png", a->png, "Write the map's picture (WFC: the tiles' own images, as the reference draws them)");
  cmd->add_option("--map-json", a->map_json, "Write the map as JSON: the tile of every cell");
  cmd->add_option("--tiled", a->tiled,
                  "Write a Tiled map (NAME-fill.tmx) and its tileset into this folder (with --cells MAP.tmx: "
                  "MAP-fill.tmx over MAP's own tilesets)");
  cmd->add_option("--tile-px", a->tile_px, "Pixels per tile of built-in pictures")->check(CLI::Range(2, 512))->capture_default_str();
  add_json_flag(cmd, ctx);
  cmd->callback([a, cmd, &ctx] { run_fill_cmd(*a, *cmd, ctx); });
}

}  // namespace tilekit::cli
