// `tilekit pack --impose SPEC`, `--method search` (the imposed-group portfolio; `auto` tries the database and constructions first) and
// `--portfolio-report` and `--estimate` end to end.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <algorithm>

#include "tests/cli_runner.hpp"

using namespace tilekit::test;

namespace {

struct ImposeCli : ::testing::Test {
  TempDir dir;
  CliResult pack(const std::string& args) {
    return run_cli("pack --quiet --db " + (dir / "results.sqlite") + " --portfolio-stats " + (dir / "stats.json") + " " +
                   args);
  }
  void expect_checked_packing(const std::string& file, const std::string& set) {
    CliResult c = run_cli("check " + file + " --set " + set + " --json");
    ASSERT_EQ(c.code, 0) << c.err;
    EXPECT_EQ(c.json()["packing"], true);
  }
};

TEST_F(ImposeCli, ImposedGroupGivesAValidInvariantPackingWithTheGroupInJsonAndDatabase) {
  CliResult r = pack("--kind corner --colors 4 --impose 't=0,4:pi=1,2,3,0' --threads 2 --json --out " + (dir / "p.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = r.json();
  EXPECT_EQ(j["valid"], true);
  EXPECT_EQ(j["group"]["spec"], "t=0,4:pi=1,2,3,0");
  EXPECT_EQ(j["group"]["order"], 4);
  expect_checked_packing(dir / "p.json", "complete-corner-4");
  // Invariance on the printed cells: cell (r, c+4) is cell (r, c) with colours x -> x+1 mod 4.
  auto cells = j["cells"];
  auto shift = [](unsigned t) {
    unsigned ne = t / 64, se = t / 16 % 4, sw = t / 4 % 4, nw = t % 4;
    return ((((ne + 1) % 4) * 4 + (se + 1) % 4) * 4 + (sw + 1) % 4) * 4 + (nw + 1) % 4;  // thesis eq. (2.5)
  };
  for (int row = 0; row < 16; ++row)
    for (int col = 0; col < 16; ++col)
      EXPECT_EQ(cells[row][(col + 4) % 16].get<unsigned>(), shift(cells[row][col].get<unsigned>()));
  // The database row of the solution carries the group.
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open_v2((dir / "results.sqlite").c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  sqlite3_stmt* st = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(db, "SELECT group_json FROM solutions", -1, &st, nullptr), SQLITE_OK);
  ASSERT_EQ(sqlite3_step(st), SQLITE_ROW);
  auto stored = nlohmann::json::parse(reinterpret_cast<const char*>(sqlite3_column_text(st, 0)));
  EXPECT_EQ(stored["spec"], "t=0,4:pi=1,2,3,0");
  sqlite3_finalize(st);
  sqlite3_close(db);
}

TEST_F(ImposeCli, BadGroupsExit2WithTheReason) {
  struct Case {
    const char* args;
    const char* reason;
  };
  for (Case c : {Case{"--kind corner --colors 4 --impose 't=0,4:pi=1,0,3,2'", "has order 4"},
                 Case{"--kind corner --colors 4 --impose 't=0,8:pi=1,0,2,3'", "fixes colour 2"},
                 Case{"--kind wang --colors 4 --impose 't=0,8:pih=1,0,2,3:piv=0,1,3,2'", "its own image"},
                 Case{"--kind corner --colors 4 --impose 't=0,4:pi=1,2,3'", "has 3 entries but there are 4 colours"},
                 Case{"--kind corner --colors 4 --impose 'x=1'", "unknown key 'x'"}}) {
    CliResult r = pack(c.args);
    EXPECT_EQ(r.code, 2) << c.args;
    EXPECT_NE(r.err.find(c.reason), std::string::npos) << c.args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(r.out.empty());
  }
}

TEST_F(ImposeCli, CountUnderAGroupMatchesTheBruteForceFilter) {
  // Of the 203,520 C=2 Wang packings, those invariant under t=(0,2) with both colour classes
  // swapped; the API test checks the same number against a brute-force filter.
  CliResult r = pack("--kind wang --colors 2 --mode count --impose 't=0,2:pi=1,0' --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.json()["complete"], true);
  EXPECT_GT(r.json()["solutions"].get<long>(), 0);
  EXPECT_LT(r.json()["solutions"].get<long>(), 203520);
  EXPECT_EQ(r.json()["group"]["order"], 2);
}

TEST_F(ImposeCli, SearchPortfolioFindsFourColourCornerAndWangPackingsOnTwoThreads) {
  for (const char* kind : {"corner", "wang"}) {
    std::string out = dir / (std::string(kind) + ".json");
    CliResult r = pack(std::string("--kind ") + kind + " --colors 4 --method search --threads 2 --json --out " + out);
    ASSERT_EQ(r.code, 0) << r.err;
    auto j = r.json();
    EXPECT_EQ(j["valid"], true);
    ASSERT_TRUE(j.contains("portfolio"));
    EXPECT_FALSE(j["portfolio"]["winner"].is_null());
    expect_checked_packing(out, std::string("complete-") + kind + "-4");
  }
  CliResult rep = run_cli("pack --portfolio-report --json --portfolio-stats " + (dir / "stats.json"));
  ASSERT_EQ(rep.code, 0) << rep.err;
  long successes = 0;
  const auto report = rep.json();
  for (const auto& row : report["groups"]) successes += row["successes"].get<long>();
  EXPECT_GE(successes, 2) << rep.out << slurp(dir / "stats.json");
  CliResult human = run_cli("pack --portfolio-report --kind wang --portfolio-stats " + (dir / "stats.json"));
  ASSERT_EQ(human.code, 0) << human.err;
  EXPECT_NE(human.out.find("wang"), std::string::npos);
  EXPECT_EQ(human.out.find("corner  "), std::string::npos);  // filtered by --kind
}

// --estimate: every candidate's search tree (Knuth) and node rate, reproducible for a seed,
// nothing stored; requests it cannot measure are exit 2.
TEST_F(ImposeCli, EstimateGivesEachCandidatesTreeAndRateAndStoresNothing) {
  const std::string args = "--kind corner --colors 4 --estimate 100 --estimate-seconds 0.3 --threads 1 --seed 3 --json";
  CliResult r = pack(args);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = r.json();
  EXPECT_EQ(j["probes"], 100);
  double plain = 0, largest_group = 0;  // log10 of the trees
  int estimable = 0;
  for (const auto& c : j["candidates"]) {
    if (!c["estimable"].get<bool>()) {
      EXPECT_EQ(c["family"].get<std::string>().find("sat"), c["family"].get<std::string>().size() - 3) << c;
      continue;
    }
    ++estimable;
    EXPECT_GT(c["log10_tree_nodes"].get<double>(), 0.0) << c;
    EXPECT_GT(c["nodes"].get<std::uint64_t>(), 0u) << c;
    EXPECT_GT(c["nodes_per_cpu_second"].get<double>(), 0.0) << c;
    if (c["candidate"] == "plain") plain = c["log10_tree_nodes"].get<double>();
    if (c["family"] == "impose") largest_group = std::max(largest_group, c["log10_tree_nodes"].get<double>());
  }
  EXPECT_GE(estimable, 3);
  // The whole space's tree dwarfs every invariant subspace's (1e83 against at most 1e43 here).
  EXPECT_GT(plain, largest_group + 20);
  EXPECT_FALSE(std::filesystem::exists(dir / "results.sqlite"));
  // The probes follow the seed: the same estimates again.
  CliResult again = pack(args);
  ASSERT_EQ(again.code, 0) << again.err;
  for (std::size_t i = 0; i < j["candidates"].size(); ++i)
    EXPECT_EQ(again.json()["candidates"][i].value("log10_tree_nodes", 0.0),
              j["candidates"][i].value("log10_tree_nodes", 0.0));
  for (const std::string bad :
       {"--kind corner --colors 4 --estimate 0", "--kind corner --colors 4 --estimate 10 --mode all",
        "--kind corner --colors 4 --estimate 10 --impose 't=0,4:pi=1,2,3,0'",
        "--kind corner --colors 4 --estimate 10 --estimate-seconds 0"}) {
    CliResult b = pack(bad);
    EXPECT_EQ(b.code, 2) << bad << ": " << b.err;
    EXPECT_EQ(std::count(b.err.begin(), b.err.end(), '\n'), 1) << b.err;
  }
}

}  // namespace
