#include <gtest/gtest.h>
#include <sqlite3.h>

#include <atomic>
#include <cstdlib>
#include <sstream>
#include <thread>

#include "results/results_db.hpp"
#include "tests/results/db_test_util.hpp"
#include "base/error.hpp"

using namespace tilekit;
using namespace tilekit::test;

namespace {

std::string query_text(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
  sqlite3_stmt* st = nullptr;
  std::string out;
  if (sqlite3_prepare_v2(db, sql.c_str(), -1, &st, nullptr) == SQLITE_OK && sqlite3_step(st) == SQLITE_ROW) {
    const unsigned char* p = sqlite3_column_text(st, 0);
    out = p ? reinterpret_cast<const char*>(p) : "";
  }
  sqlite3_finalize(st);
  sqlite3_close(db);
  return out;
}

void make_foreign_db(const std::string& path) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  sqlite3_exec(db, "CREATE TABLE photos(id INTEGER PRIMARY KEY, name TEXT); INSERT INTO photos(name) VALUES ('a');",
               nullptr, nullptr, nullptr);
  sqlite3_close(db);
}

}  // namespace

TEST(ResultsDb, NewDatabaseHasCurrentSchemaInWalMode) {
  TempDir d;
  const std::string path = d / "sub/dir/r.sqlite";
  { ResultsDb db(path); }
  ASSERT_TRUE(exists(path));  // directory created on first use
  EXPECT_EQ(query_text(path, "PRAGMA journal_mode"), "wal");
  EXPECT_EQ(query_text(path, "PRAGMA user_version"), std::to_string(ResultsDb::kSchemaVersion));
  EXPECT_EQ(query_text(path, "PRAGMA application_id"), std::to_string(ResultsDb::kApplicationId));
  for (const char* t : {"runs", "solutions", "tilesets", "conversions"})
    EXPECT_EQ(query_text(path, std::string("SELECT name FROM sqlite_master WHERE name = '") + t + "'"), t);
  EXPECT_EQ(query_text(path, "SELECT name FROM sqlite_master WHERE name = 'solutions_by_canonical'"),
            "solutions_by_canonical");
}

TEST(ResultsDb, MissingFileWithoutCreateIsNotFound) {
  TempDir d;
  EXPECT_THROW(ResultsDb(d / "none.sqlite", false), NotFound);
  EXPECT_FALSE(exists(d / "none.sqlite"));
}

TEST(ResultsDb, SolutionsAreUniqueBySolutionHash) {
  TempDir d;
  ResultsDb db(d / "r.sqlite");
  EXPECT_TRUE(db.add_solution(record_of(numbered_grid(1))));
  EXPECT_FALSE(db.add_solution(record_of(numbered_grid(1))));
  EXPECT_TRUE(db.add_solution(record_of(numbered_grid(2))));
  EXPECT_EQ(db.stats().solutions, 2u);
  std::vector<SolutionRecord> batch;
  for (std::uint32_t i = 0; i < 10; ++i) batch.push_back(record_of(numbered_grid(i)));
  EXPECT_EQ(db.add_solutions(batch), 8u);  // 1 and 2 are already there
  EXPECT_EQ(db.stats().solutions, 10u);
}

TEST(ResultsDb, DistinctSolutionsCountsCanonicalHashesOnce) {
  TempDir d;
  ResultsDb db(d / "r.sqlite");
  db.add_solution(record_of(numbered_grid(1), "orbitA"));
  db.add_solution(record_of(numbered_grid(2), "orbitA"));
  db.add_solution(record_of(numbered_grid(3), "orbitB"));
  db.add_solution(record_of(numbered_grid(4)));  // no canonical hash: counts by itself
  DbStats st = db.stats();
  EXPECT_EQ(st.solutions, 4u);
  EXPECT_EQ(st.distinct_solutions, 3u);
}

