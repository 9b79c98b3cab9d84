// `pack --stats` and `aperiodic verify --stats`: the engine's statistics (solver/search_stats.hpp)
// as a "stats" object in the one JSON result, or a table on stderr.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/cli_runner.hpp"

using namespace tilekit::test;

TEST(PackStats, JsonCarriesCountersThatMatchTheResult) {
  TempDir d;
  const CliResult r =
      run_cli("pack --kind wang --colors 2 --mode count --threads 2 --stats --json --quiet --db " + d / "r.sqlite");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = r.json();
  ASSERT_TRUE(j.contains("stats")) << r.out;
  const nlohmann::json& s = j["stats"];
  EXPECT_EQ(s["solutions"], 203520);
  EXPECT_EQ(s["nodes"], j["nodes"]);
  EXPECT_GT(s["decisions"].get<std::uint64_t>(), 0u);
  EXPECT_LE(s["backtracks"].get<std::uint64_t>(), s["nodes"].get<std::uint64_t>());
  EXPECT_GT(s["prunes"]["forward-check"].get<std::uint64_t>(), 0u);
  EXPECT_GT(s["seconds"]["search"].get<double>(), 0.0);
  EXPECT_EQ(r.err, "") << "with --json the statistics are in the JSON only";
  // Without --stats, no "stats" object.
  const CliResult plain = run_cli("pack --kind corner --colors 2 --mode count --json --quiet --db " + d / "r.sqlite");
  ASSERT_EQ(plain.code, 0) << plain.err;
  EXPECT_FALSE(plain.json().contains("stats"));
}

TEST(PackStats, HumanOutputPrintsATableOnStderr) {
  TempDir d;
  const CliResult r =
      run_cli("pack --kind corner --colors 2 --mode count --threads 1 --stats --quiet --db " + d / "r.sqlite");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("statistics:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("prune tile-used"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("time search"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("statistics:"), std::string::npos) << "stdout keeps the result only";
}

TEST(VerifyStats, TheTorusSearchesStatisticsAreSummed) {
  const CliResult r = run_cli("aperiodic verify culik-13 --route torus --max-period 8 --stats --json --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = r.json();
  ASSERT_TRUE(j.contains("stats")) << r.out;
  EXPECT_EQ(j["stats"]["nodes"], j["nodes"]);
  EXPECT_EQ(j["stats"]["searches"], j["shapes_searched"]);  // one solve() per torus shape searched
  EXPECT_GT(j["shapes_searched"].get<int>(), 0);
  EXPECT_EQ(j["stats"]["solutions"], 0) << "culik-13 tiles no torus";
}

TEST(PackStats, APortfolioRunSumsItsSlices) {
  TempDir d;
  const CliResult r = run_cli(
      "pack --kind corner --colors 3 --mode first --method search --threads 1 --stats --json "
      "--quiet --db " +
      d / "r.sqlite");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = r.json();
  ASSERT_EQ(j["formulation"], "portfolio") << r.out;
  const nlohmann::json& s = j["stats"];
  // A slice that resumes its candidate's engine reports the nodes of the earlier slices too; the
  // statistics count each slice's own.
  EXPECT_GT(s["nodes"].get<std::uint64_t>(), 0u);
  EXPECT_LE(s["nodes"].get<std::uint64_t>(), j["nodes"].get<std::uint64_t>());
  EXPECT_GE(s["searches"].get<std::uint64_t>(), 1u);  // one per slice
  EXPECT_EQ(s["solutions"], 1);
  EXPECT_EQ(s["leaves"], 1);
}
