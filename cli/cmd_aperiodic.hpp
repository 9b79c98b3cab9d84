#pragma once
// The `tilekit aperiodic` subcommands (cmd_aperiodic*.cpp): flags in, printing out; the work is
// in aperiodic/requests.hpp, aperiodic/table_checks.hpp and aperiodic/smallest.hpp.
#include "aperiodic/enumerate.hpp"
#include "aperiodic/verify.hpp"
#include "cli/command.hpp"
#include "cli/run_options.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit::cli {

// The flags every command that verifies shares: --route, --max-k, --max-period, --max-square,
// --no-merge, --direction, --memory-limit, and the run options --time-limit (default 10 s, the
// whole run, every route) and --threads (cli/run_options.hpp; with `checkpoints` also
// --checkpoint, --checkpoint-every, --resume of the transducer route) into `run`.
void add_verify_flags(CLI::App* cmd, VerifyOptions& o, RunOptions& run, bool checkpoints);
// The run options into `o` (after parsing).
void apply_verify_run(const RunOptions& run, VerifyOptions& o);

// The command that checks a link of a chain: "tilekit aperiodic link SOURCE --steps S1,S2,...
// --json", or "tilekit tileset show SOURCE --json" for the source itself.
std::string check_command(const LinkDerivation& d);

// The command that reruns a search with these options (the flags that change its results),
// which a chain record keeps (aperiodic/smallest.hpp).
std::string enumerate_command(const EnumerateOptions& o);

// "12 repeated tiles dropped (file:3 repeats tile 1, ...)" or "".
std::string repeated_text(const std::vector<RepeatedTile>& r);

void add_aperiodic_table_command(CLI::App* aperiodic, Context& ctx);
void add_aperiodic_verify_command(CLI::App* aperiodic, Context& ctx);
void add_aperiodic_enumerate_commands(CLI::App* aperiodic, Context& ctx);
// `aperiodic certify` and `aperiodic check-certificate` (cmd_aperiodic_certificate.cpp).
void add_aperiodic_certificate_commands(CLI::App* aperiodic, Context& ctx);

}  // namespace tilekit::cli
