// Every numeric flag goes through one strict parse (cli/numeric_flags.hpp): NaN, inf,
// out-of-range values, negative unsigned values and trailing text are exit 2 naming the flag,
// never saturated, wrapped or read as octal; and every evaluation of a density expression is
// checked for finiteness.
#include <gtest/gtest.h>

#include <string>

#include "cli/numeric_flags.hpp"
#include "tests/cli_runner.hpp"

using namespace tilekit;
using namespace tilekit::test;

namespace {

std::string strict(std::string text, const std::string& type) {
  const std::string why = cli::strict_number(text, type);
  return why.empty() ? "ok " + text : why;
}

// Exit 2 with one line naming `flag` (and nothing else on stdout).
void expect_refused(const std::string& args, const std::string& flag) {
  CliResult r = run_cli(args);
  EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
  EXPECT_NE(r.err.find(flag), std::string::npos) << args << "\n" << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
}

}  // namespace

TEST(NumericFlags, TheStrictParseRefusesWhatStrtodAndStrtoullAccept) {
  EXPECT_EQ(strict("42", "INT"), "ok 42");
  EXPECT_EQ(strict("-7", "INT"), "ok -7");
  EXPECT_EQ(strict("010", "INT"), "ok 10");  // decimal, not octal 8
  EXPECT_EQ(strict("18446744073709551615", "UINT"), "ok 18446744073709551615");
  EXPECT_EQ(strict("2.5e3", "FLOAT"), "ok 2.5e3");
  EXPECT_EQ(strict("-0.25", "FLOAT"), "ok -0.25");
  for (const char* bad : {"18446744073709551616", "-1", "0x10", " 5", "5 ", "5x", "", "+3", "1.5"})
    EXPECT_NE(strict(bad, "UINT").rfind("ok", 0), 0u) << bad;
  for (const char* bad : {"9223372036854775808", "-9223372036854775809", "0x10", "1e3", "3.0", "nan"})
    EXPECT_NE(strict(bad, "INT").rfind("ok", 0), 0u) << bad;
  for (const char* bad : {"nan", "NaN", "-nan", "inf", "-inf", "infinity", "1e400", "-1e400", "0x1p3", "1.5s", ""})
    EXPECT_NE(strict(bad, "FLOAT").rfind("ok", 0), 0u) << bad;
}

TEST(NumericFlags, NaNInfAndOutOfRangeValuesAreExit2NamingTheFlag) {
  expect_refused("aperiodic verify kari-14 --checkpoint-every nan", "--checkpoint-every");
  expect_refused("points spectrum --set-points nan", "--set-points");
  expect_refused("points zoneplate --set-points nan", "--set-points");
  for (const char* v : {"-1", "nan", "-inf", "0"})
    expect_refused(std::string("points generate --window 0,0,1,1 --density 10 --base-tile ") + v, "--base-tile");
  expect_refused("points analyze missing.f32 --tile-size nan", "--tile-size");
  expect_refused("points analyze missing.f32 --tile-size -1", "--tile-size");
  expect_refused("aperiodic smallest --time-limit nan", "--time-limit");
  expect_refused("pack --kind corner --colors 2 --time-limit -1", "--time-limit");
  expect_refused("pack --kind corner --colors 2 --seed 18446744073709551616", "--seed");
  expect_refused("pack --kind corner --colors 2 --seed -1", "--seed");
  expect_refused("pack --kind corner --colors 2 --threads 2x", "--threads");
  expect_refused("cluster submit --kind corner --colors 4 --shards 2 --checkpoint-every inf", "--checkpoint-every");
  expect_refused("cluster submit --kind corner --colors 4 --shards 2 --checkpoint-every 1e308", "--checkpoint-every");
  // A value in range still works, and "010" is ten, as everywhere else.
  CliResult r = run_cli("pack --kind corner --colors 2 --seed 010 --json");
  EXPECT_EQ(r.code, 0) << r.err;
}

TEST(NumericFlags, ADensityExpressionThatIsNotFiniteOrIsEmptyIsExit2) {
  for (const char* e : {"exp(1000)", "0/0", "log(-1)", "1/(x-x)"})
    expect_refused(std::string("points generate --method recursive --window 0,0,1,1 --density 10 --density-expr '") +
                       e + "'",
                   "density expression");
  expect_refused("points generate --method recursive --window 0,0,1,1 --density 10 --density-expr ''",
                 "--density-expr");
  // A finite expression, negative in places (which count as 0), is fine.
  CliResult ok = run_cli(
      "points generate --method recursive --window 0,0,1,1 --density 10 --density-expr '2000 * (x - 0.5)' --json");
  EXPECT_EQ(ok.code, 0) << ok.err;
}
