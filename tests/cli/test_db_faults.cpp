// The results database under faults: SIGKILL in the middle of `db merge`, `db add`
// and a storing `pack`; two writers on one file; a full disk; a read-only file. Each time the
// database passes PRAGMA integrity_check and holds all or nothing of the interrupted
// transaction, and a refused write is exit 2 with one line naming the file.
#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <random>
#include <thread>

#include "results/results_db.hpp"
#include "tests/cli_runner.hpp"

using namespace tilekit;
using namespace tilekit::test;
namespace fs = std::filesystem;

namespace {

// A distinct 4x4 corner grid per n < 16^16 (not a valid tiling: storage only).
Tiling grid(std::uint64_t n) {
  Tiling t(TileKind::Corner, 2, 4, 4, true);
  for (auto& c : t.cells) c = TileIndex(n % 16), n /= 16;
  return t;
}

// A database of `count` solutions numbered from `first`, in one run.
void make_db(const std::string& path, std::uint64_t first, std::uint64_t count) {
  ResultsDb db(path);
  RunRecord run;
  run.command = "test";
  std::vector<SolutionRecord> batch;
  for (std::uint64_t i = first; i < first + count; ++i) {
    SolutionRecord s;
    s.tiling = grid(i);
    s.method = "test";
    batch.push_back(std::move(s));
  }
  db.add_run_with_solutions(run, batch);
}

struct DbState {
  std::string integrity;
  std::int64_t solutions = -1, runs = -1;
};

// Integrity and counts, read with plain SQLite (recovering the WAL of a killed writer).
DbState state_of(const std::string& path) {
  DbState st;
  sqlite3* h = nullptr;
  if (sqlite3_open_v2(path.c_str(), &h, SQLITE_OPEN_READWRITE, nullptr) != SQLITE_OK) {
    sqlite3_close(h);
    return st;
  }
  auto one = [&](const char* sql) {
    sqlite3_stmt* s = nullptr;
    std::string v;
    if (sqlite3_prepare_v2(h, sql, -1, &s, nullptr) == SQLITE_OK && sqlite3_step(s) == SQLITE_ROW)
      v = reinterpret_cast<const char*>(sqlite3_column_text(s, 0));
    sqlite3_finalize(s);
    return v;
  };
  st.integrity = one("PRAGMA integrity_check");
  const std::string sols = one("SELECT COUNT(*) FROM solutions"), runs = one("SELECT COUNT(*) FROM runs");
  st.solutions = sols.empty() ? 0 : std::stoll(sols);  // no table yet: created before the kill
  st.runs = runs.empty() ? 0 : std::stoll(runs);
  sqlite3_close(h);
  return st;
}

// Runs `args` and SIGKILLs it after `ms` milliseconds; true when the kill ended it.
bool kill_after(const std::vector<std::string>& args, int ms, const TempDir& d) {
  pid_t pid = spawn_tilekit(args, d / "out", d / "err");
  EXPECT_GT(pid, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(ms));
  kill(pid, SIGKILL);
  const int code = wait_exit(pid);
  EXPECT_TRUE(code == 128 + SIGKILL || code == 0) << code << ": " << slurp(d / "err");
  return code == 128 + SIGKILL;
}

// How long one uninterrupted run of `args` takes here, in milliseconds: kill delays are drawn
// inside it, so kills land mid-run on a fast machine and on a loaded one alike.
int run_ms(const std::vector<std::string>& args, const TempDir& d) {
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = spawn_tilekit(args, d / "out", d / "err");
  EXPECT_GT(pid, 0);
  EXPECT_EQ(wait_exit(pid), 0) << slurp(d / "err");
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - t0);
  return std::max(2, int(ms.count()));
}

