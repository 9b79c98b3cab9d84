// Every long job on the run control (base/run_control.hpp, base/signals.hpp): SIGTERM or SIGINT
// once the job catches signals ends it with exit 3 and one line saying what was kept, no
// temporary file is left in its output folder (hidden `.NAME.tmpXXXXXX` files and folders
// included), and where the job has a checkpoint, resuming from it ends as an uninterrupted run.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "image/image.hpp"
#include "tests/cli_runner.hpp"

using namespace tilekit::test;
namespace fs = std::filesystem;

namespace {

struct SignalledRun {
  int code = -1;
  std::string out, err;
  double seconds = 0;  // from the signal to the exit
};

// Starts `tilekit args`, waits until it catches `sig` and then `after_ms` more (into the work),
// sends `sig` once and waits for the exit.
SignalledRun signal_job(const TempDir& d, const std::vector<std::string>& args, int sig, int after_ms) {
  const pid_t pid = spawn_tilekit(args, d / "stdout", d / "stderr");
  EXPECT_GT(pid, 0);
  SignalledRun s;
  if (pid <= 0) return s;
  EXPECT_TRUE(wait_until_catching(pid, sig, 60));
  std::this_thread::sleep_for(std::chrono::milliseconds(after_ms));
  const auto t0 = std::chrono::steady_clock::now();
  kill(pid, sig);
  s.code = wait_exit(pid);
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  s.out = slurp(d / "stdout");
  s.err = slurp(d / "stderr");
  return s;
}

const char* signal_word(int sig) {
  return sig == SIGTERM ? "SIGTERM" : "SIGINT";
}

// Exit 3 and exactly one line on stderr: "tilekit: interrupted by SIG...: <kept>".
void expect_interrupted(const SignalledRun& s, int sig, const std::string& kept) {
  EXPECT_EQ(s.code, 3) << s.err;
  EXPECT_EQ(std::count(s.err.begin(), s.err.end(), '\n'), 1) << s.err;
  EXPECT_EQ(s.err.rfind(std::string("tilekit: interrupted by ") + signal_word(sig) + ": " + kept, 0), 0u) << s.err;
}

// Every hidden (dot) file or folder under `dir`: the temp files of base/atomic_file.hpp.
std::vector<std::string> hidden_leftovers(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().filename().string().starts_with(".")) out.push_back(e.path().string());
  return out;
}

}  // namespace

class RunSignals : public ::testing::TestWithParam<int> {};
INSTANTIATE_TEST_SUITE_P(TermAndInt, RunSignals, ::testing::Values(SIGTERM, SIGINT),
                         [](const auto& info) { return std::string(signal_word(info.param)); });

// A point window of about 2e8 points streamed to a .f32 file (1.6 GB): the signal comes while the
// hidden temp file grows; nothing of it stays.
TEST_P(RunSignals, PointsGenerateRemovesItsPartialFile) {
  TempDir d;
  const SignalledRun s =
      signal_job(d,
                 {"points", "generate", "--method", "corner", "--colors", "2", "--points", "64", "--window",
                  "0,0,2000,2000", "--density", "50", "--threads", "2", "--out", d / "big.f32", "--quiet"},
                 GetParam(), 300);
  expect_interrupted(s, GetParam(), "nothing kept");
  EXPECT_LT(s.seconds, 5);
  EXPECT_FALSE(fs::exists(d / "big.f32"));
  EXPECT_EQ(hidden_leftovers(d.path), std::vector<std::string>{});
}

// The corner Poisson tile set with 1024 points a tile: seconds of sampling.
TEST_P(RunSignals, PointsTilesStopsAndWritesNothing) {
  TempDir d;
  const SignalledRun s = signal_job(d,
                                    {"points", "tiles", "--colors", "4", "--points", "1024", "--threads", "2",
                                     "--no-db", "--out", d / "t.ptiles", "--picture", d / "t.png", "--quiet"},
                                    GetParam(), 200);
  expect_interrupted(s, GetParam(), "nothing kept");
  EXPECT_LT(s.seconds, 5);
  EXPECT_FALSE(fs::exists(d / "t.ptiles"));
  EXPECT_FALSE(fs::exists(d / "t.png"));
  EXPECT_EQ(hidden_leftovers(d.path), std::vector<std::string>{});
}

