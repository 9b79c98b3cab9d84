// End-to-end tests of `tilekit aperiodic verify` by the transducer method: periodic sets with
// large periods, repeated tiles, the time limit, bad input, and checkpoints across a signal.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "tests/cli_runner.hpp"

using tilekit::test::run_cli;
using tilekit::test::TempDir;
using tilekit::test::write_text;

namespace {

const std::string kData = std::string(TILEKIT_SOURCE_DIR) + "/aperiodic/data/";

// Checks a witness (tile numbers of `tileset show`, n s w e) tile by tile, wrap-around included.
void expect_torus(const nlohmann::json& list, const nlohmann::json& w) {
  const std::size_t rows = w.size(), cols = w[0].size();
  for (std::size_t r = 0; r < rows; ++r)
    for (std::size_t c = 0; c < cols; ++c) {
      auto t = list[w[r][c].get<int>()], right = list[w[r][(c + 1) % cols].get<int>()],
           below = list[w[(r + 1) % rows][c].get<int>()];
      ASSERT_EQ(t[3], right[2]) << r << "," << c;  // e == w
      ASSERT_EQ(t[1], below[0]) << r << "," << c;  // s == n
    }
}

}  // namespace

TEST(AperiodicDecideCli, TheTenTileSetWithPeriod127IsPeriodicWithAValidatedWitness) {
  auto r = run_cli("aperiodic verify " + kData + "periodic-10-127.tiles --quiet --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = r.json();
  EXPECT_EQ(j["verdict"], "periodic");
  EXPECT_EQ(j["route"], "transducer");
  EXPECT_EQ(j["period"], nlohmann::json::array({127, 127}));
  EXPECT_TRUE(j["witness_validated"].get<bool>());
  ASSERT_EQ(j["witness"].size(), 127u);
  expect_torus(run_cli("tileset show " + kData + "periodic-10-127.tiles --json").json()["list"], j["witness"]);
}

TEST(AperiodicDecideCli, BothRoutesAgreeAndSayWhichAnswered) {
  auto r =
      run_cli("aperiodic verify " + kData + "periodic-8-28.tiles --route both --max-period 4 --time-limit 20 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = r.json();
  EXPECT_EQ(j["verdict"], "periodic");
  EXPECT_EQ(j["route"], "transducer");
  EXPECT_EQ(j["torus_verdict"], "no-period-up-to 4");  // its least period, 28, is beyond 4
}

TEST(AperiodicDecideCli, RepeatedTilesAreAcceptedReportedAndDropped) {
  TempDir d;
  write_text(d / "rep.tiles", "0 1 0 0\n0 1 0 0\n1 0 0 0\n1 0 0 0\n1 0 0 0\n");
  auto r = run_cli("aperiodic verify " + d / "rep.tiles" + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = r.json();
  EXPECT_EQ(j["tiles"], 2);
  ASSERT_EQ(j["repeated_tiles"].size(), 3u);
  EXPECT_EQ(j["repeated_tiles"][0]["repeats"], 0);
  EXPECT_NE(j["repeated_tiles"][0]["where"].get<std::string>().find(":2"), std::string::npos);
  EXPECT_EQ(j["verdict"], "periodic");
  // Rows of the two distinct tiles alternate: the witness found (possibly sheared, so 2 x 2) is
  // two rows high and checked by the validator.
  EXPECT_EQ(j["period"][0], 2);
  EXPECT_TRUE(j["witness_validated"].get<bool>());
  auto human = run_cli("aperiodic verify " + d / "rep.tiles");
  EXPECT_NE(human.out.find("3 repeated tiles dropped"), std::string::npos) << human.out;
}

TEST(AperiodicDecideCli, TheTimeLimitHoldsAndUnknownSaysHowFarItGot) {
  auto t0 = std::chrono::steady_clock::now();
  auto r = run_cli("aperiodic verify jeandel-rao-11 --time-limit 1 --quiet --json");
  double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = r.json();
  EXPECT_EQ(j["verdict"], "unknown");
  EXPECT_EQ(j["transducer"]["stopped_by"], "time-limit");
  EXPECT_GT(j["k"].get<int>(), 5);
  EXPECT_LT(j["seconds"].get<double>(), 2.0);  // within max(1 s, 10%) of the limit
  EXPECT_LT(wall, 10.0);                       // the process, start-up included (a loaded machine)
  // Every other route, and convert --verify, within the same bound (the torus route's row
  // filter once ran 90 s past a 1 s limit at --max-period 64).
  for (const char* route : {"torus", "both", "auto"}) {
    auto o = run_cli(
        std::string("aperiodic verify jeandel-rao-11 --max-period 64 --time-limit 1 --quiet --json --route ") + route);
    ASSERT_EQ(o.code, 0) << route << o.err;
    EXPECT_LT(o.json()["seconds"].get<double>(), 2.0) << route;
    EXPECT_NE(o.json()["verdict"], "periodic") << route;
  }
  auto c0 = std::chrono::steady_clock::now();
  auto c = run_cli("aperiodic convert kari-14 --method vertical --verify 64 --time-limit 1 --json");
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count(), 10.0);
}

TEST(AperiodicDecideCli, BadInputIsExit2AndAHugeSetAResult) {
  TempDir d;
  write_text(d / "empty.tiles", "# nothing\n");
  write_text(d / "range.tiles", "# colours: 2\n0 1 0 5\n");
  write_text(d / "neg.tiles", "0 -1 0 0\n");
  for (const char* f : {"empty.tiles", "range.tiles", "neg.tiles"}) {
    auto r = run_cli("aperiodic verify " + d / f + " --quiet");
    EXPECT_EQ(r.code, 2) << f << r.err;
    EXPECT_FALSE(r.err.empty());
  }
  // 200000 distinct tiles over 60 colours: a result within the time limit, not a crash.
  std::string big;
  for (int i = 0; i < 200000; ++i)
    big += fmt::format("{} {} {} {}\n", i % 60, (i / 60) % 60, (i / 3600) % 60, (i * 7) % 60);
  write_text(d / "big.tiles", big);
  auto r = run_cli("aperiodic verify " + d / "big.tiles" + " --time-limit 2 --quiet --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_LT(r.json()["seconds"].get<double>(), 4.0);
}

TEST(AperiodicDecideCli, SigtermCheckpointsExits3AndTheRunResumes) {
  TempDir d;
  const std::string ck = d / "v.ckpt";
  pid_t pid = tilekit::test::spawn_tilekit(
      {"aperiodic", "verify", "kari-14", "--time-limit", "60", "--checkpoint", ck, "--quiet", "--json"}, d / "out",
      d / "err");
  ASSERT_GT(pid, 0);
  EXPECT_TRUE(tilekit::test::wait_until_catching(pid, SIGTERM, 60));  // the kill below ends it either way
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  kill(pid, SIGTERM);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 3) << tilekit::test::slurp(d / "err");
  ASSERT_TRUE(std::filesystem::exists(ck));
  auto first = nlohmann::json::parse(tilekit::test::slurp(d / "out"));
  EXPECT_TRUE(first["interrupted"].get<bool>());
  const int k = first["k"].get<int>();
  auto r = run_cli("aperiodic verify kari-14 --time-limit 1 --resume " + ck + " --quiet --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.json()["transducer"]["resumed"].get<bool>());
  EXPECT_GE(r.json()["k"].get<int>(), k);
  // A checkpoint of another set is refused.
  auto other = run_cli("aperiodic verify culik-13 --resume " + ck + " --quiet");
  EXPECT_EQ(other.code, 2);
  EXPECT_NE(other.err.find("checkpoint"), std::string::npos) << other.err;
}
