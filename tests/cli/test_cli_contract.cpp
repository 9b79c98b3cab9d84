// The CLI contract, command by command: `tilekit --help` and every command's --help, walked down
// the "Subcommands:" lists to the leaves. Every help exits 0 and says what the command does; every
// leaf takes --json (exactly one JSON object on stdout) and --quiet (no progress on stderr).
#include <gtest/gtest.h>

#include <sstream>

#include "tests/cli_runner.hpp"

using namespace tilekit::test;

namespace {

// The names listed under "Subcommands:" up to the next blank line.
std::vector<std::string> subcommands(const std::string& help) {
  std::vector<std::string> out;
  std::istringstream in(help);
  bool listing = false;
  for (std::string line; std::getline(in, line);) {
    if (line == "Subcommands:") {
      listing = true;
      continue;
    }
    if (!listing) continue;
    if (line.empty()) break;
    std::istringstream words(line);
    std::string name;
    if (words >> name) out.push_back(name);
  }
  return out;
}

}  // namespace

TEST(CliContract, EveryCommandsHelpWorksAndEveryLeafTakesJsonAndQuiet) {
  std::vector<std::string> todo = {""}, leaves;
  while (!todo.empty()) {
    const std::string path = todo.back();
    todo.pop_back();
    const CliResult r = run_cli(path + " --help");
    SCOPED_TRACE("tilekit" + path + " --help");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    EXPECT_NE(r.out.find("Usage: tilekit" + path), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("Exit codes: 0 ok"), std::string::npos) << r.out;
    const std::vector<std::string> subs = subcommands(r.out);
    if (subs.empty()) {
      leaves.push_back(path);
      EXPECT_NE(r.out.find("--json"), std::string::npos) << r.out;
      EXPECT_NE(r.out.find("--quiet"), std::string::npos) << r.out;
      EXPECT_GT(r.out.find("Usage:"), 0u) << "a leaf opens with what it does: " << r.out;
    }
    for (const std::string& s : subs) todo.push_back(path + " " + s);
  }
  EXPECT_GE(leaves.size(), 30u);  // the walk found the commands (36 when this was written)
}

TEST(CliContract, QuietAndJsonTogetherPrintOnlyTheJsonObject) {
  TempDir d;
  for (const std::string& cmd :
       std::vector<std::string>{"tileset list", "aperiodic convert culik-13 --method diagonal",
                                "texture atlas " + d / "none --out " + d / "a.png", "db stats --db " + d / "r.sqlite",
                                "analyze neighbors --colors 2 --tilings 2 --max-size 64"}) {
    const CliResult r = run_cli(cmd + " --quiet --json");
    SCOPED_TRACE(cmd);
    if (r.code == 0) {
      EXPECT_TRUE(r.err.empty()) << r.err;
      EXPECT_TRUE(r.json().is_object());
    } else {
      // texture atlas of a missing folder (2), db stats of a missing database (1): the flags were accepted
      EXPECT_TRUE(r.code == 1 || r.code == 2) << r.code << " " << r.err;
      EXPECT_EQ(r.err.find("--quiet"), std::string::npos) << r.err;
    }
  }
}
