#include "aperiodic/json.hpp"

#include <fmt/format.h>

namespace tilekit {

nlohmann::json prune_json(const PruneReport& r, int radius) {
  return {{"radius", radius},
          {"before", r.before},
          {"after", r.after},
          {"removed_by_surround", r.removed_by_surround},
          {"removed_by_scc", r.removed_by_scc},
          {"passes", r.passes}};
}

nlohmann::json conversion_json(const LabelledConversion& c, const std::string& source_name) {
  nlohmann::json j = {{"kind", std::string(kind_name(c.set.kind()))},
                      {"tiles", c.set.size()},
                      {"colors", c.set.colours()},
                      {"horizontal_colors", c.set.horizontal_colours()},
                      {"vertical_colors", c.set.vertical_colours()},
                      {"method", method_name(c.spec.method)},
                      {"source", source_name},
                      {"soundness", soundness_name(c.soundness)},
                      {"argument", c.argument}};
  if (c.spec.method == ConversionMethod::Rotation) j["white"] = c.conversion.white, j["black"] = c.conversion.black;
  if (c.pruned) j["pruned"] = prune_json(*c.pruned, c.spec.prune);
  return j;
}

nlohmann::json decide_json(const DecideResult& d) {
  nlohmann::json levels = nlohmann::json::array();
  for (const DecideLevel& l : d.levels)
    levels.push_back({{"k", l.k},
                      {"direction", l.direction},
                      {"states", l.states},
                      {"transitions", l.transitions},
                      {"product_states", l.product_states},
                      {"product_transitions", l.product_transitions},
                      {"components", l.components},
                      {"seconds", l.seconds}});
  nlohmann::json j = {{"verdict", d.verdict},
                      {"direction", d.direction},
                      {"k", d.k},
                      {"k_rows", d.k_rows},
                      {"k_columns", d.k_columns},
                      {"stopped_by", d.stopped_by},
                      {"shift", d.shift},
                      {"levels", levels},
                      {"checkpoints", d.checkpoints},
                      {"resumed", d.resumed},
                      {"interrupted", d.interrupted},
                      {"seconds", d.seconds},
                      {"total_seconds", d.total_seconds}};
  if (d.verdict == "finite") {
    j["square_bound"] = d.square_bound ? nlohmann::json(*d.square_bound) : nlohmann::json();
    j["square_bound_log10"] = d.square_bound_log10;
    if (!d.square_bound)
      j["square_bound_note"] = fmt::format("the bound overflows 64 bits: about 10^{:.1f}", d.square_bound_log10);
  }
  return j;
}

nlohmann::json verify_json(const VerifyResult& r) {
  nlohmann::json j = {{"verdict", r.verdict},
                      {"route", r.route},
                      {"period", r.period ? nlohmann::json::array({r.period->first, r.period->second}) : nlohmann::json()},
                      {"witness", r.witness},
                      {"witness_validated", r.witness_validated},
                      {"torus_verdict", r.torus_verdict},
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
                      {"interrupted", r.interrupted},
                      {"seconds", r.seconds}};
  if (r.transducer) {
    j["transducer"] = decide_json(*r.transducer);
    j["k"] = r.transducer->k;
    if (r.transducer->verdict == "finite") {
      j["square_bound"] = j["transducer"]["square_bound"];
      if (j["transducer"].contains("square_bound_note")) j["square_bound_note"] = j["transducer"]["square_bound_note"];
    }
  }
  return j;
}

}  // namespace tilekit
