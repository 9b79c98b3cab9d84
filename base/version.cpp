#include "base/version.hpp"

#include <fmt/format.h>

namespace tilekit {

std::string version_line() {
  return fmt::format("{} (commit {})", version(), git_commit());
}

}  // namespace tilekit
