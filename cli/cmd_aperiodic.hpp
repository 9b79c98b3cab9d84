#pragma once
// Shared pieces of the `tilekit aperiodic` subcommands (cmd_aperiodic*.cpp).
#include <nlohmann/json.hpp>
#include <string>

#include "aperiodic/verify.hpp"
#include "cli/command.hpp"
#include "aperiodic/convert.hpp"
#include "aperiodic/prune.hpp"

namespace tilekit::cli {

// {kind, tiles, colors, horizontal_colors, vertical_colors, method, source, soundness,
//  argument[, white, black]}
nlohmann::json conversion_json(const Conversion& c, const std::string& source_name);
nlohmann::json prune_json(const PruneReport& r, int radius);

nlohmann::json verify_json(const VerifyResult& r);

void add_aperiodic_table_command(CLI::App* aperiodic, Context& ctx);
void add_aperiodic_verify_command(CLI::App* aperiodic, Context& ctx);

}  // namespace tilekit::cli