// A small file system mounted for one test (tmpfs, or an ext4 loop file), or nothing when this
// process may not mount (not root, or no CAP_SYS_ADMIN): then the test is skipped and says why.
struct SmallDisk {
  std::string dir, why_not;
  bool mounted = false;
  SmallDisk(const TempDir& d, const char* size) : dir(d / "disk") {
    fs::create_directories(dir);
    if (geteuid() != 0) {
      why_not = "not root: cannot mount a small file system";
      return;
    }
    const std::string opts = std::string("size=") + size + ",mode=0777";
    if (mount("tmpfs", dir.c_str(), "tmpfs", 0, opts.c_str()) == 0) {
      mounted = true;
      return;
    }
    why_not = std::string("mounting a tmpfs failed: ") + std::strerror(errno);
  }
  bool remount_read_only() { return mount("tmpfs", dir.c_str(), "tmpfs", MS_REMOUNT | MS_RDONLY, nullptr) == 0; }
  ~SmallDisk() {
    if (mounted) umount2(dir.c_str(), MNT_DETACH);
  }
};

}  // namespace

TEST(DbFaults, SigkillDuringMergeLeavesAllOrNothingOfTheMerge) {
  TempDir d;
  const std::uint64_t n = 40000;
  make_db(d / "in.sqlite", 0, n);
  std::mt19937 rng(15);
  int killed = 0;
  make_db(d / "timed.sqlite", 1'000'000, 10);
  const int full = run_ms({"db", "merge", d / "timed.sqlite", d / "in.sqlite", "--quiet"}, d);
  for (int round = 0; round < 12; ++round) {
    const std::string out = d / ("out" + std::to_string(round) + ".sqlite");
    make_db(out, 1'000'000, 10);  // the target already holds 10 solutions of its own
    if (!kill_after({"db", "merge", out, d / "in.sqlite", "--quiet"}, int(full / 10 + rng() % full), d)) continue;
    ++killed;
    const DbState st = state_of(out);
    EXPECT_EQ(st.integrity, "ok") << round;
    EXPECT_TRUE(st.solutions == 10 || st.solutions == std::int64_t(10 + n)) << round << ": " << st.solutions;
    EXPECT_TRUE(st.runs == 1 || st.runs == 2) << round;
  }
  EXPECT_GE(killed, 3);
  RecordProperty("killed_merges", killed);
}

TEST(DbFaults, SigkillDuringDbAddStoresTheWholeRunOrNothing) {
  TempDir d;
  std::vector<std::string> args{"db", "add", "--db", d / "db.sqlite"};
  // 400 distinct valid tilings: a 1x1 bounded tiling of each of the 256 corner tiles over 4
  // colours, then 144 of the 625 over 5.
  for (int i = 0; i < 400; ++i) {
    const std::string f = d / ("t" + std::to_string(i) + ".json");
    write_text(f, fmt::format(R"({{"kind":"corner","colors":{},"rows":1,"cols":1,"torus":false,"cells":[[{}]]}})",
                              i < 256 ? 4 : 5, i < 256 ? i : i - 256));
    args.push_back(f);
  }
  std::mt19937 rng(16);
  int killed = 0;
  make_db(d / "db.sqlite", 0, 5);
  const int full = run_ms(args, d);
  // Rounds until 5 kills landed mid-run (a kill drawn near the end may come after the add).
  for (int round = 0; round < 40 && killed < 5; ++round) {
    fs::remove(d / "db.sqlite");
    make_db(d / "db.sqlite", 0, 5);
    if (!kill_after(args, int(full / 10 + rng() % full), d)) continue;
    ++killed;
    const DbState st = state_of(d / "db.sqlite");
    EXPECT_EQ(st.integrity, "ok");
    // the test's own run and 5 solutions, plus either nothing or the add's run and 400 solutions
    EXPECT_TRUE((st.runs == 1 && st.solutions == 5) || (st.runs == 2 && st.solutions == 405))
        << st.runs << " runs, " << st.solutions << " solutions";
  }
  EXPECT_GE(killed, 3);
}

