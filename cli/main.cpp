// tilekit: Wang tiles and corner tiles, tile packings, aperiodic sets.
// Exit codes (docs/ARCHITECTURE.md): 0 ok, 1 not found, 2 bad input, 3 interrupted by a signal
// (after its checkpoint, where the job has one).
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <string_view>

#include "base/error.hpp"
#include "base/signals.hpp"
#include "base/temp_files.hpp"
#include "base/version.hpp"
#include "cli/command.hpp"
#include "cli/flag_terms.hpp"
#include "cli/io_policy.hpp"
#include "cli/numeric_flags.hpp"

namespace {

// The long jobs, which run on the run control (base/run_control.hpp, base/signals.hpp): on
// SIGTERM, SIGINT or SIGUSR1 each writes its checkpoint where it has one, removes its temporary
// files and exits 3 with one line saying what was kept.
bool is_long_job(std::string_view cmd, std::string_view sub) {
  return cmd == "pack" || (cmd == "aperiodic" && (sub == "enumerate" || sub == "verify")) ||
         (cmd == "points" && (sub == "tiles" || sub == "generate")) ||
         (cmd == "texture" && (sub == "tiles" || sub == "terrain")) || cmd == "fill";
}

// Signals are caught before anything else, so that no signal finds the default handler,
// however early or late it comes. The other commands exit 3 on SIGTERM or SIGINT after removing
// their temporary files (base/signals.hpp exit_on_signal_after_cleanup).
void catch_signals_of_long_jobs(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (argv[i][0] != '-') {
      const std::string_view cmd = argv[i], sub = i + 1 < argc ? argv[i + 1] : "";
      if (is_long_job(cmd, sub))
        tilekit::SignalCatcher::catch_for_process();
      else  // the others end at once, without their temporary files
        tilekit::exit_on_signal_after_cleanup();
      return;
    }
}

// Ends with `code` after removing the temporary files a failed or interrupted job left registered,
// and, on a refusal or an internal error, a database the run created (cli/io_policy.hpp).
int fail(int code) {
  tilekit::TempFiles::remove_all();
  if (code == 2 || code == 4) tilekit::cli::undo_created_databases();
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace tilekit;
  catch_signals_of_long_jobs(argc, argv);
  cli::Context ctx;
  CLI::App app{"tilekit: Wang and corner tiles, tile packings, tilings and aperiodic tile sets", "tilekit"};
  app.set_version_flag("--version", "tilekit " + version_line());
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 ok, 1 not found, 2 bad input, 3 interrupted by SIGTERM, SIGINT or SIGUSR1 (after its "
      "checkpoint, where the job has one).\n"
      "Run `tilekit COMMAND --help` for a command's options.");
  cli::add_tileset_commands(app, ctx);
  cli::add_check_command(app, ctx);
  cli::add_pack_command(app, ctx);
  cli::add_db_commands(app, ctx);
  cli::add_atlas_commands(app, ctx);
  cli::add_tile_command(app, ctx);
  cli::add_analyze_commands(app, ctx);
  cli::add_aperiodic_commands(app, ctx);
  cli::add_cluster_commands(app, ctx);
  cli::add_points_commands(app, ctx);
  cli::add_texture_commands(app, ctx);
  cli::add_tiled_commands(app, ctx);
  cli::add_fill_command(app, ctx);
  cli::install_io_policy(app);  // outputs checked against inputs and the file system before any work
  cli::check_numeric_flags(app);  // every numeric flag through one strict parse (cli/numeric_flags.hpp)
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const cli::Exit& e) {
    return fail(e.code);
  } catch (const CLI::ParseError& e) {
    std::cerr << "tilekit: " << e.what() << " (see --help)" << std::endl;
    return 2;
  } catch (const RequestError& e) {  // a library's words for a field: the flag's here
    std::cerr << "tilekit: " << cli::in_flag_terms(e) << std::endl;
    return fail(2);
  } catch (const InputError& e) {
    std::cerr << "tilekit: " << e.what() << std::endl;
    return fail(2);
  } catch (const NotFound& e) {
    std::cerr << "tilekit: " << cli::in_flag_terms(std::string_view(e.what())) << std::endl;
    return fail(1);
  } catch (const Interrupted& e) {
    std::cerr << "tilekit: " << e.what() << std::endl;
    return fail(3);
  } catch (const std::filesystem::filesystem_error& e) {
    // A file or folder the system refuses (permissions, a link loop, a full disk): the user's to
    // fix, like any other bad input.
    std::cerr << "tilekit: " << e.what() << std::endl;
    return fail(2);
  } catch (const std::exception& e) {
    std::cerr << "tilekit: internal error: " << e.what() << std::endl;
    return fail(4);
  }
  return 0;
}