// A 6-colour texture tile set (1296 tiles of 64 px, seconds) over an old 2-colour set in the same folder: the old
// set stays whole, no temp folder stays.
TEST_P(RunSignals, TextureTilesLeavesTheOldSetWhole) {
  TempDir d;
  tilekit::Image ex{96, 96, std::vector<std::uint8_t>(96 * 96 * 4)};
  for (std::size_t i = 0; i < ex.pixels.size(); ++i) ex.pixels[i] = std::uint8_t((i * 2654435761u) >> 13);
  tilekit::write_png(d / "ex.png", ex);
  const std::vector<std::string> base{"texture",   "tiles", "--exemplar", d / "ex.png", "--tile-px", "64",
                                      "--threads", "2",     "--out",      d / "set",    "--quiet"};
  std::vector<std::string> large = base;
  large.insert(large.end(), {"--colors", "6", "--search", "64"});
  ASSERT_EQ(run_cli("texture tiles --exemplar " + (d / "ex.png") +
                    " --tile-px 32 --colors 2 --search 2 --quiet --out " + (d / "set"))
                .code,
            0);
  const std::string manifest = slurp(d / "set/tiles.json");
  const SignalledRun s = signal_job(d, large, GetParam(), 300);
  expect_interrupted(s, GetParam(), "nothing kept");
  EXPECT_LT(s.seconds, 10);
  EXPECT_EQ(slurp(d / "set/tiles.json"), manifest);
  EXPECT_TRUE(fs::exists(d / "set/tile-0015.png"));
  EXPECT_FALSE(fs::exists(d / "set/tile-0016.png"));  // no tile of the 1296-tile set
  EXPECT_EQ(hidden_leftovers(d.path), std::vector<std::string>{});
}

// A terrain set of 4 terrains (256 tiles of 64 px from four synthesised corner sets, seconds):
// neither the tile set folder nor the Tiled folder is written, no temp folder stays.
TEST_P(RunSignals, TextureTerrainStopsAndWritesNothing) {
  TempDir d;
  std::vector<std::string> args{"texture", "terrain", "--tile-px", "64",        "--threads", "2",
                                "--out",   d / "set", "--tiled",   d / "tiled", "--quiet"};
  for (std::uint32_t k = 0; k < 4; ++k) {
    tilekit::Image ex{96, 96, std::vector<std::uint8_t>(96 * 96 * 4)};
    for (std::size_t i = 0; i < ex.pixels.size(); ++i) ex.pixels[i] = std::uint8_t(((i + 977 * k) * 2654435761u) >> 13);
    const std::string file = d / ("t" + std::to_string(k) + ".png");
    tilekit::write_png(file, ex);
    args.insert(args.end(), {"--terrain", "t" + std::to_string(k) + "=" + file});
  }
  const SignalledRun s = signal_job(d, args, GetParam(), 300);
  expect_interrupted(s, GetParam(), "nothing kept");
  EXPECT_LT(s.seconds, 10);
  EXPECT_FALSE(fs::exists(d / "set"));
  EXPECT_FALSE(fs::exists(d / "tiled"));
  EXPECT_EQ(hidden_leftovers(d.path), std::vector<std::string>{});
}

// `pack --estimate` with 2^31 probes per candidate ran without bound: a signal ends it, and so
// does --time-limit.
TEST_P(RunSignals, PackEstimateStopsOnASignalAndAtItsTimeLimit) {
  TempDir d;
  const std::vector<std::string> args{"pack",       "--kind",    "corner", "--colors", "5",    "--estimate",
                                      "2147483648", "--threads", "2",      "--quiet",  "--db", d / "db.sqlite"};
  const SignalledRun s = signal_job(d, args, GetParam(), 300);
  expect_interrupted(s, GetParam(), "nothing kept");
  EXPECT_LT(s.seconds, 5);
  if (GetParam() == SIGTERM) {
    const auto t0 = std::chrono::steady_clock::now();
    CliResult r = run_cli(
        "pack --kind corner --colors 5 --estimate 2147483648 --estimate-seconds 0.5 --threads 2 "
        "--time-limit 1 --quiet --json --db " +
        (d / "db.sqlite"));
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 10);
  }
  EXPECT_EQ(hidden_leftovers(d.path), std::vector<std::string>{});
}

