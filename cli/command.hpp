#pragma once
// Shared pieces of the `tilekit` commands: the --json switch and one way to print results.
#include <CLI/CLI.hpp>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

namespace tilekit::cli {

// Thrown after the result was printed, to end with a given exit code and no extra message.
struct Exit {
  int code;
};

struct Context {
  bool json = false;   // print exactly one JSON object on stdout instead of human output
  bool quiet = false;  // no progress on stderr (commands with a --quiet of their own keep it in their args)
};

// Prints `j` (with --json) or runs `human`.
void emit(const Context& ctx, const nlohmann::json& j, const std::function<void()>& human);

// Adds the --json flag to a (sub)command, and --quiet (into ctx.quiet) unless it has one of its
// own: every command takes both (tests/cli/test_cli_contract.cpp walks every --help).
void add_json_flag(CLI::App* cmd, Context& ctx);

// Command groups, one per cmd_*.cpp.
void add_tileset_commands(CLI::App& app, Context& ctx);
void add_check_command(CLI::App& app, Context& ctx);
void add_pack_command(CLI::App& app, Context& ctx);
void add_db_commands(CLI::App& app, Context& ctx);
// `db smallest` and `db chains` (cmd_db_chains.cpp), added by add_db_commands.
void add_db_chain_commands(CLI::App& db, Context& ctx);
void add_atlas_commands(CLI::App& app, Context& ctx);
void add_tile_command(CLI::App& app, Context& ctx);
void add_analyze_commands(CLI::App& app, Context& ctx);
void add_aperiodic_commands(CLI::App& app, Context& ctx);
void add_cluster_commands(CLI::App& app, Context& ctx);
void add_points_commands(CLI::App& app, Context& ctx);
void add_texture_commands(CLI::App& app, Context& ctx);
void add_tiled_commands(CLI::App& app, Context& ctx);  // cmd_tiled.cpp: `tiled tileset|map|import`
void add_fill_command(CLI::App& app, Context& ctx);    // cmd_fill.cpp: `fill`

}  // namespace tilekit::cli
