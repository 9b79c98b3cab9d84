#pragma once
// Errors a user can act on. The CLI maps each to one line on stderr and an exit code
// (the same for every command, docs/ARCHITECTURE.md): InputError -> 2, NotFound -> 1,
// Interrupted -> 3.
#include <stdexcept>
#include <string>

namespace tilekit {

// Bad input: malformed file, impossible parameter, corrupt checkpoint. Exit code 2.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The asked-for thing does not exist (no solution, unknown id). Exit code 1.
struct NotFound : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A long run stopped by a signal after writing its checkpoint. Exit code 3.
struct Interrupted : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace tilekit
