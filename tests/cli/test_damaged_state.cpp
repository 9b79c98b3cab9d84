// Damaged and edited state files: results databases whose schema or rows were changed through
// SQLite (they still pass integrity_check), and checkpoints whose checksum is valid but whose
// contents are not (nested JSON inside a string field, wrong types, finished marks outside the
// run's shard or without their counts). Each is exit 2 with one line naming the problem, the
// file's bytes unchanged, and no run row or checkpoint field written.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <filesystem>

#include "base/hash.hpp"
#include "checkpoints/checkpoint.hpp"
#include "tests/cli_runner.hpp"

using namespace tilekit;
using namespace tilekit::test;
namespace fs = std::filesystem;

namespace {

void exec_sql(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  char* err = nullptr;
  const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &err);
  EXPECT_EQ(rc, SQLITE_OK) << (err ? err : "") << " in " << sql;
  sqlite3_free(err);
  sqlite3_close(db);
}

// A database with a run and a stored packing, then changed by `sql`.
std::string tampered_db(const TempDir& d, const std::string& name, const std::string& sql) {
  const std::string path = d / name;
  const CliResult made = run_cli("pack --kind corner --colors 2 --method construct --quiet --db " + path);
  EXPECT_EQ(made.code, 0) << made.err;
  exec_sql(path, "PRAGMA journal_mode = DELETE; " + sql);  // one file, no -wal beside it
  return path;
}

void expect_exit2_naming(const CliResult& r, const std::string& fragment) {
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

struct Tampering {
  const char* name;
  const char* sql;
  const char* message;
};

const Tampering kTamperings[] = {
    {"dropped-column", "ALTER TABLE runs DROP COLUMN params", "table 'runs' has no column 'params'"},
    {"renamed-column", "ALTER TABLE solutions RENAME COLUMN cells TO grid", "table 'solutions' has no column 'cells'"},
    {"renamed-table", "ALTER TABLE tilesets RENAME TO sets", "it has a table 'sets' that Tilekit does not make"},
    {"trigger", "CREATE TRIGGER no_runs BEFORE INSERT ON runs BEGIN SELECT RAISE(ABORT, 'trigger says no'); END",
     "it has a trigger 'no_runs' of its own (on 'runs')"},
    {"view", "CREATE VIEW every_run AS SELECT * FROM runs", "it has a view 'every_run' of its own"},
    {"extra-index", "CREATE UNIQUE INDEX one_kind ON solutions(kind)",
     "it has an index 'one_kind' on 'solutions' that Tilekit does not make"},
    {"wrong-type", "UPDATE solutions SET rows = 'four'", "solutions row 1: column 'rows' holds text"},
    {"wrong-type-run", "UPDATE runs SET nodes = x'00ff'", "runs row 1: column 'nodes' holds blob"},
};

}  // namespace

TEST(DamagedDatabase, AlteredSchemasAndWrongTypesAreExit2WithTheFileUnchanged) {
  TempDir d;
  for (const Tampering& t : kTamperings) {
    SCOPED_TRACE(t.name);
    const std::string db = tampered_db(d, std::string(t.name) + ".sqlite", t.sql);
    const std::string before = slurp(db);
    const std::string good = d / (std::string(t.name) + "-good.json");
    write_text(good, slurp(std::string(TILEKIT_SOURCE_DIR) + "/tilesets/data/packing-corner-2.json"));
    const std::string other = d / (std::string(t.name) + "-other.sqlite");
    ASSERT_EQ(run_cli("pack --kind corner --colors 2 --method construct --quiet --db " + other).code, 0);
    for (const std::string& cmd :
         {"db stats --db " + db, "db list --table runs --db " + db, "db export --db " + db,
          "db add " + good + " --db " + db, "db merge " + d / (std::string(t.name) + "-out.sqlite") + " " + db,
          "db merge " + db + " " + other, "pack --kind corner --colors 2 --mode count --quiet --db " + db,
          "atlas lookup --kind corner --colors 2 --db " + db}) {
      SCOPED_TRACE(cmd);
      expect_exit2_naming(run_cli(cmd), t.message);
      EXPECT_EQ(slurp(db), before);
      EXPECT_FALSE(fs::exists(db + "-wal"));
      EXPECT_FALSE(fs::exists(db + "-journal"));
    }
    EXPECT_FALSE(fs::exists(d / (std::string(t.name) + "-out.sqlite")));
  }
}

