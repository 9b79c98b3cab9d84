// Hostile or careless input, case by case (README.md, "Bad input and limits"), is exit 2 with
// one line naming the file (and line or JSON path) and the problem, creates no file, and never
// crashes, hangs or leaks an internal error. Valid inputs that used to crash (a 30 KB comment)
// now succeed.
#include <gtest/gtest.h>
#include <omp.h>
#include <sqlite3.h>

#include <filesystem>
#include <fstream>

#include "checkpoints/checkpoint.hpp"
#include "results/results_db.hpp"
#include "tests/cli_runner.hpp"

using namespace tilekit;
using namespace tilekit::test;
namespace fs = std::filesystem;

namespace {

// Exit code 2, exactly one line on stderr, and that line is "tilekit: " + `message`.
void expect_refused(const CliResult& r, const std::string& message) {
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(r.err, "tilekit: " + message + "\n");
  EXPECT_EQ(r.err.find("internal error"), std::string::npos);
}

// A wrong type, a number beyond a double (1e999) and a 100-digit integer in one field.
const std::string k100Digits = std::string(100, '7');

}  // namespace

TEST(BadInput, PackSetWithHugeColoursIsRefusedNotACrash) {
  TempDir d;
  write_text(d / "big.tiles", "# kind: corner\n0 0 0 1000000\n");
  expect_refused(run_cli("pack --set " + d / "big.tiles" + " --size 1x1 --db " + d / "db.sqlite"),
                 d / "big.tiles" + ":2: colour 1000000 is too large (at most 65535)");
  write_text(d / "c300.tiles", "# kind: corner\n0 0 0 300\n");  // fits the parser, not a 32-bit tile index
  expect_refused(run_cli("pack --set " + d / "c300.tiles" + " --size 1x1 --db " + d / "db.sqlite"),
                 d / "c300.tiles" +
                     ": a corner set over 301 colours is too large: tile indices (thesis eq. 2.5) are "
                     "32-bit, so at most 256 colours");
  write_text(d / "five.tiles", "0 0 0 0 0\n");
  expect_refused(run_cli("pack --set " + d / "five.tiles" + " --db " + d / "db.sqlite"),
                 d / "five.tiles" + ":1: expected 4 colours (n s w e), found more than 4 fields");
  EXPECT_FALSE(fs::exists(d / "db.sqlite"));  // refused before the database is touched
}

TEST(BadInput, PackSizeThatCannotHoldThePackingIsRefusedAtOnce) {
  TempDir d;
  expect_refused(run_cli("pack --set complete-wang-2 --size 1x1 --db " + d / "db.sqlite"),
                 "--size 1x1: a packing of the 16 tiles of complete-wang-2 needs rows*cols = 16, not 1");
  expect_refused(run_cli("pack --set complete-wang-2 --size 4x4x4 --db " + d / "db.sqlite"),
                 "--size ROWSxCOLS: expected two positive integers such as 16x16, got '4x4x4'");
  EXPECT_FALSE(fs::exists(d / "db.sqlite"));
}

TEST(BadInput, DeeplyNestedJsonIsRefusedForEveryReader) {
  TempDir d;
  write_text(d / "deep.json", "{\"a\":" + std::string(100000, '[') + std::string(100000, ']') + "}");
  const std::string msg = d / "deep.json" + ":1: invalid JSON: nested deeper than 64 levels";
  expect_refused(run_cli("tileset show " + d / "deep.json"), msg);
  expect_refused(run_cli("check " + d / "deep.json"), msg);
  expect_refused(run_cli("db add " + d / "deep.json" + " --db " + d / "db.sqlite"), msg);
  expect_refused(run_cli("tile --set complete-corner-2 --algo controlled --size 4x4 --map " + d / "deep.json"), msg);
  write_text(d / "deepobj.json", "{\"version\":1,\"groups\":" + std::string(1000, '[') + std::string(1000, ']') + "}");
  expect_refused(run_cli("pack --portfolio-report --portfolio-stats " + d / "deepobj.json"),
                 d / "deepobj.json" +
                     " (portfolio statistics; delete the file to start afresh):1: invalid JSON: "
                     "nested deeper than 64 levels");
  EXPECT_FALSE(fs::exists(d / "db.sqlite"));
}

