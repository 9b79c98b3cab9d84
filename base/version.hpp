#pragma once
// Which build this is: the project version (CMakeLists.txt) and the git commit the build was made
// from. `tilekit --version` prints both, every JSON result carries them and every run stored in
// the results database records them, so a result says which build made it.
#include <string>
#include <string_view>

namespace tilekit {

// "0.1.0": the version of the project (CMake's PROJECT_VERSION).
std::string_view version();

// The commit as `git rev-parse --short=12 HEAD` prints it, with "-dirty" when tracked files differed
// from it at build time; "unknown" for a build from outside a git checkout (a source tarball).
// Written at every build by cmake/version.cmake, so it never lags behind the checkout.
std::string_view git_commit();

// "0.1.0 (commit 8f6dccb1a2b3)": what `tilekit --version` prints after the program name.
std::string version_line();

}  // namespace tilekit
