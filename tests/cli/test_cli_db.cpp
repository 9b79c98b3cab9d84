#include <gtest/gtest.h>
#include <sqlite3.h>

#include "results/results_db.hpp"
#include "tests/results/db_test_util.hpp"
#include "tests/cli_runner.hpp"

using namespace tilekit;
using namespace tilekit::test;

namespace {

void make_shard(const std::string& path, std::uint32_t first, std::uint32_t count) {
  ResultsDb db(path);
  RunRecord run;
  run.command = "pack";
  run.params = {{"shard", first}};
  const auto rid = db.begin_run(run);
  std::vector<SolutionRecord> batch;
  for (std::uint32_t i = first; i < first + count; ++i) {
    SolutionRecord s = record_of(numbered_grid(i), "orbit" + std::to_string(i % 7));
    s.run_id = rid;
    batch.push_back(s);
  }
  db.add_solutions(batch);
}

}  // namespace

TEST(CliDb, HelpWorksForEveryDbCommand) {
  for (const char* cmd : {"db", "db list", "db stats", "db show", "db export", "db merge", "db add"}) {
    CliResult r = run_cli(std::string(cmd) + " --help");
    EXPECT_EQ(r.code, 0) << cmd << ": " << r.err;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << cmd;
  }
}

TEST(CliDb, StatsCreatesTheEmbeddedDefaultOnFirstUse) {
  TempDir d;
  const std::string path = d / "data/tilekit/results.sqlite";
  CliResult r = run_cli("--version >/dev/null; TILEKIT_DB=" + q(path) + " " + std::string(TILEKIT_BINARY) + " db stats --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = r.json();
  EXPECT_EQ(j["db"], path);
  for (const char* k : {"runs", "solutions", "distinct_solutions", "tilesets", "conversions"}) EXPECT_EQ(j[k], 0) << k;
  EXPECT_TRUE(exists(path));
}

TEST(CliDb, XdgDataHomeIsTheDefaultDirectory) {
  TempDir d;
  CliResult r = run_cli("--version >/dev/null; env -u TILEKIT_DB XDG_DATA_HOME=" + q(d / "xdg") + " " +
                        std::string(TILEKIT_BINARY) + " db stats --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.json()["db"], d / "xdg/tilekit/results.sqlite");
}

TEST(CliDb, MissingExplicitDatabaseIsNotFound) {
  TempDir d;
  CliResult r = run_cli("db stats --db " + q(d / "typo.sqlite"));
  EXPECT_EQ(r.code, 1);
  EXPECT_FALSE(exists(d / "typo.sqlite"));
}

TEST(CliDb, CorruptAndForeignFilesExit2AndStayByteForByteUntouched) {
  TempDir d;
  const std::string junk = d / "junk.sqlite", foreign = d / "foreign.sqlite", damaged = d / "damaged.sqlite";
  write_text(junk, std::string("SQLite format 3") + std::string(3000, '\x7f'));
  {
    sqlite3* db = nullptr;
    sqlite3_open(foreign.c_str(), &db);
    sqlite3_exec(db, "CREATE TABLE t(x); INSERT INTO t VALUES (1);", nullptr, nullptr, nullptr);
    sqlite3_close(db);
  }
  make_shard(damaged, 0, 300);
  {
    std::string bytes = slurp(damaged);
    const std::size_t page = bytes.size() / 4096 / 2;  // a whole b-tree page in the middle
    for (std::size_t i = page * 4096; i < (page + 1) * 4096; ++i) bytes[i] = char(i * 37);
    write_text(damaged, bytes);
  }
  make_shard(d / "good.sqlite", 0, 5);
  write_text(d / "ok.json", R"({"kind":"wang","colors":2,"rows":1,"cols":2,"torus":false,"cells":[[4,1]]})");
  for (const std::string& f : {junk, foreign, damaged}) {
    const std::string before = slurp(f);
    for (const std::string& cmd :
         {"db stats --db " + q(f), "db list --db " + q(f), "db show 1 --db " + q(f), "db export --db " + q(f),
          "db merge " + q(f) + " " + q(d / "good.sqlite"), "db merge " + q(d / "out.sqlite") + " " + q(f),
          "db add " + q(d / "ok.json") + " --db " + q(f)}) {
      CliResult r = run_cli(cmd + " --json");
      EXPECT_EQ(r.code, 2) << cmd << ": " << r.err;
      EXPECT_TRUE(slurp(f) == before) << "modified by: " << cmd;
      // A reader of a WAL database may create the empty -wal/-shm side files, nothing more.
      EXPECT_TRUE(!exists(f + "-wal") || std::filesystem::file_size(f + "-wal") == 0) << cmd;
    }
  }
  // The failed merges did not even create their target.
  EXPECT_FALSE(exists(d / "out.sqlite"));
}

TEST(CliDb, ExportThenMergeIntoAnEmptyDatabaseRoundTrips) {
  TempDir d;
  make_shard(d / "a.sqlite", 0, 40);
  {
    ResultsDb db(d / "a.sqlite");
    auto s = db.add_tileset("kari-14", TileKind::Wang, 14, 6, "h1", "Kari 1996", "");
    auto t = db.add_tileset("kari-14-d", TileKind::Corner, 214, 6, "h2", "diagonal", "");
    db.add_conversion(s, "diagonal", t, 14, 214, 6, "unknown", {});
  }
  ASSERT_EQ(run_cli("db export --db " + q(d / "a.sqlite") + " --out " + q(d / "a.json")).code, 0);
  CliResult m = run_cli("db merge " + q(d / "b.sqlite") + " " + q(d / "a.json") + " --json");
  ASSERT_EQ(m.code, 0) << m.err;
  EXPECT_EQ(m.json()["added"]["solutions"], 40);
  EXPECT_EQ(m.json()["added"]["conversions"], 1);
  CliResult again = run_cli("db export --db " + q(d / "b.sqlite"));
  ASSERT_EQ(again.code, 0);
  EXPECT_EQ(again.out, slurp(d / "a.json"));
  // CSV of the same table from both has identical rows.
  CliResult ca = run_cli("db export --format csv --table solutions --db " + q(d / "a.sqlite"));
  CliResult cb = run_cli("db export --format csv --table solutions --db " + q(d / "b.sqlite"));
  EXPECT_EQ(ca.out, cb.out);
  EXPECT_EQ(std::count(ca.out.begin(), ca.out.end(), '\n'), 41);
}

TEST(CliDb, MergingTheSameShardTwiceChangesNothing) {
  TempDir d;
  make_shard(d / "s1.sqlite", 0, 30);
  make_shard(d / "s2.sqlite", 20, 30);  // overlaps s1 in 10 solutions
  CliResult first = run_cli("db merge " + q(d / "out.sqlite") + " " + q(d / "s1.sqlite") + " " + q(d / "s2.sqlite") + " --json");
  ASSERT_EQ(first.code, 0) << first.err;
  EXPECT_EQ(first.json()["added"]["solutions"], 50);
  EXPECT_EQ(first.json()["total"]["distinct_solutions"], 7);
  const std::string before = run_cli("db export --db " + q(d / "out.sqlite")).out;
  CliResult second = run_cli("db merge " + q(d / "out.sqlite") + " " + q(d / "s2.sqlite") + " " + q(d / "s1.sqlite") + " --json");
  ASSERT_EQ(second.code, 0) << second.err;
  EXPECT_EQ(second.json()["added"]["solutions"], 0);
  EXPECT_EQ(second.json()["added"]["runs"], 0);
  EXPECT_EQ(run_cli("db export --db " + q(d / "out.sqlite")).out, before);
}

TEST(CliDb, TwoProcessesWritingConcurrentlyLoseNothing) {
  TempDir d;
  // Four shards of 300 solutions; two processes each merge two of them into one database at
  // the same time (each merge is one write transaction; the other process waits).
  for (int i = 0; i < 4; ++i) make_shard(d / ("s" + std::to_string(i) + ".sqlite"), std::uint32_t(i) * 300, 300);
  const std::string out = q(d / "out.sqlite");
  auto merge = [&](int i) { return std::string(TILEKIT_BINARY) + " db merge " + out + " " + q(d / ("s" + std::to_string(i) + ".sqlite")) + " >/dev/null"; };
  const std::string script = "--version >/dev/null; ( " + merge(0) + " && " + merge(2) + " ) & ( " + merge(1) + " && " +
                             merge(3) + " ) & wait %1 && wait %2";
  CliResult r = run_cli(script);
  ASSERT_EQ(r.code, 0) << r.err;
  CliResult s = run_cli("db stats --json --db " + out);
  ASSERT_EQ(s.code, 0) << s.err;
  EXPECT_EQ(s.json()["solutions"], 1200);
  EXPECT_EQ(s.json()["runs"], 4);
}

TEST(CliDb, ShowPrintsACheckableTilingAndListFilters) {
  TempDir d;
  make_shard(d / "a.sqlite", 0, 3);
  CliResult show = run_cli("db show 2 --json --db " + q(d / "a.sqlite"));
  ASSERT_EQ(show.code, 0) << show.err;
  auto j = show.json();
  EXPECT_EQ(j["rows"], 4);
  EXPECT_EQ(j["cells"].size(), 4u);
  EXPECT_EQ(j["run"]["command"], "pack");
  write_text(d / "s.json", show.out);
  EXPECT_NE(run_cli("check " + q(d / "s.json") + " --json").out.find("\"kind\":\"corner\""), std::string::npos);
  EXPECT_EQ(run_cli("db show 99 --db " + q(d / "a.sqlite")).code, 1);
  CliResult list = run_cli("db list --json --kind wang --db " + q(d / "a.sqlite"));
  ASSERT_EQ(list.code, 0);
  EXPECT_EQ(list.json()["rows"].size(), 0u);
  list = run_cli("db list --json --kind corner --colors 2 --limit 2 --db " + q(d / "a.sqlite"));
  EXPECT_EQ(list.json()["rows"].size(), 2u);
  list = run_cli("db list --json --table runs --db " + q(d / "a.sqlite"));
  EXPECT_EQ(list.json()["rows"].size(), 1u);
}

TEST(CliDb, AddStoresOnlyValidTilings) {
  TempDir d;
  write_text(d / "ok.json", R"({"kind":"wang","colors":2,"rows":1,"cols":2,"torus":false,"cells":[[4,1]]})");
  write_text(d / "bad.json", R"({"kind":"wang","colors":2,"rows":1,"cols":2,"torus":false,"cells":[[0,1]]})");
  CliResult bad = run_cli("db add " + q(d / "ok.json") + " " + q(d / "bad.json") + " --db " + q(d / "r.sqlite"));
  EXPECT_EQ(bad.code, 2);
  CliResult ok = run_cli("db add " + q(d / "ok.json") + " --json --db " + q(d / "r.sqlite"));
  ASSERT_EQ(ok.code, 0) << ok.err;
  EXPECT_EQ(ok.json()["added"], 1);
  EXPECT_EQ(run_cli("db add " + q(d / "ok.json") + " --json --db " + q(d / "r.sqlite")).json()["added"], 0);
}

TEST(CliDb, TwoSolverRunsAppendingConcurrentlyLoseNothing) {
  TempDir d;
  // The two shards of the C=2 corner enumeration (32 packings) write to one database at once.
  const std::string db = q(d / "r.sqlite");
  auto shard = [&](int i) {
    return std::string(TILEKIT_BINARY) + " pack --kind corner --colors 2 --mode all --threads 1 --quiet --shard " +
           std::to_string(i) + "/2 --db " + db + " --json > " + q(d / ("s" + std::to_string(i) + ".json"));
  };
  CliResult r = run_cli("--version >/dev/null; " + shard(0) + " & " + shard(1) + " & wait %1 && wait %2");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto s0 = nlohmann::json::parse(slurp(d / "s0.json")), s1 = nlohmann::json::parse(slurp(d / "s1.json"));
  EXPECT_EQ(s0["solutions"].get<int>() + s1["solutions"].get<int>(), 32);
  CliResult st = run_cli("db stats --json --db " + db);
  ASSERT_EQ(st.code, 0) << st.err;
  EXPECT_EQ(st.json()["solutions"], 32);
  EXPECT_EQ(st.json()["runs"], 2);
}
