// The status of a run from a fabricated run directory: each shard's attempts, state, result and
// checkpoint progress over the subproblems it owns (the engine's ShardSpec::owns), and files
// that are not what a job script writes (a FIFO, a link to /dev/urandom, a huge file) reported
// without ever being waited on.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <future>

#include "base/error.hpp"
#include "checkpoints/checkpoint.hpp"
#include "cluster/run_directory.hpp"
#include "cluster/status.hpp"
#include "base/run_control.hpp"
#include "solver/solve.hpp"
#include "tests/cli_runner.hpp"

namespace tilekit {
namespace {
namespace fs = std::filesystem;
using test::TempDir;
using test::write_text;

// Runs `f`; a call that has not returned after 20 s (a read blocked on a FIFO) fails the test
// and ends the process, since the blocked thread cannot be stopped.
template <class F>
auto within_seconds(F f) {
  auto done = std::async(std::launch::async, f);
  if (done.wait_for(std::chrono::seconds(20)) != std::future_status::ready) {
    ADD_FAILURE() << "blocked for 20 s";
    std::_Exit(1);
  }
  return done.get();
}

// A run directory of `shards` shards of `tilekit pack` with the given pack arguments.
void make_run(const TempDir& d, int shards) {
  fs::create_directories(d / "r/shards");
  write_text(d / "r/run.json",
             fmt::format(R"({{"shards": {}, "pack_args": ["--kind","wang","--colors","2"]}})", shards));
}

std::string shard(const TempDir& d, int i, const std::string& ext) {
  return d / fmt::format("r/shards/shard-{}{}", i, ext);
}

// A checkpoint of 10 subproblems: 0, 1 and 7 finished, 4 in flight.
SearchState sample_state() {
  SearchState s;
  s.fingerprint = R"({"mode":"count"})";
  s.subproblem_count = 10;
  s.subproblem_hash = 0x1234;
  s.finished = {true, true, false, false, false, false, false, true, false, false};
  s.finished_counts = {9, 3, 300};
  s.finished_each = {{2, 1, 100}, {3, 1, 100}, {4, 1, 100}};
  s.in_flight.push_back({4, {{0, 1}, {5, 7}}, {5, 0, 17}});
  s.seconds = 2.5;
  return s;
}

TEST(ClusterRunStatus, ShardStatesAttemptsResultsAndTheMergedCount) {
  TempDir d;
  make_run(d, 4);
  write_text(shard(d, 0, ".attempts"),
             "{\"attempt\":0,\"exit\":3,\"resumed\":false}\n{\"attempt\":1,\"exit\":0,\"resumed\":true}\n");
  write_text(shard(d, 0, ".done.json"), R"({"solutions": 7, "complete": true})");
  write_text(shard(d, 1, ".attempts"), "{\"attempt\":0,\"exit\":3}\n[1]\n{\"exit\":\"x\"}\n{\"attem");
  write_text(shard(d, 1, ".ckpt"), "x");
  write_text(shard(d, 2, ".sqlite"), "");
  write_text(d / "r/merged.json", R"({"solutions": 7, "distinct_solutions": 2})");
  const cluster::RunStatus r = cluster::read_run_status(d / "r");
  EXPECT_EQ(r.run_dir, d / "r");
  EXPECT_EQ(r.shards, 4);
  EXPECT_TRUE(r.pack);
  EXPECT_EQ(r.done, 1);
  EXPECT_EQ(r.checkpointed, 1);
  EXPECT_EQ(r.started, 1);
  EXPECT_EQ(r.pending, 1);
  EXPECT_EQ(r.solutions_in_done_shards, 7u);
  EXPECT_EQ(r.merged_solutions, 7u);
  EXPECT_EQ(r.merged_orbits, 2u);
  ASSERT_EQ(r.per_shard.size(), 4u);
  const auto& s = r.per_shard;
  EXPECT_EQ(s[0].state, "done");
  EXPECT_EQ(s[0].attempts, 2);
  EXPECT_EQ(s[0].checkpointed_exits, 1);
  EXPECT_EQ(s[0].last_exit, 0);
  EXPECT_EQ(s[0].complete, true);
  EXPECT_EQ(s[1].state, "checkpointed");
  EXPECT_EQ(s[1].attempts, 1);  // not attempts: a JSON array, a string exit, a line cut short by a kill
  EXPECT_EQ(s[1].last_exit, 3);
  ASSERT_TRUE(s[1].progress);
  EXPECT_FALSE(s[1].progress->error.empty());  // "x" is not a checkpoint
  ASSERT_TRUE(s[1].checkpoint_age_seconds);
  EXPECT_GE(*s[1].checkpoint_age_seconds, 0);
  EXPECT_EQ(s[2].state, "started");  // its database exists
  EXPECT_EQ(s[3].state, "pending");
  EXPECT_FALSE(s[3].last_exit);
  EXPECT_FALSE(s[3].progress);
  for (const auto& one : s) EXPECT_TRUE(one.attempts_error.empty());
}

TEST(ClusterRunStatus, JsonHasTheKeysTheCommandPrints) {
  TempDir d;
  make_run(d, 1);
  const nlohmann::json j = cluster::to_json(cluster::read_run_status(d / "r"));
  std::vector<std::string> keys;
  for (const auto& [k, v] : j.items()) keys.push_back(k);
  EXPECT_EQ(keys, (std::vector<std::string>{"checkpointed", "done", "eta_seconds", "merged_orbits",
                                            "merged_solutions", "mpi_ranks", "pack_args", "pending", "per_shard",
                                            "run_dir", "shards", "solutions_in_done_shards", "started", "submissions",
                                            "work_done_nodes", "work_outstanding_nodes"}));
  keys.clear();
  for (const auto& [k, v] : j["per_shard"][0].items()) keys.push_back(k);
  EXPECT_EQ(keys, (std::vector<std::string>{"attempts", "checkpoint_age_seconds", "checkpointed_exits", "complete",
                                            "last_exit", "progress", "shard", "solutions", "state"}));
  EXPECT_TRUE(j["merged_solutions"].is_null());
  EXPECT_TRUE(j["per_shard"][0]["last_exit"].is_null());
}

TEST(ClusterRunStatus, ProgressCountsOnlyTheSubproblemsTheShardOwns) {
  TempDir d;
  write_checkpoint(d / "ckpt", sample_state());
  // Shard 1 of 3 owns 1, 4 and 7: 1 and 7 are finished.
  const cluster::ShardProgress p = cluster::checkpoint_progress(d / "ckpt", ShardSpec{1, 3});
  EXPECT_TRUE(p.error.empty()) << p.error;
  EXPECT_EQ(p.subproblems, 3u);
  EXPECT_EQ(p.subproblems_done, 2u);
  EXPECT_DOUBLE_EQ(p.fraction, 2.0 / 3.0);
  EXPECT_EQ(p.solutions, 9u + 5u);  // the finished ones and what the one in flight found so far
  EXPECT_EQ(p.nodes, 317u);
  EXPECT_DOUBLE_EQ(p.seconds, 2.5);
  // Outstanding: subproblem 4, as large as the mean finished one of the shard (100 nodes), less
  // the 17 it counted; at 317 nodes / 2.5 s.
  EXPECT_EQ(p.open, 1u);
  ASSERT_TRUE(p.remaining_nodes);
  EXPECT_DOUBLE_EQ(*p.remaining_nodes, 83.0);
  EXPECT_DOUBLE_EQ(p.node_rate, 317.0 / 2.5);
  ASSERT_TRUE(p.eta_seconds);
  EXPECT_DOUBLE_EQ(*p.eta_seconds, 83.0 / (317.0 / 2.5));
  // Shard 2 of 3 finished none of its subproblems: no estimate yet.
  EXPECT_FALSE(cluster::checkpoint_progress(d / "ckpt", ShardSpec{2, 3}).remaining_nodes);
  // Shard 0 of 3 owns 0, 3, 6 and 9; shard 2 of 3 owns 2, 5 and 8.
  EXPECT_EQ(cluster::checkpoint_progress(d / "ckpt", ShardSpec{0, 3}).subproblems, 4u);
  EXPECT_EQ(cluster::checkpoint_progress(d / "ckpt", ShardSpec{0, 3}).subproblems_done, 1u);
  EXPECT_EQ(cluster::checkpoint_progress(d / "ckpt", ShardSpec{2, 3}).subproblems_done, 0u);
}

TEST(ClusterRunStatus, ShardOwnershipIsTheEnginesOwn) {
  // A complete shard's final checkpoint marks finished exactly the subproblems the engine ran
  // for it; the status counts the same ones, and every subproblem belongs to one shard.
  TempDir d;
  const TilingProblem problem = complete_packing_problem(TileKind::Wang, 2);
  std::uint64_t owned = 0, total = 0;
  const int shards = 4;
  for (int i = 0; i < shards; ++i) {
    SearchOptions o;
    o.mode = SearchMode::Count;
    o.run.threads = 1;
    o.run.shard = {i, shards};
    o.run.checkpoint_path = d / fmt::format("shard-{}.ckpt", i);
    const SearchResult r = solve_checkpointed(problem, o);
    ASSERT_TRUE(r.complete);
    const SearchState st = read_checkpoint(o.run.checkpoint_path);
    ASSERT_EQ(st.subproblem_count, r.subproblems);
    ASSERT_GT(r.subproblems, std::uint64_t(shards));
    for (std::uint64_t k = 0; k < st.subproblem_count; ++k)
      EXPECT_EQ(bool(st.finished[k]), (ShardSpec{i, shards}.owns(k))) << "subproblem " << k << ", shard " << i;
    const cluster::ShardProgress p = cluster::checkpoint_progress(o.run.checkpoint_path, {i, shards});
    EXPECT_EQ(p.subproblems, r.shard_subproblems);
    EXPECT_EQ(p.subproblems_done, r.shard_subproblems);
    EXPECT_EQ(p.solutions, r.solutions);
    owned += p.subproblems;
    total = r.subproblems;
  }
  EXPECT_EQ(owned, total);
}

TEST(ClusterRunStatus, EnumerateRunsHaveNoCheckpointProgress) {
  TempDir d;
  fs::create_directories(d / "r/shards");
  write_text(d / "r/run.json", R"({"shards": 1, "pack_args": [], "command": ["aperiodic", "enumerate"]})");
  write_checkpoint(shard(d, 0, ".ckpt"), sample_state());
  const cluster::RunStatus r = cluster::read_run_status(d / "r");
  EXPECT_FALSE(r.pack);
  ASSERT_TRUE(r.per_shard[0].progress);
  EXPECT_NE(r.per_shard[0].progress->error.find("enumerate"), std::string::npos);
}

TEST(ClusterRunStatus, AFifoOrADeviceAsAttemptsFileIsReportedNotRead) {
  TempDir d;
  make_run(d, 3);
  ASSERT_EQ(::mkfifo(shard(d, 0, ".attempts").c_str(), 0600), 0);
  fs::create_symlink("/dev/urandom", shard(d, 1, ".attempts"));
  fs::create_directories(shard(d, 2, ".attempts"));
  const cluster::RunStatus r = within_seconds([&] { return cluster::read_run_status(d / "r"); });
  for (int i = 0; i < 3; ++i) {
    const auto& s = r.per_shard[std::size_t(i)];
    EXPECT_NE(s.attempts_error.find("not a regular file"), std::string::npos) << i << ": " << s.attempts_error;
    EXPECT_EQ(s.attempts, 0);
    EXPECT_TRUE(cluster::to_json(s).contains("attempts_error"));
  }
}

TEST(ClusterRunStatus, AnAttemptsFileOverTheBoundIsReported) {
  TempDir d;
  make_run(d, 1);
  write_text(shard(d, 0, ".attempts"), "");
  fs::resize_file(shard(d, 0, ".attempts"), cluster::kMaxShardFileBytes + 1);
  const cluster::RunStatus r = cluster::read_run_status(d / "r");
  EXPECT_NE(r.per_shard[0].attempts_error.find("more than the limit"), std::string::npos)
      << r.per_shard[0].attempts_error;
}

TEST(ClusterRunStatus, FifosAndDevicesAsResultsOrCheckpointsAreNotWaitedOn) {
  TempDir d;
  make_run(d, 2);
  ASSERT_EQ(::mkfifo(shard(d, 0, ".done.json").c_str(), 0600), 0);
  ASSERT_EQ(::mkfifo(shard(d, 0, ".ckpt").c_str(), 0600), 0);
  fs::create_symlink("/dev/urandom", shard(d, 1, ".done.json"));
  fs::create_symlink("/dev/zero", shard(d, 1, ".ckpt"));
  ASSERT_EQ(::mkfifo((d / "r/merged.json").c_str(), 0600), 0);
  const cluster::RunStatus r = within_seconds([&] { return cluster::read_run_status(d / "r"); });
  for (const auto& s : r.per_shard) {
    EXPECT_EQ(s.state, "checkpointed");  // a result that cannot be read is not written yet
    ASSERT_TRUE(s.progress);
    EXPECT_NE(s.progress->error.find("not a regular file"), std::string::npos) << s.progress->error;
  }
  EXPECT_FALSE(r.merged_solutions);
}

TEST(ClusterRunStatus, RunFileMissingIsNotFoundAndAFifoIsBadInput) {
  TempDir d;
  EXPECT_THROW(cluster::read_run_status(d / "none"), NotFound);
  fs::create_directories(d / "r");
  ASSERT_EQ(::mkfifo((d / "r/run.json").c_str(), 0600), 0);
  EXPECT_THROW(within_seconds([&] { return cluster::read_run_status(d / "r"); }), InputError);
  fs::remove(d / "r/run.json");
  write_text(d / "r/run.json", R"({"shards": 0, "pack_args": []})");
  EXPECT_THROW(cluster::read_run_status(d / "r"), InputError);
}

TEST(ClusterRunStatus, RunEtaIsTheSlowestShardsAndUnknownUntilEveryShardHasAnEstimate) {
  TempDir d;
  make_run(d, 3);
  write_checkpoint(shard(d, 1, ".ckpt"), sample_state());  // shard 1: ETA 83 / 126.8 s
  write_text(shard(d, 0, ".done.json"), R"({"solutions": 5, "nodes": 40, "complete": true})");
  cluster::RunStatus r = cluster::read_run_status(d / "r");
  EXPECT_EQ(r.work_done_nodes, 40u + 317u);
  EXPECT_FALSE(r.eta_seconds);  // shard 2 has not started
  EXPECT_FALSE(r.work_outstanding_nodes);
  write_text(shard(d, 2, ".done.json"), R"({"solutions": 7, "nodes": 60, "complete": true})");
  r = cluster::read_run_status(d / "r");
  ASSERT_TRUE(r.eta_seconds);
  EXPECT_DOUBLE_EQ(*r.eta_seconds, 83.0 / (317.0 / 2.5));
  EXPECT_DOUBLE_EQ(*r.work_outstanding_nodes, 83.0);
  EXPECT_EQ(r.work_done_nodes, 40u + 317u + 60u);
  const nlohmann::json j = cluster::to_json(r);
  EXPECT_DOUBLE_EQ(j["eta_seconds"].get<double>(), *r.eta_seconds);
  EXPECT_EQ(j["per_shard"][1]["progress"]["open_subproblems"], 1);
}

}  // namespace
}  // namespace tilekit