TEST(ResultsDb, StoredSolutionReadsBackExactly) {
  TempDir d;
  ResultsDb db(d / "r.sqlite");
  RunRecord run;
  run.command = "pack";
  run.params = {{"colors", 2}};
  const auto run_id = db.begin_run(run);
  SolutionRecord s = record_of(numbered_grid(7), "c7");
  s.run_id = run_id;
  s.orbit_size = 32;
  s.validated = true;
  s.group = {{"t", {0, 8}}, {"pi", {1, 0}}};
  ASSERT_TRUE(db.add_solution(s));
  auto found = db.find_solution(TileKind::Corner, 2, 4, 4);
  ASSERT_TRUE(found);
  EXPECT_EQ(found->tiling.cells, s.tiling.cells);
  EXPECT_EQ(found->run_id, run_id);
  EXPECT_EQ(found->orbit_size, 32u);
  EXPECT_EQ(found->group, s.group);
  EXPECT_EQ(found->solution_hash, solution_hash(s.tiling));
  EXPECT_FALSE(db.find_solution(TileKind::Wang, 2, 4, 4));
  EXPECT_FALSE(db.find_solution(TileKind::Corner, 3, 9, 9));
}

TEST(ResultsDb, FindSolutionIgnoresUnvalidatedRows) {
  TempDir d;
  ResultsDb db(d / "r.sqlite");
  db.add_solution(record_of(numbered_grid(1)));
  EXPECT_FALSE(db.find_solution(TileKind::Corner, 2, 4, 4));
}

TEST(ResultsDb, RunLifecycleIsRecorded) {
  TempDir d;
  ResultsDb db(d / "r.sqlite");
  RunRecord run;
  run.command = "pack";
  run.params = {{"kind", "corner"}, {"colors", 3}};
  run.threads = 4;
  run.id = db.begin_run(run);
  auto started = db.run(run.id);
  ASSERT_TRUE(started);
  EXPECT_EQ(started->status, "running");
  EXPECT_FALSE(started->uid.empty());
  EXPECT_FALSE(started->host.empty());
  run.status = "complete";
  run.solutions = 5;
  run.nodes = 1234;
  run.orbits = 2;
  run.seconds = 1.5;
  db.finish_run(run);
  auto done = db.run(run.id);
  ASSERT_TRUE(done);
  EXPECT_EQ(done->status, "complete");
  EXPECT_EQ(done->solutions, 5u);
  EXPECT_EQ(done->nodes, 1234u);
  EXPECT_EQ(done->orbits, std::optional<std::uint64_t>(2));
  EXPECT_EQ(done->params["colors"], 3);
  EXPECT_FALSE(done->finished_at.empty());
  run.id = 999;
  EXPECT_THROW(db.finish_run(run), NotFound);
}

TEST(ResultsDb, TilesetsAndConversionsAreIdempotent) {
  TempDir d;
  ResultsDb db(d / "r.sqlite");
  auto a = db.add_tileset("culik-13", TileKind::Wang, 13, 5, "h13", "Culik 1996", "0 1 2 3\n");
  auto b = db.add_tileset("culik-13-diagonal", TileKind::Corner, 125, 5, "h125", "conversion", "");
  EXPECT_NE(a, b);
  EXPECT_EQ(db.add_tileset("culik-13", TileKind::Wang, 13, 5, "h13", "Culik 1996", "0 1 2 3\n"), a);
  auto c = db.add_conversion(a, "diagonal", b, 13, 125, 5, "unknown", {{"note", "first"}});
  auto c2 = db.add_conversion(a, "diagonal", b, 13, 125, 5, "sound", {{"note", "verified"}});
  EXPECT_EQ(c, c2);
  auto conv = db.conversion(c);
  ASSERT_TRUE(conv);
  EXPECT_EQ(conv->soundness, "sound");
  EXPECT_EQ(conv->details["note"], "verified");
  EXPECT_EQ(conv->tiles_after, 125u);
  DbStats st = db.stats();
  EXPECT_EQ(st.tilesets, 2u);
  EXPECT_EQ(st.conversions, 1u);
  EXPECT_THROW(db.add_conversion(a, "diagonal", 77, 13, 125, 5, "unknown", {}), InputError);
}

