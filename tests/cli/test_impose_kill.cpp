// Kill safety under an imposed group: a `pack --impose` enumeration, SIGKILLed at
// random moments and continued each time by `pack --resume FILE` alone, ends with the same count
// and exactly the same stored solutions as an uninterrupted run; SIGTERM ends a run with exit 3
// after a checkpoint. The subspace: shard 3/128 of the C=3 Wang packings invariant under a group
// of order 9 (about 21,000 packings, a few seconds of storing).
#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>

#include <chrono>
#include <filesystem>
#include <random>
#include <set>
#include <thread>
#include <vector>

#include "tests/cli_runner.hpp"

using namespace tilekit::test;
namespace fs = std::filesystem;

namespace {

const char* kGroup = "t=0,3:pi=1,2,0;t=3,0:piv=1,2,0";

std::vector<std::string> full_args(const std::string& db, const std::string& ck = "",
                                   const std::string& every = "0.05") {
  std::vector<std::string> a{"pack", "--kind",   "wang", "--colors", "3",     "--mode",
                             "all",  "--impose", kGroup, "--shard",  "3/128", "--threads",
                             "2",    "--db",     db,     "--quiet",  "--json"};
  if (!ck.empty()) a.insert(a.end(), {"--checkpoint", ck, "--checkpoint-every", every});
  return a;
}

// `pack --resume FILE` alone: the checkpoint names the problem, mode, group, shard and database.
std::vector<std::string> resume_args(const std::string& ck) {
  return {"pack", "--resume", ck, "--quiet", "--json"};
}

std::set<std::string> stored_hashes(const std::string& db) {
  std::set<std::string> out;
  sqlite3* h = nullptr;
  if (sqlite3_open_v2(db.c_str(), &h, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) return out;
  sqlite3_stmt* q = nullptr;
  if (sqlite3_prepare_v2(h, "SELECT solution_hash, group_json IS NOT NULL, validated FROM solutions", -1, &q,
                         nullptr) == SQLITE_OK)
    while (sqlite3_step(q) == SQLITE_ROW) {
      if (sqlite3_column_int(q, 1) && sqlite3_column_int(q, 2))  // every row carries its group, validated
        out.insert(reinterpret_cast<const char*>(sqlite3_column_text(q, 0)));
    }
  sqlite3_finalize(q);
  sqlite3_close(h);
  return out;
}

struct Reference {
  long solutions = 0;
  std::set<std::string> hashes;
};

const Reference& reference() {
  static const Reference ref = [] {
    TempDir d;
    Reference r;
    pid_t pid = spawn_tilekit(full_args(d / "ref.sqlite"), d / "out", d / "err");
    EXPECT_EQ(wait_exit(pid), 0) << slurp(d / "err");
    auto j = nlohmann::json::parse(slurp(d / "out"));
    EXPECT_EQ(j["complete"], true);
    r.solutions = j["solutions"].get<long>();
    r.hashes = stored_hashes(d / "ref.sqlite");
    return r;
  }();
  return ref;
}

void expect_final_run_matches_reference(const std::string& ck, const std::string& db, const TempDir& d) {
  const Reference& ref = reference();
  ASSERT_GT(ref.solutions, 10000);
  ASSERT_EQ(ref.hashes.size(), std::size_t(ref.solutions));
  pid_t pid = spawn_tilekit(resume_args(ck), d / "out", d / "err");
  ASSERT_EQ(wait_exit(pid), 0) << slurp(d / "err");
  auto j = nlohmann::json::parse(slurp(d / "out"));
  EXPECT_EQ(j["complete"], true);
  EXPECT_EQ(j["solutions"], ref.solutions);  // the count survives every interruption
  EXPECT_EQ(j["group"]["order"], 9);
  EXPECT_EQ(j["shard"], "3/128");
  EXPECT_EQ(stored_hashes(db), ref.hashes);  // exactly the same stored solutions
}

}  // namespace

TEST(ImposeKill, TenRandomSigkillsResumedFromTheCheckpointAloneStoreTheSameSolutions) {
  TempDir d;
  std::string ck = d / "ck", db = d / "db.sqlite";
  std::mt19937 rng(20261123);
  int kills = 0, rounds = 0;
  while (kills < 10 && rounds < 200) {
    ++rounds;
    // The first run names everything; every later one is `--resume FILE` alone.
    pid_t pid = spawn_tilekit(fs::exists(ck) ? resume_args(ck) : full_args(db, ck), d / "out", d / "err");
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
  ASSERT_TRUE(fs::exists(ck));
  expect_final_run_matches_reference(ck, db, d);
}

TEST(ImposeKill, SigtermWritesTheCheckpointAndExits3AndResumeAloneFinishes) {
  TempDir d;
  std::string ck = d / "ck", db = d / "db.sqlite";
  pid_t pid = spawn_tilekit(full_args(db, ck, "0.02"), d / "out", d / "err");
  ASSERT_GT(pid, 0);
  // The first checkpoint is written as the search starts; then the handlers are surely installed.
  auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(ck) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  auto first = mtime(ck);
  while (mtime(ck) == first && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  kill(pid, SIGTERM);
  int code = wait_exit(pid);
  auto j = nlohmann::json::parse(slurp(d / "out"));
  if (!(code == 0 && j["complete"] == true)) {  // unless the run ended before the signal
    EXPECT_EQ(code, 3) << slurp(d / "err");
    EXPECT_EQ(j["interrupted"], true);
    EXPECT_EQ(j["checkpoint"], ck);
    EXPECT_NE(slurp(d / "err").find("--resume " + ck), std::string::npos);
  }
  expect_final_run_matches_reference(ck, db, d);
}