TEST(DamagedDatabase, AReadOnlyFolderStillServesTheCommandsThatOnlyRead) {
  // Root reads and writes every folder whatever its mode: as root, the commands run as nobody.
  const std::string as = geteuid() == 0 ? "setpriv --reuid=65534 --regid=65534 --clear-groups " : "";
  TempDir d;
  fs::create_directories(d / "ro");
  const std::string db = d / "ro/r.sqlite";
  ASSERT_EQ(run_cli("pack --kind corner --colors 2 --method construct --quiet --db " + db).code, 0);
  const auto rx = fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read | fs::perms::group_exec |
                  fs::perms::others_read | fs::perms::others_exec;
  fs::permissions(d.path, rx);
  fs::permissions(d / "ro", rx);
  fs::permissions(db, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  const std::string before = slurp(db);
  for (const std::string& cmd : {"db stats --db " + db, "db list --db " + db, "db show 1 --db " + db}) {
    const CliResult r = run_cli_prefixed(as, cmd + " --json");
    EXPECT_EQ(r.code, 0) << cmd << ": " << r.err;
  }
  EXPECT_EQ(slurp(db), before);
  EXPECT_EQ(std::distance(fs::directory_iterator(d / "ro"), fs::directory_iterator()), 1);
  fs::permissions(d / "ro", fs::perms::owner_all);
  fs::permissions(d.path, fs::perms::owner_all);
}

TEST(DamagedDatabase, AKilledRunIsMarkedKilledWhenTheDatabaseIsNextOpened) {
  TempDir d;
  const std::string db = d / "r.sqlite";
  // A run row as a killed process leaves it: "running", with the pid of a process that is gone.
  ASSERT_EQ(run_cli("pack --kind corner --colors 2 --method construct --quiet --db " + db).code, 0);
  exec_sql(db, "UPDATE runs SET status = 'running', finished_at = NULL, pid = 999999999, pid_start = 1");
  const CliResult listed = run_cli("db list --table runs --json --db " + db);  // read-only: shown as killed
  ASSERT_EQ(listed.code, 0) << listed.err;
  EXPECT_EQ(listed.json()["rows"][0]["status"], "killed");
  ASSERT_EQ(run_cli("pack --kind corner --colors 2 --method construct --quiet --db " + db).code, 0);
  sqlite3* raw = nullptr;
  ASSERT_EQ(sqlite3_open(db.c_str(), &raw), SQLITE_OK);
  sqlite3_stmt* st = nullptr;
  sqlite3_prepare_v2(raw, "SELECT status FROM runs WHERE id = 1", -1, &st, nullptr);
  ASSERT_EQ(sqlite3_step(st), SQLITE_ROW);
  EXPECT_STREQ(reinterpret_cast<const char*>(sqlite3_column_text(st, 0)), "killed");  // stored by the writer
  sqlite3_finalize(st);
  sqlite3_close(raw);
}

namespace {

// A checkpoint of an interrupted two-colour Wang count, its JSON body changed by `edit` and
// sealed again with a valid checksum.
struct CheckpointCase {
  TempDir d;
  std::string db = d / "r.sqlite", original = d / "c.ckpt";
  CheckpointCase() {
    run_cli("pack --kind wang --colors 2 --mode count --threads 1 --quiet --checkpoint " + original +
            " --time-limit 0.05 --db " + db);
  }
  std::string edited(const std::string& name, const std::function<void(nlohmann::json&)>& edit) const {
    const std::string text = slurp(original);
    const std::string_view body =
        open_checkpoint(text, "TILEKIT-CHECKPOINT", kCheckpointVersion, kCheckpointVersion, original);
    nlohmann::json j = nlohmann::json::parse(body);
    edit(j);
    const std::string path = d / name;
    write_text(path, seal_checkpoint("TILEKIT-CHECKPOINT", kCheckpointVersion, j.dump()));
    return path;
  }
  std::string runs() const { return run_cli("db list --table runs --json --db " + db).out; }
};

}  // namespace

TEST(DamagedCheckpoint, JsonInStringFieldsIsDepthLimitedAndTypeChecked) {
  CheckpointCase c;
  ASSERT_TRUE(fs::exists(c.original));
  const std::string runs = c.runs();
  for (const std::string& fingerprint :
       {std::string(100000, '[') + std::string(100000, ']'),
        "{\"a\":" + std::string(5000, '[') + "1" + std::string(5000, ']') + "}", std::string("[1]"),
        std::string("\"text\""), std::string("{\"mode\":[[{}]]}"), std::string("not json")}) {
    const std::string path = c.edited("f.ckpt", [&](nlohmann::json& j) { j["search"]["fingerprint"] = fingerprint; });
    const std::string before = slurp(path);
    const CliResult r = run_cli("pack --resume " + path + " --quiet");
    expect_exit2_naming(r, "does not match this search");
    EXPECT_EQ(slurp(path), before);  // refused: the checkpoint is not rewritten
  }
  EXPECT_EQ(c.runs(), runs);  // and no run row was added
}

TEST(DamagedCheckpoint, WrongTypesInNestedObjectsAreExit2) {
  CheckpointCase c;
  const std::vector<std::pair<std::function<void(nlohmann::json&)>, std::string>> cases = {
      {[](nlohmann::json& j) { j["request"]["shard"] = nlohmann::json::array(); }, "the request's shard is malformed"},
      {[](nlohmann::json& j) { j["request"]["candidates"] = "plain"; }, "the request's candidates is malformed"},
      {[](nlohmann::json& j) { j["request"]["time_limit"] = "soon"; }, "the request's time_limit is malformed"},
      {[](nlohmann::json& j) {
         j["search"]["in_flight"] = {{{"index", 0}, {"path", {{1}}}}};
       },
       "expected an array of 2 elements"},
      {[](nlohmann::json& j) {
         j["search"]["finished_counts"] = {1, 2, 3};
       },
       "expected a JSON object"},
  };
  for (const auto& [edit, message] : cases) {
    const std::string path = c.edited("t.ckpt", edit);
    expect_exit2_naming(run_cli("pack --resume " + path + " --quiet"), message);
  }
}

TEST(DamagedCheckpoint, FinishedMarksOutsideTheShardOrWithoutTheirCountsAreRefused) {
  CheckpointCase c;
  const std::string runs = c.runs();
  // A finished mark cleared while its counts stay in the total: resuming would count it twice.
  const std::string unmarked = c.edited("u.ckpt", [](nlohmann::json& j) {
    std::string& bits = j["search"]["finished"].get_ref<std::string&>();
    bits[0] = 'e';
  });
  expect_exit2_naming(run_cli("pack --resume " + unmarked + " --quiet"), "are marked finished");
  // The counts of one finished subproblem changed: the total no longer adds up.
  const std::string recounted = c.edited("r.ckpt", [](nlohmann::json& j) { j["search"]["finished_each"][0][0] = 7; });
  expect_exit2_naming(run_cli("pack --resume " + recounted + " --quiet"), "but their total says");
  // The same run relabelled as shard 0/2: half of its finished subproblems belong to shard 1.
  const std::string sharded = c.edited("s.ckpt", [](nlohmann::json& j) {
    nlohmann::json f = nlohmann::json::parse(j["search"]["fingerprint"].get<std::string>());
    f["shard"] = {0, 2};
    j["search"]["fingerprint"] = f.dump();
    j["request"]["shard"] = "0/2";
  });
  const std::string before = slurp(sharded);
  expect_exit2_naming(run_cli("pack --resume " + sharded + " --quiet"), "finished subproblem 1 is not in shard 0/2");
  EXPECT_EQ(slurp(sharded), before);
  EXPECT_EQ(c.runs(), runs);
  // A consistent change (a subproblem unmarked with its counts) resumes to the exact count.
  const std::string redo = c.edited("ok.ckpt", [](nlohmann::json& j) {
    nlohmann::json& s = j["search"];
    s["finished"].get_ref<std::string&>()[0] = 'e';
    const nlohmann::json e = s["finished_each"][0];
    s["finished_each"].erase(0);
    s["finished_counts"]["solutions"] =
        s["finished_counts"]["solutions"].get<std::uint64_t>() - e[0].get<std::uint64_t>();
    s["finished_counts"]["orbits"] = s["finished_counts"]["orbits"].get<std::uint64_t>() - e[1].get<std::uint64_t>();
    s["finished_counts"]["nodes"] = s["finished_counts"]["nodes"].get<std::uint64_t>() - e[2].get<std::uint64_t>();
  });
  const CliResult r = run_cli("pack --resume " + redo + " --time-limit 0 --quiet --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.json()["solutions"], 203520);
  EXPECT_EQ(r.json()["orbits"], 538);
}

TEST(DamagedCheckpoint, ResumeAloneKeepsTheOriginalTimeLimit) {
  CheckpointCase c;
  EXPECT_EQ(nlohmann::json::parse(open_checkpoint(slurp(c.original), "TILEKIT-CHECKPOINT", kCheckpointVersion,
                                                  kCheckpointVersion, c.original))["request"]["time_limit"],
            0.05);
  // A count far longer than its stored limit (the C=3 corner count runs for minutes): resuming
  // with the checkpoint alone stops at the stored 0.2 s again; --time-limit 0 given again runs to
  // the end of the Wang count.
  const std::string longer = c.d / "long.ckpt";
  ASSERT_EQ(run_cli("pack --kind corner --colors 3 --mode count --threads 1 --quiet --checkpoint " + longer +
                    " --time-limit 0.2 --db " + c.db)
                .code,
            0);
  const CliResult r = run_cli("pack --resume " + longer + " --quiet --json --db " + c.db);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(r.json()["complete"]) << "the stored limit applies again";
  EXPECT_LT(r.json()["seconds"].get<double>(), 30.0);
  const CliResult all = run_cli("pack --resume " + c.original + " --time-limit 0 --quiet --json");
  ASSERT_EQ(all.code, 0) << all.err;
  EXPECT_EQ(all.json()["solutions"], 203520);
}

TEST(DamagedCheckpoint, OlderFormatVersionsAreRefusedNamingTheVersion) {
  CheckpointCase c;
  std::string text = slurp(c.original);
  text.replace(0, text.find('\n'), "TILEKIT-CHECKPOINT 2");
  const std::string old = c.d / "old.ckpt";
  write_text(old, text);
  expect_exit2_naming(run_cli("pack --resume " + old + " --quiet"),
                      "format version 2 is not supported (this build reads version 3)");
}
