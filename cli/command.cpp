#include "cli/command.hpp"

#include <fmt/format.h>

#include <iostream>

namespace tilekit::cli {

void emit(const Context& ctx, const nlohmann::json& j, const std::function<void()>& human) {
  if (ctx.json) {
    std::cout << j.dump() << std::endl;
  } else {
    human();
    std::cout.flush();
  }
}

void add_json_flag(CLI::App* cmd, Context& ctx) {
  cmd->add_flag("--json", ctx.json, "Print exactly one JSON object on stdout");
}

}  // namespace tilekit::cli