TEST(ResultsDb, ForeignSqliteFileIsRejectedAndUntouched) {
  TempDir d;
  const std::string path = d / "photos.sqlite";
  make_foreign_db(path);
  const std::string before = slurp(path);
  EXPECT_THROW(ResultsDb db(path), InputError);
  EXPECT_EQ(slurp(path), before);
  EXPECT_FALSE(exists(path + "-wal"));
  EXPECT_FALSE(exists(path + "-shm"));
  EXPECT_EQ(query_text(path, "PRAGMA journal_mode"), "delete");
}

TEST(ResultsDb, NonSqliteFileIsRejectedAndUntouched) {
  TempDir d;
  const std::string path = d / "junk.sqlite";
  std::string junk(5000, '\0');
  for (std::size_t i = 0; i < junk.size(); ++i) junk[i] = char((i * 131 + 7) % 251);
  write_text(path, junk);
  try {
    ResultsDb db(path);
    FAIL() << "opened a junk file";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("left untouched"), std::string::npos) << e.what();
  }
  EXPECT_EQ(slurp(path), junk);
  EXPECT_FALSE(exists(path + "-wal"));
}

TEST(ResultsDb, DamagedPagesAreRejectedAndUntouched) {
  TempDir d;
  const std::string path = d / "r.sqlite";
  {
    ResultsDb db(path);
    std::vector<SolutionRecord> batch;
    for (std::uint32_t i = 0; i < 300; ++i) batch.push_back(record_of(numbered_grid(i), "x" + std::to_string(i)));
    db.add_solutions(batch);
  }
  ASSERT_FALSE(exists(path + "-wal"));  // checkpointed on close
  std::string bytes = slurp(path);
  ASSERT_GT(bytes.size(), 5 * 4096u);
  for (std::size_t i = 3 * 4096; i < 3 * 4096 + 600; ++i) bytes[i] = char(0xA5 ^ (i & 0xff));
  write_text(path, bytes);
  EXPECT_THROW(ResultsDb db(path), InputError);
  EXPECT_EQ(slurp(path), bytes);
}

TEST(ResultsDb, NewerSchemaVersionIsRejectedAndUntouched) {
  TempDir d;
  const std::string path = d / "r.sqlite";
  { ResultsDb db(path); }
  sqlite3* raw = nullptr;
  sqlite3_open(path.c_str(), &raw);
  sqlite3_exec(raw, "PRAGMA user_version = 99", nullptr, nullptr, nullptr);
  sqlite3_close(raw);
  const std::string before = slurp(path);
  EXPECT_THROW(ResultsDb db(path), InputError);
  EXPECT_EQ(slurp(path), before);
}

TEST(ResultsDb, EmptyFileIsInitialised) {
  TempDir d;
  const std::string path = d / "empty.sqlite";
  write_text(path, "");
  ResultsDb db(path);
  EXPECT_EQ(db.stats().solutions, 0u);
}

TEST(ResultsDb, ReadOnlyOpenNeverWrites) {
  TempDir d;
  const std::string path = d / "r.sqlite";
  {
    ResultsDb db(path);
    db.add_solution(record_of(numbered_grid(3)));
  }
  ResultsDb ro(path, DbOpenOptions{.create = false, .read_only = true});
  EXPECT_EQ(ro.stats().solutions, 1u);
  EXPECT_ANY_THROW(ro.add_solution(record_of(numbered_grid(4))));
}

TEST(ResultsDb, TwoWritersBothLandEveryRow) {
  TempDir d;
  const std::string path = d / "r.sqlite";
  { ResultsDb init(path); }
  auto writer = [&](std::uint32_t base) {
    ResultsDb db(path);
    for (std::uint32_t i = 0; i < 150; ++i) db.add_solution(record_of(numbered_grid(base + i)));
  };
  std::thread a(writer, 0), b(writer, 1000);
  a.join();
  b.join();
  ResultsDb db(path);
  EXPECT_EQ(db.stats().solutions, 300u);
}

