#pragma once
// Errors a user can act on. The CLI maps each to one line on stderr and an exit code
// (the same for every command, docs/ARCHITECTURE.md): InputError -> 2, NotFound -> 1,
// Interrupted -> 3.
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace tilekit {

// Bad input: malformed file, impossible parameter, corrupt checkpoint. Exit code 2.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Bad input in a field of a request (a library's options struct): the library knows the field,
// not the flag or the setting that filled it. The message names each field it mentions between
// backquotes by its name in the request ("`shard` must be I/N ..."), and field() is the one at
// fault, so that a caller words it in its own terms: the CLI prints "--shard must be I/N ...".
struct RequestError : InputError {
  RequestError(std::string field, const std::string& message) : InputError(message), field_(std::move(field)) {}
  const std::string& field() const noexcept { return field_; }

 private:
  std::string field_;
};

// Throws `message` as a RequestError about the field `what` names when `what` starts with one
// ("`size` RxS": the field size), else as an InputError. For the shared checks and parsers
// (base/parse.hpp, check_colour_count) whose callers name either a field or a plain thing.
[[noreturn]] inline void throw_input_error(std::string_view what, const std::string& message) {
  if (what.size() > 2 && what.front() == '`') {
    const auto end = what.find('`', 1);
    if (end != std::string_view::npos && end > 1) throw RequestError(std::string(what.substr(1, end - 1)), message);
  }
  throw InputError(message);
}

// The asked-for thing does not exist (no solution, unknown id). Exit code 1. Its message may
// name fields of the request as a RequestError does ("try `method` search").
struct NotFound : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A long run stopped by a signal after writing its checkpoint. Exit code 3.
struct Interrupted : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace tilekit
