// A signal ends an imposed-group search (`pack --impose`) and the portfolio with exit code 3.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>
#include <vector>

#include "tests/cli_runner.hpp"

using namespace tilekit::test;

namespace {

int run_and_signal(const std::vector<std::string>& args, const std::string& out, const std::string& err) {
  pid_t pid = spawn_tilekit(args, out, err);
  if (pid < 0) return -1;
  // A sanitizer build can take longer than the wait below just to start (a SIGTERM before the
  // handler ends the process with 143, which the callers report).
  wait_until_catching(pid, SIGTERM, 60);
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  kill(pid, SIGTERM);
  return wait_exit(pid);
}

TEST(ImposeSignals, SigtermEndsImposedSearchAndPortfolioWithExit3) {
  TempDir d;
  // C=7 corner: far beyond 0.7 s for the imposed search and for the search portfolio (`auto`
  // would answer at once from the odd-C construction).
  for (std::vector<std::string> extra : {std::vector<std::string>{"--impose", "t=0,7:pi=1,2,3,4,5,6,0"},
                                         std::vector<std::string>{"--method", "search"}}) {
    std::vector<std::string> args{"pack", "--kind", "corner", "--colors", "7", "--threads", "1", "--time-limit", "60",
                                  "--quiet", "--json", "--db", d / "r.sqlite", "--portfolio-stats", d / "s.json"};
    args.insert(args.end(), extra.begin(), extra.end());
    auto t0 = std::chrono::steady_clock::now();
    int code = run_and_signal(args, d / "out", d / "err");
    double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(code, 3) << extra[0] << ": " << slurp(d / "err");
    EXPECT_LT(secs, 30.0);
    auto j = nlohmann::json::parse(slurp(d / "out"));
    EXPECT_EQ(j["interrupted"], true);
  }
}

}  // namespace