// A reader opening a database while a writer creates it, fills it and checkpoints it on close
// must see it whole. Its header fields and tables were once read from two snapshots
// (application_id 0 with 5 tables: refused as another application's), and a lock-free
// (immutable) read of a file that a checkpoint was rewriting could see a mixture of both.
TEST(ResultsDb, AReaderDuringTheCreationAndCheckpointOfANewFileSeesItWhole) {
  TempDir d;
  for (int round = 0; round < 20; ++round) {
    const std::string path = d / ("r" + std::to_string(round) + ".sqlite");
    std::atomic<bool> done{false};
    std::string written;  // the writer's error, if any
    std::thread writer([&] {
      try {
        ResultsDb db(path);
        for (std::uint32_t i = 0; i < 100; ++i) db.add_solution(record_of(numbered_grid(i)));
      } catch (const std::exception& e) {  // the close (at the brace) checkpoints the -wal into the file
        written = e.what();
      }
      done = true;
    });
    std::string error;
    int reads = 0;
    while (!done && error.empty()) {
      try {
        ResultsDb db(path, DbOpenOptions{.create = false, .read_only = true});
        ++reads;
      } catch (const NotFound&) {  // not created yet
      } catch (const std::exception& e) {
        error = e.what();
      }
    }
    writer.join();
    ASSERT_EQ(written, "") << "round " << round;
    ASSERT_EQ(error, "") << "round " << round << ", after " << reads << " reads";
  }
}

TEST(ResultsDb, ExportThenMergeIntoEmptyRoundTrips) {
  TempDir d;
  {
    ResultsDb db(d / "a.sqlite");
    RunRecord run;
    run.command = "pack";
    run.params = {{"colors", 2}};
    const auto rid = db.begin_run(run);
    for (std::uint32_t i = 0; i < 20; ++i) {
      SolutionRecord s = record_of(numbered_grid(i), "o" + std::to_string(i % 3));
      s.run_id = i % 2 ? rid : 0;
      s.validated = i % 3 == 0;
      db.add_solution(s);
    }
    auto a = db.add_tileset("kari-14", TileKind::Wang, 14, 6, "k14", "Kari 1996", "text");
    auto b = db.add_tileset("kari-14-diag", TileKind::Corner, 214, 6, "k214", "conversion", "");
    db.add_conversion(a, "diagonal", b, 14, 214, 6, "unknown", {{"x", 1}});
    std::ofstream(d / "a.json") << [&] {
      std::ostringstream o;
      db.export_json(o);
      return o.str();
    }();
  }
  ResultsDb b(d / "b.sqlite");
  MergeReport rep = b.merge({d / "a.json"});
  EXPECT_EQ(rep.solutions, 20u);
  EXPECT_EQ(rep.runs, 1u);
  std::ostringstream exported;
  b.export_json(exported);
  EXPECT_EQ(exported.str(), slurp(d / "a.json"));
  // And merging the database itself gives the same again.
  ResultsDb c(d / "c.sqlite");
  c.merge({d / "a.sqlite"});
  std::ostringstream exported_c;
  c.export_json(exported_c);
  EXPECT_EQ(exported_c.str(), slurp(d / "a.json"));
}

