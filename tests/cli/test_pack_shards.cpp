// Shards of the stored enumeration: their databases merged equal the whole run's database.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <set>
#include <string>

#include "results/results_db.hpp"
#include "tests/cli_runner.hpp"

using namespace tilekit::test;

namespace {

std::set<std::string> solution_hashes(const std::string& path) {
  tilekit::ResultsDb db(path, false);
  std::set<std::string> out;
  sqlite3_stmt* q = nullptr;
  sqlite3_prepare_v2(db.handle(), "SELECT solution_hash FROM solutions", -1, &q, nullptr);
  while (sqlite3_step(q) == SQLITE_ROW) out.insert(reinterpret_cast<const char*>(sqlite3_column_text(q, 0)));
  sqlite3_finalize(q);
  return out;
}

}  // namespace

TEST(PackShards, MergedShardDatabasesEqualTheWholeRunsDatabase) {
  TempDir d;
  std::string common = " --kind wang --colors 2 --mode all --threads 2 --quiet --json";
  CliResult whole = run_cli("pack" + common + " --db " + (d / "whole.sqlite"));
  ASSERT_EQ(whole.code, 0) << whole.err;
  std::string inputs;
  std::uint64_t sum = 0;
  std::size_t sizes = 0;
  for (int i = 0; i < 4; ++i) {
    std::string db = d / ("shard" + std::to_string(i) + ".sqlite");
    CliResult r = run_cli("pack" + common + " --shard " + std::to_string(i) + "/4 --db " + db);
    ASSERT_EQ(r.code, 0) << r.err;
    sum += r.json()["solutions"].get<std::uint64_t>();
    sizes += solution_hashes(db).size();
    inputs += " " + db;
  }
  EXPECT_EQ(sum, 203520u);
  EXPECT_EQ(sizes, 203520u);  // the shards are disjoint
  CliResult m = run_cli("db merge " + (d / "merged.sqlite") + inputs + " --json");
  ASSERT_EQ(m.code, 0) << m.err;
  std::set<std::string> merged = solution_hashes(d / "merged.sqlite");
  EXPECT_EQ(merged.size(), 203520u);
  EXPECT_TRUE(merged == solution_hashes(d / "whole.sqlite"));
}
