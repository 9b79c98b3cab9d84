// `tilekit aperiodic enumerate` end to end: random SIGKILLs with resumes store what an
// uninterrupted run stores, SIGTERM checkpoints and exits 3, shard databases merge to the whole
// run's, bad input is exit 2, and the chain's check commands re-derive each link.
#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include "results/results_db.hpp"
#include "tests/cli_runner.hpp"

using namespace tilekit::test;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> run_args(const std::string& ck, const std::string& db, const std::string& shard = "0/1") {
  // Two sources, depth 2: a run of seconds (the colour merges make deeper runs minutes long).
  std::vector<std::string> a{"aperiodic",
                             "enumerate",
                             "--source",
                             "jeandel-rao-11-variant-2",
                             "--source",
                             "labbe-19",
                             "--max-depth",
                             "2",
                             "--max-tiles",
                             "40",
                             "--batch",
                             "2",
                             "--threads",
                             "2",
                             "--shard",
                             shard,
                             "--checkpoint-every",
                             "0",
                             "--checkpoint",
                             ck,
                             "--db",
                             db,
                             "--quiet",
                             "--json"};
  if (fs::exists(ck)) a.insert(a.end(), {"--resume", ck});
  return a;
}

// The stored rows that identify a run's results: tile sets by content, conversions by their ends.
std::vector<std::string> stored_rows(const std::string& db) {
  tilekit::ResultsDb rdb(db, false);
  std::vector<std::string> rows;
  for (const char* sql : {"SELECT 'set ' || content_hash || ' ' || tiles FROM tilesets",
                          "SELECT 'conv ' || s.content_hash || ' ' || c.method || ' ' || r.content_hash || ' ' || "
                          "c.soundness FROM conversions c JOIN tilesets s ON s.id = c.source_set "
                          "JOIN tilesets r ON r.id = c.result_set"}) {
    sqlite3_stmt* q = nullptr;
    EXPECT_EQ(sqlite3_prepare_v2(rdb.handle(), sql, -1, &q, nullptr), SQLITE_OK);
    while (sqlite3_step(q) == SQLITE_ROW) rows.emplace_back(reinterpret_cast<const char*>(sqlite3_column_text(q, 0)));
    sqlite3_finalize(q);
  }
  std::sort(rows.begin(), rows.end());
  return rows;
}

struct Baseline {
  std::string digest;
  std::vector<std::string> rows;
  double seconds = 0;
};

const Baseline& baseline() {
  static const Baseline b = [] {
    TempDir d;
    Baseline out;
    auto t0 = std::chrono::steady_clock::now();
    pid_t pid = spawn_tilekit(run_args(d / "ck", d / "db.sqlite"), d / "out", d / "err");
    EXPECT_EQ(wait_exit(pid), 0) << slurp(d / "err");
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    auto j = nlohmann::json::parse(slurp(d / "out"));
    EXPECT_EQ(j["complete"], true);
    out.digest = j["digest"];
    out.rows = stored_rows(d / "db.sqlite");
    return out;
  }();
  return b;
}

}  // namespace

TEST(EnumerateKill, TenRandomSigkillsWithResumesStoreTheSameSetsAndConversions) {
  const Baseline& base = baseline();
  ASSERT_FALSE(base.rows.empty());
  TempDir d;
  std::string ck = d / "ck", db = d / "db.sqlite";
  std::mt19937 rng(20261125);
  const int span_ms = std::max(60, int(base.seconds * 1000 * 0.5));
  int kills = 0, rounds = 0;
  while (kills < 10 && rounds < 300) {
    ++rounds;
    pid_t pid = spawn_tilekit(run_args(ck, db), d / "out", d / "err");
    ASSERT_GT(pid, 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(20 + int(rng() % unsigned(span_ms))));
    kill(pid, SIGKILL);
    const int code = wait_exit(pid);
    if (code == 128 + SIGKILL) {
      ++kills;
      continue;
    }
    ASSERT_EQ(code, 0) << slurp(d / "err");  // finished first: start over for more kills
    fs::remove(ck);
    fs::remove(db);
  }
  EXPECT_EQ(kills, 10);
  RecordProperty("rounds", rounds);
  pid_t pid = spawn_tilekit(run_args(ck, db), d / "out", d / "err");
  ASSERT_EQ(wait_exit(pid), 0) << slurp(d / "err");
  auto j = nlohmann::json::parse(slurp(d / "out"));
  EXPECT_EQ(j["complete"], true);
  EXPECT_EQ(j["digest"], base.digest);
  EXPECT_EQ(stored_rows(db), base.rows);
}

