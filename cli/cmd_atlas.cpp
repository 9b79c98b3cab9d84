// tilekit atlas lookup|build (placeholder registration filled in below).
#include "cli/command.hpp"

namespace tilekit::cli {
void add_atlas_commands(CLI::App& app, Context& ctx);
}
namespace tilekit::cli { void add_atlas_commands(CLI::App&, Context&) {} }