TEST(BadInput, OutOfRangeNumbersAndWrongTypesNameTheJsonPath) {
  TempDir d;
  const std::string tiling = R"({"kind":"wang","colors":2,"rows":1,"cols":1,"torus":true,"cells":[[X]]})";
  auto with = [&](const std::string& v) {
    std::string t = tiling;
    t.replace(t.find('X'), 1, v);
    return t;
  };
  write_text(d / "e999.json", with("1e999"));
  expect_refused(run_cli("check " + d / "e999.json"),
                 d / "e999.json" + ": invalid JSON: number overflow parsing '1e999'");
  write_text(d / "digits.json", with(k100Digits));
  expect_refused(
      run_cli("db add " + d / "digits.json" + " --db " + d / "db.sqlite"),
      d / "digits.json" + ": cells[0][0]: expected an integer between 0 and 4294967295, got 7.777777777777778e+99");
  write_text(d / "array.json", with("[]"));
  expect_refused(run_cli("check " + d / "array.json"),
                 d / "array.json" + ": cells[0][0]: expected an integer between 0 and 4294967295, got []");
  write_text(d / "nullrows.json", R"({"kind":"wang","colors":2,"rows":null,"cols":1,"torus":true,"cells":[[0]]})");
  expect_refused(run_cli("check " + d / "nullrows.json"),
                 d / "nullrows.json" + ": rows: expected an integer between 1 and 1048576, got null");
  write_text(d / "set.json", R"({"kind":"corner","tiles":[[0,0,0,1e999]]})");
  expect_refused(run_cli("pack --set " + d / "set.json" + " --db " + d / "db.sqlite"),
                 d / "set.json" + ": invalid JSON: number overflow parsing '1e999'");
  write_text(d / "set2.json", R"({"kind":"corner","tiles":[[0,0,0,null]]})");
  expect_refused(run_cli("pack --set " + d / "set2.json" + " --db " + d / "db.sqlite"),
                 d / "set2.json" + ": tiles[0][3]: expected an integer between 0 and 65535, got null");
  write_text(d / "map.json", R"({"colors":2,"rows":1,"cols":1,"p":[[[0.5,"0.5"]]]})");
  expect_refused(run_cli("tile --set complete-corner-2 --algo controlled --size 4x4 --map " + d / "map.json"),
                 d / "map.json" + ": p[0][0][1]: expected a number, got \"0.5\"");
  write_text(d / "stats.json", R"({"version":1,"groups":{"corner/4/t=0,4:pi=1,2,3,0":{"tries":)" + k100Digits +
                                   R"(,"successes":0,"success_seconds":[]}}})");
  expect_refused(run_cli("pack --portfolio-report --portfolio-stats " + d / "stats.json"),
                 d / "stats.json" +
                     " (portfolio statistics; delete the file to start afresh): "
                     "groups[\"corner/4/t=0,4:pi=1,2,3,0\"].tries: expected an integer between 0 and "
                     "18446744073709551615, got 7.777777777777778e+99");
  EXPECT_FALSE(fs::exists(d / "db.sqlite"));
}

TEST(BadInput, AtlasLookupWithExtremeColoursIsRefusedNotBadAlloc) {
  expect_refused(run_cli("atlas lookup --kind wang --colors 255"),
                 "--colors must be between 1 and 64 for a packing or atlas of the complete set, got 255");
  expect_refused(run_cli("atlas lookup --kind corner --colors 4294967295"),
                 "--colors must be between 1 and 64 for a packing or atlas of the complete set, got 4294967295");
}

TEST(BadInput, RefusedMergeLeavesNoNewDatabase) {
  TempDir d;
  write_text(d / "bad.json",
             R"({"tilekit_results":1,"runs":[],"tilesets":[],"conversions":[],"solutions":[{"kind":"wang"}]})");
  expect_refused(run_cli("db merge " + d / "out.sqlite" + " " + d / "bad.json"),
                 d / "bad.json" + ": solutions[0]: missing \"colors\"");
  write_text(
      d / "bad2.json",
      R"({"tilekit_results":1,"runs":[{"uid":"u","command":"pack","nodes":-5}],"tilesets":[],"conversions":[],"solutions":[]})");
  expect_refused(run_cli("db merge " + d / "out.sqlite" + " " + d / "bad2.json"),
                 d / "bad2.json" + ": runs[0].nodes: expected an integer between 0 and 9223372036854775807, got -5");
  for (const char* f : {"out.sqlite", "out.sqlite-wal", "out.sqlite-shm", "out.sqlite-journal"})
    EXPECT_FALSE(fs::exists(d / f)) << f;
}

