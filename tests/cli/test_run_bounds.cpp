// Work that a flag could make unbounded is bounded or refused: `pack --estimate` with a huge probe
// count honours --time-limit, refuses --resume and a repeated --candidate like a run does, and
// `aperiodic link` stops at its --time-limit with the links re-derived so far.
#include <gtest/gtest.h>

#include <string>

#include "tests/cli_runner.hpp"

using namespace tilekit::test;

TEST(RunBounds, PackEstimateWithAHugeProbeCountStopsAtTheTimeLimit) {
  CliResult r = run_cli("pack --kind corner --colors 5 --estimate 2147483648 --time-limit 1 --threads 1 --quiet --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.json()["probes"], 2147483648ll);
  CliResult big = run_cli("pack --kind corner --colors 5 --estimate 18446744073709551617 --quiet");
  EXPECT_EQ(big.code, 2) << big.err;
  EXPECT_NE(big.err.find("--estimate"), std::string::npos) << big.err;
}

TEST(RunBounds, PackEstimateRefusesResumeAndARepeatedCandidateLikeARun) {
  TempDir d;
  write_text(d / "x.ckpt", "not a checkpoint\n");
  CliResult resume = run_cli("pack --kind corner --colors 5 --estimate 5 --resume " + std::string(d / "x.ckpt"));
  EXPECT_EQ(resume.code, 2) << resume.err;
  EXPECT_NE(resume.err.find("--estimate"), std::string::npos) << resume.err;
  EXPECT_NE(resume.err.find("--resume"), std::string::npos) << resume.err;
  EXPECT_EQ(resume.err.find("solve_checkpointed"), std::string::npos) << resume.err;
  CliResult twice = run_cli("pack --kind corner --colors 5 --estimate 5 --candidate plain --candidate plain --quiet");
  EXPECT_EQ(twice.code, 2) << twice.err;
  EXPECT_NE(twice.err.find("listed twice"), std::string::npos) << twice.err;
}

TEST(RunBounds, AperiodicLinkStopsAtItsTimeLimitWithTheLinksSoFar) {
  // Four fuses make a set whose canonical form alone takes minutes.
  CliResult r = run_cli("aperiodic link kari-14 --steps fuse,fuse,fuse,fuse,fuse --time-limit 1 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = r.json();
  EXPECT_EQ(j["complete"], false);
  EXPECT_EQ(j["timed_out"], true);
  EXPECT_EQ(j["sound"], false);  // a chain cut short proves nothing
  EXPECT_LT(j["links"].size(), 6u);
  // Within the limit the chain is complete.
  CliResult ok = run_cli("aperiodic link kari-14 --steps fuse --time-limit 60 --json");
  ASSERT_EQ(ok.code, 0) << ok.err;
  EXPECT_EQ(ok.json()["complete"], true);
  EXPECT_EQ(ok.json()["links"].size(), 2u);
}
