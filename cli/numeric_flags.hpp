#pragma once
// The one parser of every numeric flag. CLI11 converts numbers with strtoll/strtoull/strtold,
// which accept what a flag must not: "nan", "inf", 1e400 (as inf), 18446744073709551616 (as
// 2^64-1, saturated), -1 for an unsigned value (as 2^64-1), "010" (as octal 8), "0x10" and
// leading spaces. check_numeric_flags() walks every option of every command once they are all
// registered (cli/main.cpp) and puts a strict parse in front of CLI11's on each option whose
// value is a number (CLI11's type names INT, UINT and FLOAT): decimal only, no trailing text,
// integers within 64 bits (and no sign for unsigned ones), floating-point values finite. The
// refusal is a CLI11 validation error naming the flag (exit 2). A flag's own range (a positive
// size, seconds >= 0) is still its own check, next to the flag.
#include <CLI/CLI.hpp>
#include <string>

namespace tilekit::cli {

// Adds the strict parse to every numeric option of `app` and of its subcommands, recursively.
void check_numeric_flags(CLI::App& app);

// The strict parse alone: "" when `text` is a valid value of `type` ("INT", "UINT" or "FLOAT"),
// else why not; integers are rewritten to plain decimal (so "010" is ten for CLI11 too).
std::string strict_number(std::string& text, const std::string& type);

// A text flag that may not be empty (an empty --density-expr is a mistake, not "none").
const CLI::Validator& non_empty_text();

// A number > 0 (a size, a scale): CLI::PositiveNumber's check with a message a user can read.
const CLI::Validator& positive_number();

// Seconds: a finite number >= 0 (NaN and inf are refused by the strict parse already).
const CLI::Validator& non_negative_seconds();

}  // namespace tilekit::cli
