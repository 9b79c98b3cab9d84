#pragma once
// Inputs and outputs as one policy (base/io_paths.hpp), wired once for every command: each
// command's files are declared here by flag (kRules in io_policy.cpp), and before the command
// runs its outputs are checked against its inputs and the file system. A refused command (exit 2)
// has changed nothing: an output over an input, an output in a missing or read-only folder and
// a database in one are all found before any work, and a database the refused run created is
// removed again.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "base/io_paths.hpp"

namespace tilekit::cli {

// The declared files of the leaf command `cmd` ("texture tiles"), from its options' values.
std::vector<IoPath> declared_paths(const CLI::App& leaf, const std::string& cmd);

// Checks the parsed command's files before its callback runs (a parse-complete callback on `app`).
void install_io_policy(CLI::App& app);

// On a refused run (exit 2 or 4): removes the databases it was to store into that did not exist
// before it and hold nothing stored (a refused command creates no database; one another process
// made and filled meanwhile stays).
void undo_created_databases();

}  // namespace tilekit::cli