TEST(EnumerateKill, SigtermCheckpointsAndExits3ThenTheResumeEndsTheSame) {
  const Baseline& base = baseline();
  TempDir d;
  std::string ck = d / "ck", db = d / "db.sqlite";
  int terms = 0;
  bool complete = false;
  // A SIGTERM in the middle of a batch drops the batch, so the waits are fractions of the
  // uninterrupted run (four batches), each a tenth of it longer than the last: a fixed wait could
  // end every run before its first batch on a loaded machine or under the sanitizers (ten times
  // slower), and waits longer than the run would end none of them.
  for (int round = 0; round < 30 && !complete; ++round) {
    pid_t pid = spawn_tilekit(run_args(ck, db), d / "out", d / "err");
    std::this_thread::sleep_for(std::chrono::duration<double>(base.seconds * (0.3 + 0.1 * round)));
    kill(pid, SIGTERM);
    const int code = wait_exit(pid);
    auto j = nlohmann::json::parse(slurp(d / "out"));
    if (code == 0 && j["complete"] == true) {
      EXPECT_EQ(j["digest"], base.digest);
      complete = true;
      break;
    }
    ASSERT_EQ(code, 3) << slurp(d / "err");
    EXPECT_EQ(j["interrupted"], true);
    EXPECT_TRUE(fs::exists(ck));
    ++terms;
  }
  EXPECT_TRUE(complete);
  EXPECT_GE(terms, 1);
  EXPECT_EQ(stored_rows(db), base.rows);
}

TEST(EnumerateShards, ShardDatabasesMergeToTheWholeRun) {
  const Baseline& base = baseline();
  TempDir d;
  std::vector<std::string> inputs;
  for (int i = 0; i < 3; ++i) {
    const std::string db = d / ("shard" + std::to_string(i) + ".sqlite");
    pid_t pid =
        spawn_tilekit(run_args(d / ("ck" + std::to_string(i)), db, std::to_string(i) + "/3"), d / "out", d / "err");
    ASSERT_EQ(wait_exit(pid), 0) << slurp(d / "err");
    inputs.push_back(db);
  }
  std::string merge = "db merge " + std::string(d / "merged.sqlite");
  for (const auto& in : inputs) merge += " " + in;
  ASSERT_EQ(run_cli(merge).code, 0);
  EXPECT_EQ(stored_rows(d / "merged.sqlite"), base.rows);
}

