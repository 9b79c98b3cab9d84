// The kill test: the stored enumeration of the 203,520 two-colour Wang packings,
// killed at random moments and resumed each time, ends with exactly 203,520 distinct
// solutions in the database; SIGTERM ends each run with exit code 3 and a checkpoint.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <random>
#include <thread>
#include <vector>

#include "results/results_db.hpp"
#include "tests/cli_runner.hpp"

using namespace tilekit::test;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> enumeration_args(const std::string& ck, const std::string& db,
                                          const std::string& every = "0.1") {
  std::vector<std::string> a{"pack",  "--kind",       "wang",   "--colors",  "2", "--mode",
                             "all",   "--method",     "search", "--threads", "2", "--checkpoint-every",
                             every,   "--checkpoint", ck,       "--db",      db,  "--quiet",
                             "--json"};
  if (fs::exists(ck)) a.insert(a.end(), {"--resume", ck});
  return a;
}

void expect_final_run_and_database(const std::vector<std::string>& args, const std::string& db, const TempDir& d) {
  pid_t pid = spawn_tilekit(args, d / "out", d / "err");
  ASSERT_EQ(wait_exit(pid), 0) << slurp(d / "err");
  auto j = nlohmann::json::parse(slurp(d / "out"));
  EXPECT_EQ(j["complete"], true);
  EXPECT_EQ(j["solutions"], 203520);  // the exact count survives every interruption
  tilekit::ResultsDb rdb(db, false);
  tilekit::DbStats st = rdb.stats();
  EXPECT_EQ(st.solutions, 203520u);
  EXPECT_EQ(st.distinct_solutions, 538u);  // the db counts orbits (canonical hashes) as distinct
  sqlite3_stmt* q = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(rdb.handle(), "SELECT COUNT(DISTINCT solution_hash), COUNT(*) FROM solutions", -1, &q,
                               nullptr),
            SQLITE_OK);
  ASSERT_EQ(sqlite3_step(q), SQLITE_ROW);
  EXPECT_EQ(sqlite3_column_int64(q, 0), 203520);
  EXPECT_EQ(sqlite3_column_int64(q, 1), 203520);
  sqlite3_finalize(q);
}

}  // namespace

TEST(PackKill, TenRandomSigkillsWithResumeStoreExactly203520DistinctPackings) {
  TempDir d;
  std::string ck = d / "ck", db = d / "db.sqlite";
  std::mt19937 rng(20261122);
  int kills = 0, rounds = 0;
  while (kills < 10 && rounds < 200) {
    ++rounds;
    pid_t pid = spawn_tilekit(enumeration_args(ck, db), d / "out", d / "err");
    ASSERT_GT(pid, 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(30 + rng() % 400));
    kill(pid, SIGKILL);
    int code = wait_exit(pid);
    if (code == 128 + SIGKILL) {
      ++kills;
    } else {
      ASSERT_EQ(code, 0) << slurp(d / "err");  // finished before the kill: start over for more kills
      fs::remove(ck);
      fs::remove(db);
    }
  }
  EXPECT_EQ(kills, 10);
  RecordProperty("rounds", rounds);
  expect_final_run_and_database(enumeration_args(ck, db), db, d);
}

TEST(PackKill, EverySigtermEndsWithExit3AndTheResumedRunsStoreExactly203520) {
  TempDir d;
  // Frequent checkpoints and a signal soon after one: each round does a little work, so several
  // rounds are interrupted before the last run completes.
  const std::string kEvery = "0.02";
  std::string ck = d / "ck", db = d / "db.sqlite";
  std::mt19937 rng(7);
  int terms = 0;
  for (int round = 0; round < 200; ++round) {
    auto before = mtime(ck);
    pid_t pid = spawn_tilekit(enumeration_args(ck, db, kEvery), d / "out", d / "err");
    ASSERT_GT(pid, 0);
    // Once this run has written a checkpoint its handlers are surely installed.
    auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (mtime(ck) == before && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    std::this_thread::sleep_for(std::chrono::milliseconds(rng() % 40));
    kill(pid, SIGTERM);
    int code = wait_exit(pid);
    auto j = nlohmann::json::parse(slurp(d / "out"));
    if (j["complete"] == true && code == 0) break;  // the run ended before the signal
    ASSERT_EQ(code, 3) << slurp(d / "err");
    EXPECT_EQ(j["interrupted"], true);
    ++terms;
  }
  EXPECT_GE(terms, 3);
  RecordProperty("sigterm_rounds", terms);
  expect_final_run_and_database(enumeration_args(ck, db, kEvery), db, d);
}
