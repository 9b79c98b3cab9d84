// The libraries name the fields of their requests; the CLI words them as its flags
// (cli/flag_terms.hpp): the mapping, the rewriting of a message, and the binary printing a
// library's RequestError in flag terms.
#include <gtest/gtest.h>

#include "base/error.hpp"
#include "base/parse.hpp"
#include "cli/flag_terms.hpp"
#include "packing/request.hpp"
#include "tests/cli_runner.hpp"

using namespace tilekit;
using namespace tilekit::test;

TEST(FlagTerms, AFieldsFlagIsItsNameUnlessSpelledOtherwise) {
  EXPECT_EQ(cli::flag_of_field("shard"), "--shard");
  EXPECT_EQ(cli::flag_of_field("max_depth"), "--max-depth");
  EXPECT_EQ(cli::flag_of_field("time_limit"), "--time-limit");
  EXPECT_EQ(cli::flag_of_field("colours"), "--colors");
  EXPECT_EQ(cli::flag_of_field("edge_colours"), "--edge-colors");
  EXPECT_EQ(cli::flag_of_field("candidates"), "--candidate");
}

TEST(FlagTerms, EveryBackquotedFieldOfAMessageBecomesItsFlag) {
  EXPECT_EQ(cli::in_flag_terms(std::string_view("`rho` 0.9 with `points` 16: use `rho` 0.2 (or `lloyd` 0)")),
            "--rho 0.9 with --points 16: use --rho 0.2 (or --lloyd 0)");
  // Backquoted text that is not a field's name (spaces, capitals) stays, and so does a lone quote.
  EXPECT_EQ(cli::in_flag_terms(std::string_view("run `tilekit texture tiles` or `X`; a ` b")),
            "run `tilekit texture tiles` or `X`; a ` b");
  try {
    parse_shard("2/2");
    ADD_FAILURE() << "accepted 2/2";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.field(), "shard");
    EXPECT_EQ(cli::in_flag_terms(e), "--shard must be I/N with 0 <= I < N <= 1000000, got '2/2'");
  }
}

// pack finds the request fields given on its command line by their flags: each PackField has one.
TEST(FlagTerms, EveryPackFieldHasAFlagOfPack) {
  const std::string help = run_cli("pack --help").out;
  for (PackField f : pack_fields()) {
    const std::string flag = cli::flag_of_field(pack_field_name(f));
    EXPECT_NE(help.find(flag + " "), std::string::npos) << flag;
  }
}

// A library's error about a field reaches the user in flag terms, as one line with exit 2.
TEST(FlagTerms, TheBinaryWordsLibraryErrorsAsFlags) {
  CliResult r = run_cli("aperiodic enumerate --source kari-14 --max-depth -1 --quiet");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("--max-depth must be >= 0, got -1"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('`'), std::string::npos) << r.err;
  r = run_cli("points tiles --colors 2 --points 16 --rho 1.5 --quiet");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("--rho must be in (0, 1), got 1.5"), std::string::npos) << r.err;
}
