// Signals end a pack run with a checkpoint and exit code 3; resuming continues the search.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <random>
#include <thread>
#include <vector>

#include "tests/cli_runner.hpp"

using namespace tilekit::test;

namespace {

bool wait_for_file(const std::string& path, double seconds) {
  auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (std::filesystem::exists(path)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

}  // namespace

TEST(PackSignals, SigtermAndSigusr1WriteACheckpointAndExit3AndResumeContinues) {
  TempDir d;
  std::string ck = d / "ck";
  // A search far too large to finish: the 36-tile complete 2x3-colour Wang set on a 6x6 torus.
  std::vector<std::string> args{
      "pack",         "--set", "complete-wang-2x3",  "--mode", "count", "--threads",    "2", "--quiet", "--json",
      "--checkpoint", ck,      "--checkpoint-every", "0.05",   "--db",  d / "db.sqlite"};
  std::mt19937 rng(42);
  std::uint64_t last_nodes = 0;
  for (int round = 0; round < 3; ++round) {
    std::vector<std::string> a = args;
    if (round > 0) a.insert(a.end(), {"--resume", ck});
    pid_t pid = spawn_tilekit(a, d / "out", d / "err");
    ASSERT_GT(pid, 0);
    const int sig = round == 1 ? SIGUSR1 : SIGTERM;
    // Under ASan, starting alone can take longer than the wait below; the kill ends it either way.
    EXPECT_TRUE(wait_until_catching(pid, sig, 60));
    if (round == 0) {
      ASSERT_TRUE(wait_for_file(ck, 20));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100 + rng() % 200));
    kill(pid, sig);
    EXPECT_EQ(wait_exit(pid), 3) << slurp(d / "err");
    EXPECT_NE(slurp(d / "err").find("checkpoint written to " + ck), std::string::npos) << slurp(d / "err");
    auto j = nlohmann::json::parse(slurp(d / "out"));
    EXPECT_EQ(j["interrupted"], true);
    EXPECT_EQ(j["complete"], false);
    std::uint64_t nodes = j["nodes"].get<std::uint64_t>();
    EXPECT_GT(nodes, last_nodes);  // each resumed run continues where the last one stopped
    last_nodes = nodes;
  }
}
