#include "cli/command.hpp"

#include <fmt/format.h>

#include <iostream>

#include "base/version.hpp"

namespace tilekit::cli {

void emit(const Context& ctx, const nlohmann::json& j, const std::function<void()>& human) {
  if (ctx.json) {
    // Every JSON result says which build made it (base/version.hpp).
    nlohmann::json out = j;
    if (out.is_object()) out["tilekit_version"] = version_line();
    // Stored text from older databases may hold bytes that are not UTF-8: print U+FFFD for
    // them rather than fail (input is UTF-8 only, base/input.hpp).
    std::cout << out.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << std::endl;
  } else {
    human();
    std::cout.flush();
  }
}

void add_json_flag(CLI::App* cmd, Context& ctx) {
  cmd->add_flag("--json", ctx.json, "Print exactly one JSON object on stdout");
}

}  // namespace tilekit::cli