TEST(DbFaults, SigkillDuringAStoringPackKeepsWholeBatches) {
  TempDir d;
  std::mt19937 rng(17);
  int killed = 0;
  for (int round = 0; round < 4; ++round) {
    const std::string db = d / ("db" + std::to_string(round) + ".sqlite");
    if (!kill_after({"pack", "--kind", "wang", "--colors", "2", "--mode", "all", "--threads", "2", "--db", db,
                     "--quiet"},
                    int(200 + rng() % 2500), d))
      continue;
    ++killed;
    const DbState st = state_of(db);
    EXPECT_EQ(st.integrity, "ok");
    EXPECT_TRUE(st.solutions % 50000 == 0 || st.solutions == 203520) << st.solutions;  // batches of 50,000
  }
  EXPECT_GE(killed, 1);
}

TEST(DbFaults, TwoWritersOnOneFileBothFinishAndStoreEachSolutionOnce) {
  TempDir d;
  make_db(d / "a.sqlite", 0, 30000);
  make_db(d / "b.sqlite", 20000, 30000);  // 10,000 solutions in both
  const std::string out = d / "out.sqlite";
  pid_t a = spawn_tilekit({"db", "merge", out, d / "a.sqlite", "--quiet"}, d / "out-a", d / "err-a");
  pid_t b = spawn_tilekit({"db", "merge", out, d / "b.sqlite", "--quiet"}, d / "out-b", d / "err-b");
  EXPECT_EQ(wait_exit(a), 0) << slurp(d / "err-a");
  EXPECT_EQ(wait_exit(b), 0) << slurp(d / "err-b");
  const DbState st = state_of(out);
  EXPECT_EQ(st.integrity, "ok");
  EXPECT_EQ(st.solutions, 50000);
  EXPECT_EQ(st.runs, 2);
}

TEST(DbFaults, AFullDiskIsExit2AndTheDatabaseKeepsItsContent) {
  TempDir d;
  SmallDisk disk(d, "600k");
  if (!disk.mounted) GTEST_SKIP() << "full-disk test skipped: " << disk.why_not;
  make_db(d / "in.sqlite", 0, 40000);  // ~6 MB of solutions: more than the disk holds
  const std::string db = disk.dir + "/db.sqlite";
  make_db(db, 1'000'000, 10);
  CliResult r = run_cli("db merge " + db + " " + d / "in.sqlite" + " --quiet");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(db), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("disk is full"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  DbState st = state_of(db);
  EXPECT_EQ(st.integrity, "ok");
  EXPECT_EQ(st.solutions, 10);
  // A checkpoint that does not fit is refused the same way, and the old one stays.
  write_text(disk.dir + "/filler", std::string(600 * 1024, 'x'));
  r = run_cli("pack --kind wang --colors 2 --mode count --quiet --checkpoint " + disk.dir + "/ck --db " + d / "db2.sqlite");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_FALSE(fs::exists(disk.dir + "/ck"));
}

TEST(DbFaults, AReadOnlyDatabaseIsExit2ForWritersAndReadableForReaders) {
  TempDir d;
  SmallDisk disk(d, "4m");
  const std::string db = (disk.mounted ? disk.dir : d / "ro") + "/db.sqlite";
  fs::create_directories(fs::path(db).parent_path());
  make_db(db, 0, 100);
  if (disk.mounted) {
    ASSERT_TRUE(disk.remount_read_only()) << std::strerror(errno);
  } else if (geteuid() != 0) {
    chmod(db.c_str(), 0444);
    chmod(fs::path(db).parent_path().c_str(), 0555);
  } else {
    GTEST_SKIP() << "read-only test skipped: root ignores file modes and " << disk.why_not;
  }
  const std::string before = slurp(db);
  write_text(d / "t.json", R"({"kind":"corner","colors":2,"rows":1,"cols":1,"torus":false,"cells":[[5]]})");
  CliResult r = run_cli("db add " + d / "t.json" + " --db " + db);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(db), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  r = run_cli("db stats --json --db " + db);
  EXPECT_EQ(r.code, 0) << r.err;
  if (r.code == 0) {
    EXPECT_EQ(r.json()["solutions"], 100);
  }
  EXPECT_EQ(slurp(db), before);
  if (!disk.mounted) chmod(fs::path(db).parent_path().c_str(), 0755);
}