TEST(EnumerateCli, BadInputIsExit2) {
  TempDir d;
  for (const std::string& args :
       {std::string("aperiodic enumerate --source penrose-2"), std::string("aperiodic enumerate --max-depth -1"),
        std::string("aperiodic enumerate --max-tiles -3"), std::string("aperiodic enumerate --max-tiles 0"),
        std::string("aperiodic enumerate --time-limit -5"), std::string("aperiodic enumerate --batch -1"),
        std::string("aperiodic enumerate --lead-max-k 0"), std::string("aperiodic enumerate --shard 3/3"),
        std::string("aperiodic link kari-14 --steps squash"), std::string("aperiodic link penrose-2 --steps prune")}) {
    CliResult r = run_cli(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
  }
  write_text(d / "garbage.ckpt", "not a checkpoint\n");
  EXPECT_EQ(run_cli("aperiodic enumerate --resume " + std::string(d / "garbage.ckpt")).code, 2);
  // A checkpoint of another command (a transducer decision) is refused.
  ASSERT_EQ(run_cli("aperiodic verify kari-14 --route transducer --time-limit 0.2 --checkpoint " +
                    std::string(d / "decide.ckpt") + " --json")
                .code,
            0);
  EXPECT_EQ(run_cli("aperiodic enumerate --resume " + std::string(d / "decide.ckpt")).code, 2);
}

TEST(EnumerateCli, TheSmallestSetsChainLinksReplayWithTheirCheckCommands) {
  CliResult r =
      run_cli("aperiodic enumerate --source jeandel-rao-11-variant-2 --max-depth 2 --max-tiles 40 --quiet --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.contains("smallest"));
  const auto& chain = j["smallest"]["chain"];
  ASSERT_GE(chain.size(), 2u);
  for (std::size_t i = 1; i < chain.size(); ++i) {
    std::string cmd = chain[i]["check"];
    ASSERT_EQ(cmd.rfind("tilekit ", 0), 0u);
    CliResult c = run_cli(cmd.substr(8));
    ASSERT_EQ(c.code, 0) << cmd << "\n" << c.err;
    auto l = nlohmann::json::parse(c.out);
    EXPECT_EQ(l["set"], chain[i]["set"]);
    EXPECT_EQ(l["tiles"], chain[i]["tiles"]);
    EXPECT_EQ(l["label"], chain[i]["label"]);
    EXPECT_EQ(l["sound"], true);
  }
  EXPECT_EQ(j["smallest"]["tiles"], chain.back()["tiles"]);
}

TEST(EnumerateCli, ARunsRecordIsWhatSmallestReDerives) {
  TempDir d;
  const std::string rec = d / "record.json";
  const std::string db = d / "e.sqlite";
  CliResult r = run_cli("aperiodic enumerate --source jeandel-rao-11-variant-2 --max-depth 1 --max-tiles 100 --record " +
                        rec + " --db " + db + " --quiet --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["record"], rec);
  // The record names the command that reruns the search: the flags that change its results.
  std::ifstream in(rec);
  EXPECT_EQ(nlohmann::json::parse(in)["command"],
            "tilekit aperiodic enumerate --source jeandel-rao-11-variant-2 --max-depth 1 --max-tiles 100");
  CliResult s = run_cli("aperiodic smallest --record " + rec + " --max-period 4 --time-limit 1 --json");
  ASSERT_EQ(s.code, 0) << s.err;
  auto js = nlohmann::json::parse(s.out);
  EXPECT_EQ(js["set"], j["smallest"]["set"]);
  EXPECT_EQ(js["tiles"], j["smallest"]["tiles"]);
  EXPECT_EQ(js["found_by"]["digest"], j["digest"]);
  // The same run's database gives the same chain (re-derived the same way; a database records no command).
  CliResult sd = run_cli("aperiodic smallest --db " + db + " --max-period 4 --time-limit 1 --json");
  ASSERT_EQ(sd.code, 0) << sd.err;
  auto jd = nlohmann::json::parse(sd.out);
  EXPECT_EQ(jd["set"], js["set"]);
  EXPECT_EQ(jd["chain"], js["chain"]);
  EXPECT_FALSE(jd.contains("found_by"));
  // Bad records: not JSON, another format, a set the chain does not give, --db with --record.
  write_text(d / "bad.json", "{\"format\": \"tilekit-smallest-chain\"}\n");
  EXPECT_EQ(run_cli("aperiodic smallest --record " + std::string(d / "bad.json")).code, 2);
  write_text(d / "garbage.json", "not json\n");
  EXPECT_EQ(run_cli("aperiodic smallest --record " + std::string(d / "garbage.json")).code, 2);
  EXPECT_EQ(run_cli("aperiodic smallest --record " + std::string(d / "missing.json")).code, 2);
  EXPECT_EQ(run_cli("aperiodic smallest --record " + rec + " --db " + std::string(d / "x.sqlite")).code, 2);
  // Records and databases that lie are exit 2 naming the link, never an internal error: a chain
  // that ends in a Wang set, one that names another set's hash, and a database with one extra
  // well-typed conversion row claiming a sound link to a smaller (periodic) corner set.
  auto record = nlohmann::json::parse(slurp(rec));
  auto refused = [&](const nlohmann::json& bad, const std::string& words) {
    write_text(d / "lie.json", bad.dump());
    CliResult x = run_cli("aperiodic smallest --record " + std::string(d / "lie.json") + " --max-period 4");
    EXPECT_EQ(x.code, 2) << bad.dump() << "\n" << x.err;
    EXPECT_NE(x.err.find(words), std::string::npos) << x.err;
  };
  auto wang = record;
  wang["steps"] = nlohmann::json::array();
  refused(wang, "link 0");
  auto other = record;
  other["set"] = "0123456789abcdef";
  refused(other, "link 1");
  sqlite3* h = nullptr;
  ASSERT_EQ(sqlite3_open(db.c_str(), &h), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(h,
                         "INSERT INTO conversions (source_set, method, result_set, tiles_before, tiles_after, colors, "
                         "soundness, details, created_at) SELECT s.id, 'horizontal', r.id, s.tiles, r.tiles, r.colors, "
                         "'conjugate', '{}', 'now' FROM tilesets s, tilesets r WHERE s.source LIKE 'published:%' AND "
                         "r.kind = 'corner' AND NOT EXISTS (SELECT 1 FROM conversions c WHERE c.source_set = s.id AND "
                         "c.method = 'horizontal' AND c.result_set = r.id) ORDER BY r.tiles LIMIT 1",
                         nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(h);
  CliResult lie = run_cli("aperiodic smallest --db " + db + " --max-period 4");
  EXPECT_EQ(lie.code, 2) << lie.err;
  EXPECT_NE(lie.err.find("link 1 (step horizontal"), std::string::npos) << lie.err;
}
