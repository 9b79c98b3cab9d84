#pragma once
// The JSON forms of aperiodic-engine results: what `tilekit aperiodic ... --json` prints and what
// the results database keeps in its details columns (one format for both).
#include <nlohmann/json.hpp>
#include <string>

#include "aperiodic/conversion.hpp"
#include "aperiodic/decide.hpp"
#include "aperiodic/prune.hpp"
#include "aperiodic/verify.hpp"

namespace tilekit {

// {kind, tiles, colors, horizontal_colors, vertical_colors, method, source, soundness,
//  argument[, white, black][, pruned]}
nlohmann::json conversion_json(const LabelledConversion& c, const std::string& source_name);
nlohmann::json prune_json(const PruneReport& r, int radius);
// {verdict, direction, k, k_rows, k_columns, stopped_by, square_bound, square_bound_log10,
//  [square_bound_note], shift, levels: [...], checkpoints, resumed, interrupted, seconds, total_seconds}
nlohmann::json decide_json(const DecideResult& d);
// {verdict, route, period, witness, witness_validated, transducer, torus_verdict, largest_square,
//  nodes, shapes_*, periodic_rows/cols, excluded_*_periods, threads, seconds}
nlohmann::json verify_json(const VerifyResult& r);

}  // namespace tilekit
