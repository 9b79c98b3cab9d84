// tilekit aperiodic convert | table | verify: the thesis ch. 8 constructions, the recomputed
// Tables 8.1-8.7 and the periodicity search.
#include <fmt/format.h>

#include "base/atomic_file.hpp"
#include "aperiodic/store.hpp"
#include "cli/cmd_aperiodic.hpp"
#include "cli/command.hpp"
#include "aperiodic/convert.hpp"
#include "aperiodic/prune.hpp"
#include "base/error.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit::cli {

nlohmann::json conversion_json(const Conversion& c, const std::string& source_name) {
  nlohmann::json j = {{"kind", std::string(kind_name(c.kind))},
                      {"tiles", c.size()},
                      {"colors", c.colours},
                      {"horizontal_colors", c.horizontal_colours},
                      {"vertical_colors", c.vertical_colours},
                      {"method", method_name(c.method)},
                      {"source", source_name},
                      {"soundness", soundness_name(c.soundness)},
                      {"argument", c.argument}};
  if (c.method == ConversionMethod::Rotation) j["white"] = c.white, j["black"] = c.black;
  return j;
}

nlohmann::json prune_json(const PruneReport& r, int radius) {
  return {{"radius", radius},
          {"before", r.before},
          {"after", r.after},
          {"removed_by_surround", r.removed_by_surround},
          {"removed_by_scc", r.removed_by_scc},
          {"passes", r.passes}};
}

namespace {

struct ConvertArgs {
  std::string set, method, out, db;
  int prune = -1, verify = 0;
  bool merge_centres = false, star_edge = false, list = false;
};

void run_convert(const Context& ctx, const ConvertArgs& a) {
  TileSet src = resolve_tile_set(a.set);
  if (src.empty()) throw InputError(fmt::format("tile set '{}' has no tiles", a.set));
  ConversionMethod m = parse_method(a.method);
  Conversion conv = convert(src, m, {a.merge_centres, a.star_edge});
  nlohmann::json j = conversion_json(conv, src.name());
  std::optional<TileSet> result;
  if (a.prune >= 0 || !a.out.empty() || a.list || !a.db.empty() || a.verify > 0) {
    result = conversion_tile_set(conv, src.name() + "-" + a.method, fmt::format("{} of {} (thesis 8.3/8.4)", a.method, src.name()));
  }
  if (a.prune >= 0) {
    PruneReport rep;
    result = prune(*result, a.prune, &rep);
    j["pruned"] = prune_json(rep, a.prune);
    j["tiles"] = result->size();
    j["colors"] = result->colours();
    j["horizontal_colors"] = result->horizontal_colours();
    j["vertical_colors"] = result->vertical_colours();
    std::string why;
    Soundness sp = after_pruning(pruned_soundness(src.wang_tiles(), conv, result->corner_tiles(), &why), rep);
    if (why.empty() && sp != conv.soundness) why = "pruning removed tiles outside the transducer SCCs: tilings still lift";
    if (sp != conv.soundness) {
      j["soundness"] = soundness_name(sp);
      j["argument"] = why;
      conv.argument = why;
    }
  }
  if (a.verify > 0) {
    // A periodic tiling found by the search overrides any other label (DESIGN.md).
    VerifyOptions vo;
    vo.max_period = a.verify;
    VerifyResult v = verify_tile_set(*result, vo);
    j["verify"] = verify_json(v);
    if (v.period) {
      j["soundness"] = soundness_name(Soundness::Periodic);
      j["argument"] = fmt::format("a {}x{} torus tiling was found", v.period->first, v.period->second);
      conv.argument = j["argument"].get<std::string>();
    }
  }
  if (a.list) {
    nlohmann::json list = nlohmann::json::array();
    for (std::size_t k = 0; k < result->size(); ++k) list.push_back(result->file_colours(k));
    j["list"] = list;
  }
  if (!a.out.empty()) {
    write_file_atomic(a.out, format_tile_set_text(*result));
    j["out"] = a.out;
  }
  if (!a.db.empty()) {
    ResultsDb db(a.db);
    nlohmann::json details = j;
    details.erase("list");
    j["conversion_id"] = store_conversion(db, src, *result, a.method, j["soundness"].get<std::string>(), details);
    j["db"] = a.db;
  }
  emit(ctx, j, [&] {
    fmt::print("{} of {}: {} {} tiles, {} colours", a.method, src.name(), j["tiles"].get<std::size_t>(),
               j["kind"].get<std::string>(), j["colors"].get<std::uint32_t>());
    if (m == ConversionMethod::Rotation) fmt::print(" ({} white + {} black)", conv.white, conv.black);
    fmt::print("\nsoundness: {} ({})\n", j["soundness"].get<std::string>(), conv.argument);
    if (j.contains("pruned"))
      fmt::print("pruned (radius {}): {} -> {} tiles ({} by surround, {} by transducer SCC)\n", a.prune,
                 j["pruned"]["before"].get<std::size_t>(), j["pruned"]["after"].get<std::size_t>(),
                 j["pruned"]["removed_by_surround"].get<std::size_t>(), j["pruned"]["removed_by_scc"].get<std::size_t>());
    if (j.contains("verify")) fmt::print("verify (max period {}): {}\n", a.verify, j["verify"]["verdict"].get<std::string>());
    if (!a.out.empty()) fmt::print("written to {}\n", a.out);
    if (a.list) fmt::print("{}", format_tile_set_text(*result));
  });
}

}  // namespace

void add_aperiodic_commands(CLI::App& app, Context& ctx) {
  auto* ap = app.add_subcommand("aperiodic", "Aperiodic tile sets: thesis ch. 8 conversions, tables, verification");
  ap->require_subcommand(1);

  auto* conv = ap->add_subcommand("convert", "Convert a Wang set to a corner set (or back) by a thesis ch. 8 method");
  static ConvertArgs ca;
  conv->add_option("SET", ca.set, "Built-in name or tile-set file")->required();
  conv->add_option("--method", ca.method,
                   "diagonal (8.3.1) | horizontal | vertical (8.3.2) | rotation (8.3.3) | subdivision (8.3.4) | to-wang (8.4)")
      ->required();
  conv->add_option("--prune", ca.prune, "Prune the result: surround radius R, then transducer SCCs (R >= 0)");
  conv->add_flag("--merge-centres", ca.merge_centres, "subdivision: merge centre colours where provably sound");
  conv->add_flag("--star-edge-colour", ca.star_edge, "subdivision: reuse an edge colour as the star (unverified)");
  conv->add_flag("--list", ca.list, "Include the result's tiles");
  conv->add_option("--out", ca.out, "Write the result as a tile-set file (atomically)");
  conv->add_option("--verify", ca.verify, "Also run verify on the result up to this period (label periodic if found)")
      ->check(CLI::Range(1, 64));
  conv->add_option("--db", ca.db, "Store source, result and conversion in this results database");
  add_json_flag(conv, ctx);
  conv->callback([&ctx] { run_convert(ctx, ca); });

  add_aperiodic_table_command(ap, ctx);
  add_aperiodic_verify_command(ap, ctx);
}

}  // namespace tilekit::cli