TEST(BadInput, ALongCommentLineIsReadNotARegexStackOverflow) {
  TempDir d;
  write_text(d / "long.tiles",
             "# " + std::string(30000, 'a') + "\n# source: " + std::string(3000, 'b') + "\n0 1 1 0\n");
  CliResult r = run_cli("tileset show " + d / "long.tiles" + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.json()["tiles"], 1);
  EXPECT_EQ(r.json()["source"], std::string(3000, 'b'));
}

TEST(BadInput, ThreadCountsBeyondTheBoundAreRefused) {
  TempDir d;
  for (const char* t : {"100000", "2147483647", "-1"})
    expect_refused(
        run_cli(std::string("pack --kind wang --colors 2 --mode count --threads ") + t + " --db " + d / "db.sqlite"),
        std::string("--threads must be between 0 (every core) and 4096, got ") + t);
  EXPECT_FALSE(fs::exists(d / "db.sqlite"));
  // 0 is every core, the same for every command (base/run_control.hpp resolve_threads).
  CliResult all =
      run_cli("pack --kind wang --colors 2 --mode count --quiet --json --threads 0 --db " + d / "all.sqlite");
  ASSERT_EQ(all.code, 0) << all.err;
  EXPECT_EQ(all.json()["threads"], omp_get_max_threads());
  CliResult pts = run_cli("points generate --window 0,0,4,4 --density 10 --threads 0 --quiet --json");
  ASSERT_EQ(pts.code, 0) << pts.err;
  EXPECT_EQ(pts.json()["threads"], omp_get_max_threads());
}

TEST(BadInput, ShardsBeyondIntAreRefusedNotWrappedToShardZero) {
  TempDir d;
  expect_refused(run_cli("pack --kind wang --colors 2 --mode count --shard 4294967296/1 --db " + d / "db.sqlite"),
                 "--shard must be I/N with 0 <= I < N <= 1000000, got '4294967296/1'");
  expect_refused(run_cli("pack --kind wang --colors 2 --mode count --shard 1/2x --db " + d / "db.sqlite"),
                 "--shard must be I/N with 0 <= I < N <= 1000000, got '1/2x'");
  EXPECT_FALSE(fs::exists(d / "db.sqlite"));
}

TEST(BadInput, CheckpointWithHugeRestartCountIsRefusedNotAnEndlessLubyLoop) {
  TempDir d;
  SearchState st;
  st.fingerprint = "{}";
  st.restarts = std::uint64_t(1) << 63;
  st.restart_nodes = 1;
  write_checkpoint(d / "ck", st);
  expect_refused(run_cli("pack --kind corner --colors 3 --method search --plain --resume " + d / "ck" + " --db " +
                         d / "db.sqlite"),
                 "checkpoint " + d / "ck" +
                     ": search: inconsistent: 9223372036854775808 restarts is more than the limit of 1099511627776");
}

TEST(BadInput, CheckpointListingAnInFlightSubproblemTwiceIsRefused) {
  TempDir d;
  const std::string run = "pack --kind wang --colors 2 --mode count --threads 2 --quiet --checkpoint " + d / "ck" +
                          " --db " + d / "db.sqlite";
  ASSERT_EQ(run_cli(run).code, 0);
  SearchState st = read_checkpoint(d / "ck");  // the final checkpoint: everything finished
  ASSERT_GT(st.subproblem_count, 3u);
  st.finished[3] = false;  // with its counts, so that only the in-flight list is wrong
  const SearchCounters c3 = st.finished_each[3];
  st.finished_each.erase(st.finished_each.begin() + 3);
  st.finished_counts.solutions -= c3.solutions;
  st.finished_counts.orbits -= c3.orbits;
  st.finished_counts.nodes -= c3.nodes;
  st.in_flight = {{3, {}, {}}, {3, {}, {}}};
  write_checkpoint(d / "ck", st);  // a valid checksum over an impossible state
  expect_refused(run_cli(run + " --resume " + d / "ck"),
                 "checkpoint " + d / "ck" + ": search: inconsistent: in-flight subproblem 3 is listed twice");
}