// All 203,520 two-colour Wang packings stored (seconds): the signal writes the checkpoint, and the
// resumed run counts exactly what an uninterrupted run counts.
TEST_P(RunSignals, PackCheckpointsAndTheResumeCountsTheSame) {
  TempDir d;
  const std::string ck = d / "ck";
  std::vector<std::string> args{"pack",
                                "--kind",
                                "wang",
                                "--colors",
                                "2",
                                "--mode",
                                "all",
                                "--threads",
                                "2",
                                "--quiet",
                                "--json",
                                "--db",
                                d / "db.sqlite",
                                "--checkpoint",
                                ck,
                                "--checkpoint-every",
                                "0.05"};
  const SignalledRun s = signal_job(d, args, GetParam(), 1000);
  expect_interrupted(s, GetParam(), "checkpoint written to " + ck);
  EXPECT_LT(s.seconds, 5);
  EXPECT_EQ(hidden_leftovers(d.path), std::vector<std::string>{});
  EXPECT_EQ(nlohmann::json::parse(s.out)["complete"], false);
  CliResult r = run_cli("pack --quiet --json --resume " + ck + " --db " + (d / "db.sqlite"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.json()["complete"], true);
  EXPECT_EQ(r.json()["solutions"], 203520);
}

// The transducer route of kari-14 up to k = 9 (seconds), interrupted and resumed, ends as the
// uninterrupted run; with --route both one signal stops both routes.
TEST_P(RunSignals, AperiodicVerifyCheckpointsStopsEveryRouteAndResumesToTheSameVerdict) {
  TempDir d;
  const std::string ck = d / "ck";
  const std::vector<std::string> args{
      "aperiodic",    "verify",  "kari-14",   "--route", "both",         "--max-k", "9",
      "--time-limit", "0",       "--threads", "2",       "--checkpoint", ck,        "--checkpoint-every",
      "0.1",          "--quiet", "--json"};
  const SignalledRun s = signal_job(d, args, GetParam(), 500);
  expect_interrupted(s, GetParam(), "checkpoint written to " + ck);
  EXPECT_LT(s.seconds, 5);  // the torus route did not run on after the signal
  EXPECT_EQ(hidden_leftovers(d.path), std::vector<std::string>{});
  const std::string rest = "aperiodic verify kari-14 --route transducer --max-k 9 --time-limit 0 --quiet --json";
  CliResult resumed = run_cli(rest + " --resume " + ck);
  ASSERT_EQ(resumed.code, 0) << resumed.err;
  CliResult whole = run_cli(rest);
  ASSERT_EQ(whole.code, 0) << whole.err;
  for (const char* key : {"verdict", "route"}) EXPECT_EQ(resumed.json()[key], whole.json()[key]) << key;
  EXPECT_EQ(resumed.json()["transducer"]["k_rows"], whole.json()["transducer"]["k_rows"]);
  EXPECT_EQ(resumed.json()["transducer"]["k_columns"], whole.json()["transducer"]["k_columns"]);
  // The torus route alone keeps no checkpoint: it stops as quickly and says nothing was kept
  // (asked for a checkpoint, it refuses before any work: AperiodicCli.BadInput...).
  const SignalledRun t = signal_job(d,
                                    {"aperiodic", "verify", "kari-14", "--route", "torus", "--max-period", "40",
                                     "--time-limit", "0", "--threads", "2", "--quiet"},
                                    GetParam(), 500);
  expect_interrupted(t, GetParam(), "nothing kept");
  EXPECT_LT(t.seconds, 5);
}

// labbe-19 to depth 2 (seconds), interrupted mid-run: the resumed run's digest is the uninterrupted one.
TEST_P(RunSignals, AperiodicEnumerateCheckpointsAndTheResumeEndsTheSame) {
  TempDir d;
  const std::string ck = d / "ck";
  auto args = [&](bool resume) {
    std::vector<std::string> a{"aperiodic",          "enumerate", "--source",     "labbe-19", "--max-depth", "2",
                               "--max-tiles",        "40",        "--batch",      "1",        "--threads",   "2",
                               "--checkpoint-every", "0",         "--checkpoint", ck,         "--quiet",     "--json"};
    if (resume) a.insert(a.end(), {"--resume", ck});
    return a;
  };
  const SignalledRun s = signal_job(d, args(false), GetParam(), 700);
  expect_interrupted(s, GetParam(), "checkpoint written to " + ck);
  EXPECT_LT(s.seconds, 10);
  EXPECT_EQ(hidden_leftovers(d.path), std::vector<std::string>{});
  std::string cmd;
  for (const std::string& a : args(true)) cmd += q(a) + " ";
  CliResult resumed = run_cli(cmd);
  ASSERT_EQ(resumed.code, 0) << resumed.err;
  EXPECT_EQ(resumed.json()["complete"], true);
  EXPECT_EQ(resumed.json()["resumed"], true);
  fs::remove(ck);
  cmd.clear();
  for (const std::string& a : args(false)) cmd += q(a) + " ";
  CliResult whole = run_cli(cmd);
  ASSERT_EQ(whole.code, 0) << whole.err;
  EXPECT_EQ(resumed.json()["digest"], whole.json()["digest"]);
  EXPECT_EQ(resumed.json()["sets"], whole.json()["sets"]);
}