TEST(ResultsDb, MergeIsIdempotentAndDedupesBySolutionHash) {
  TempDir d;
  for (int shard = 0; shard < 2; ++shard) {
    ResultsDb db(d / ("s" + std::to_string(shard) + ".sqlite"));
    RunRecord run;
    run.command = "pack";
    db.begin_run(run);
    for (std::uint32_t i = 0; i < 30; ++i) db.add_solution(record_of(numbered_grid(std::uint32_t(shard) * 20 + i)));
  }
  ResultsDb out(d / "out.sqlite");
  MergeReport first = out.merge({d / "s0.sqlite", d / "s1.sqlite"});
  EXPECT_EQ(first.solutions, 50u);  // 0..29 and 20..49 overlap in 10
  EXPECT_EQ(first.solutions_seen, 60u);
  EXPECT_EQ(first.runs, 2u);
  RunRecord other;
  other.command = "other";
  out.begin_run(other);
  const std::string before = [&] {
    std::ostringstream o;
    out.export_json(o);
    return o.str();
  }();
  MergeReport again = out.merge({d / "s0.sqlite", d / "s1.sqlite"});
  EXPECT_EQ(again.solutions, 0u);
  EXPECT_EQ(again.runs, 0u);
  std::ostringstream after;
  out.export_json(after);
  EXPECT_EQ(after.str(), before);
}

TEST(ResultsDb, MergeWithDistinctOrbitsKeepsOnePerCanonicalHash) {
  TempDir d;
  {
    ResultsDb db(d / "s.sqlite");
    for (std::uint32_t i = 0; i < 12; ++i) db.add_solution(record_of(numbered_grid(i), "orbit" + std::to_string(i % 4)));
  }
  ResultsDb out(d / "out.sqlite");
  EXPECT_EQ(out.merge({d / "s.sqlite"}, true).solutions, 4u);
  EXPECT_EQ(out.stats().distinct_solutions, 4u);
}

TEST(ResultsDb, MergeWithABadInputWritesNothing) {
  TempDir d;
  {
    ResultsDb db(d / "good.sqlite");
    db.add_solution(record_of(numbered_grid(1)));
  }
  make_foreign_db(d / "foreign.sqlite");
  const std::string foreign_before = slurp(d / "foreign.sqlite");
  ResultsDb out(d / "out.sqlite");
  EXPECT_THROW(out.merge({d / "good.sqlite", d / "foreign.sqlite"}), InputError);
  EXPECT_EQ(out.stats().solutions, 0u);
  EXPECT_EQ(slurp(d / "foreign.sqlite"), foreign_before);
  write_text(d / "notexport.json", "{\"kind\":\"corner\"}");
  EXPECT_THROW(out.merge({d / "good.sqlite", d / "notexport.json"}), InputError);
  EXPECT_EQ(out.stats().solutions, 0u);
}

TEST(SolutionHash, IsStableAndSensitiveToEveryField) {
  Tiling t = numbered_grid(5);
  const std::string h = solution_hash(t);
  EXPECT_EQ(h.size(), 16u);
  EXPECT_EQ(h, "86ffbe175f25f689");  // pinned (also computed by an independent Python script of the same definition)
  Tiling u = t;
  u.cells[15] ^= 1;
  EXPECT_NE(solution_hash(u), h);
  u = t;
  u.kind = TileKind::Wang;
  EXPECT_NE(solution_hash(u), h);
  u = t;
  u.torus = false;
  EXPECT_NE(solution_hash(u), h);
  u = t;
  u.colours = 3;
  EXPECT_NE(solution_hash(u), h);
}

TEST(ResultsDb, DefaultPathFollowsEnvironment) {
  const char* old_db = std::getenv("TILEKIT_DB");
  const char* old_xdg = std::getenv("XDG_DATA_HOME");
  std::string keep_db = old_db ? old_db : "", keep_xdg = old_xdg ? old_xdg : "";
  ::unsetenv("TILEKIT_DB");
  ::setenv("XDG_DATA_HOME", "/data/x", 1);
  EXPECT_EQ(ResultsDb::default_path(), "/data/x/tilekit/results.sqlite");
  ::setenv("TILEKIT_DB", "/tmp/mine.sqlite", 1);
  EXPECT_EQ(ResultsDb::default_path(), "/tmp/mine.sqlite");
  if (old_db) ::setenv("TILEKIT_DB", keep_db.c_str(), 1);
  else ::unsetenv("TILEKIT_DB");
  if (old_xdg) ::setenv("XDG_DATA_HOME", keep_xdg.c_str(), 1);
  else ::unsetenv("XDG_DATA_HOME");
}