TEST(BadInput, Latin1BytesAreRefusedAtInputNamingFileAndLine) {
  TempDir d;
  write_text(d / "latin1.tiles", "# source: caf\xe9 au lait\n0 1 1 0\n");
  const std::string msg = d / "latin1.tiles" +
                          ":1: not UTF-8 text (byte 0xe9 at column 14); Tilekit reads UTF-8 only: convert the file "
                          "(e.g. `iconv -f latin1 -t utf-8`)";
  expect_refused(run_cli("tileset show " + d / "latin1.tiles" + " --json"), msg);
  expect_refused(run_cli("aperiodic verify " + d / "latin1.tiles" + " --db " + d / "db.sqlite"), msg);
}

TEST(BadInput, StoredNonUtf8TextStillExportsListsAndShowsAsJson) {
  // A tile set stored by an older version with a Latin-1 comment: the reading commands print
  // U+FFFD for the bad byte instead of failing.
  TempDir d;
  const std::string db = d / "db.sqlite";
  { ResultsDb created(db); }
  sqlite3* h = nullptr;
  ASSERT_EQ(sqlite3_open(db.c_str(), &h), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(h,
                         "INSERT INTO tilesets(name, kind, tiles, colors, content_hash, source, text, created_at) "
                         "VALUES ('s', 'wang', 1, 2, 'h', 'caf\xe9', '# caf\xe9\n0 1 1 0\n', 'now')",
                         nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(h);
  for (const std::string cmd : {"db export", "db list --table tilesets --json", "db show 1 --table tilesets --json"}) {
    CliResult r = run_cli(cmd + " --db " + db);
    ASSERT_EQ(r.code, 0) << cmd << ": " << r.err;
    EXPECT_NE(r.out.find("caf\xef\xbf\xbd"), std::string::npos) << cmd;  // U+FFFD
    EXPECT_TRUE(nlohmann::json::accept(r.out)) << cmd;
  }
}

TEST(BadInput, TilesetShowJsonReadsBackAsATileSetFile) {
  TempDir d;
  for (const char* set : {"kari-14", "complete-corner-2", "compact-wang-3"}) {
    CliResult shown = run_cli(std::string("tileset show ") + set + " --json");
    ASSERT_EQ(shown.code, 0) << shown.err;
    write_text(d / "set.json", shown.out);
    CliResult again = run_cli("tileset show " + d / "set.json" + " --json");
    ASSERT_EQ(again.code, 0) << set << ": " << again.err;
    auto a = shown.json(), b = again.json();
    for (const char* k : {"kind", "name", "source", "tiles", "colors", "list"})
      EXPECT_EQ(a[k], b[k]) << set << " " << k;
  }
  write_text(d / "lying.json", R"({"kind":"wang","tiles":3,"list":[[0,1,1,0]]})");
  expect_refused(run_cli("tileset show " + d / "lying.json"),
                 d / "lying.json" + ": tiles: says 3 tiles but \"list\" holds 1");
}

TEST(BadInput, DamagedDatabaseHeaderIsRefusedAndUntouched) {
  TempDir d;
  const std::string db = d / "db.sqlite";
  { ResultsDb created(db); }
  std::string bytes = slurp(db);
  bytes[18] = 3;
  write_text(db, bytes);
  for (const std::string cmd : {"db stats --db ", "db list --db ", "pack --quiet --kind corner --colors 2 --db "}) {
    CliResult r = run_cli(cmd + db);
    expect_refused(r, db + ": not a usable Tilekit results database: its SQLite header is damaged (byte 18 is 3; "
                           "SQLite writes 1 or 2); the file was left untouched");
  }
  EXPECT_EQ(slurp(db), bytes);
}

TEST(BadInput, RefusingAForeignWalDatabaseLeavesNoSideFiles) {
  TempDir d;
  const std::string db = d / "foreign.sqlite";
  sqlite3* h = nullptr;
  ASSERT_EQ(sqlite3_open(db.c_str(), &h), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(h, "PRAGMA journal_mode = WAL; CREATE TABLE t(x); INSERT INTO t VALUES (1)", nullptr, nullptr,
                         nullptr),
            SQLITE_OK);
  sqlite3_close(h);
  ASSERT_FALSE(fs::exists(db + "-wal"));
  const std::string before = slurp(db);
  for (const std::string cmd : {"db stats --db ", "db list --db ", "pack --kind corner --colors 2 --db "}) {
    CliResult r = run_cli(cmd + db);
    expect_refused(r, db + ": not a usable Tilekit results database: an SQLite database of another application "
                           "(application_id 0x0, 1 tables); the file was left untouched");
    EXPECT_FALSE(fs::exists(db + "-wal")) << cmd;
    EXPECT_FALSE(fs::exists(db + "-shm")) << cmd;
  }
  EXPECT_EQ(slurp(db), before);
}

TEST(BadInput, FileMessagesNameTheLine) {
  TempDir d;
  write_text(d / "dup.tiles", "# a set\n0 1 1 0\n1 1 0 0\n0 1 1 0\n");
  expect_refused(run_cli("tileset show " + d / "dup.tiles"),
                 d / "dup.tiles" + ":4: duplicate tile: repeats the tile of " + d / "dup.tiles" + ":2 (0 1 1 0)");
  write_text(d / "dup.json", R"({"tiles":[[0,1,1,0],[0,1,1,0]]})");
  expect_refused(
      run_cli("tileset show " + d / "dup.json"),
      d / "dup.json" + ": tiles[1]: duplicate tile: repeats the tile of " + d / "dup.json" + ": tiles[0] (0 1 1 0)");
  write_text(d / "ck", "TILEKIT-CHECKPOINT 3\nbytes 99999999999999999999999 fnv1a64 0000000000000000\n{}");
  expect_refused(run_cli("pack --kind wang --colors 2 --mode count --resume " + d / "ck" + " --db " + d / "db.sqlite"),
                 "checkpoint " + d / "ck" + ": corrupt header");
}

TEST(BadInput, PortfolioCheckpointIsValidatedStructurally) {
  // A valid checksum over an impossible portfolio state: each is refused before anything runs.
  TempDir d;
  SearchState engine;
  engine.fingerprint = "{}";
  engine.subproblem_count = 4;
  engine.finished = {false, false, false, false};
  engine.in_flight = {{3, {}, {}}, {3, {}, {}}};
  PortfolioState twice;
  twice.fingerprint = "{}";
  twice.candidates = {{"plain", false, 0, 0, 0, std::nullopt}, {"plain", false, 0, 0, 0, std::nullopt}};
  PortfolioState past = twice;
  past.candidates.pop_back();
  past.next = 2;
  PortfolioState bad_engine = past;
  bad_engine.next = 0;
  bad_engine.candidates[0].engine = engine;
  PortfolioState side_past = past;
  side_past.next = 0;
  side_past.side_next = 5;
  const std::string run = "pack --kind corner --colors 4 --quiet --resume " + d / "ck" + " --db " + d / "db.sqlite";
  const std::string where = "checkpoint " + d / "ck" + ": portfolio";
  const std::pair<PortfolioState, std::string> cases[] = {
      {twice, where + ".candidates[1].name: candidate plain is listed twice"},
      {past, where + ".next: schedule position 2 is past the 1 candidates"},
      {side_past, where + ".side_next: side-lane position 5 is past the 1 candidates"},
      {bad_engine, where + ".candidates[0].engine: inconsistent: in-flight subproblem 3 is listed twice"}};
  for (const auto& [state, message] : cases) {
    write_checkpoint(d / "ck", CheckpointFile{nullptr, std::nullopt, state});
    const std::string before = slurp(d / "ck");
    expect_refused(run_cli(run), message);
    EXPECT_EQ(slurp(d / "ck"), before);
    EXPECT_FALSE(fs::exists(d / "db.sqlite"));
  }
}

TEST(BadInput, AperiodicVerifyTimeLimitMustBeANonNegativeNumber) {
  expect_refused(run_cli("aperiodic verify culik-13 --time-limit -1"),
                 "--time-limit: expected a number of seconds >= 0, got '-1' (see --help)");
}
