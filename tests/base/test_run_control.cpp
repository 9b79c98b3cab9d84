// The run control every long job shares (base/run_control.hpp, base/signals.hpp,
// base/temp_files.hpp, base/checkpoint_envelope.hpp): one meaning of --threads 0, one deadline
// check, one shard rule, the checkpoint envelope's refusals, the temporary-file registry and the
// one line an interrupted job ends with.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <string>
#include <thread>

#include "base/atomic_file.hpp"
#include "base/checkpoint_envelope.hpp"
#include "base/error.hpp"
#include "base/run_control.hpp"
#include "base/signals.hpp"
#include "base/temp_files.hpp"
#include "tests/cli_runner.hpp"

using namespace tilekit;
namespace fs = std::filesystem;

namespace {

template <class F>
std::string run_control_refusal(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no InputError";
}

// Names in `dir` that start with a dot (the temp files and folders of base/atomic_file.hpp).
std::set<std::string> hidden_entries(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().starts_with(".")) out.insert(e.path().filename().string());
  return out;
}

}  // namespace

TEST(RunControl, ZeroThreadsIsEveryCoreAndOtherCountsAreCheckedOnce) {
  EXPECT_EQ(resolve_threads(0), omp_get_max_threads());
  EXPECT_EQ(resolve_threads(3), 3);
  EXPECT_EQ(resolve_threads(kMaxThreads), kMaxThreads);
  EXPECT_EQ(run_control_refusal([] { resolve_threads(-1); }),
            "`threads` must be between 0 (every core) and 4096, got -1");
  EXPECT_EQ(run_control_refusal([] { resolve_threads(kMaxThreads + 1, "--jobs"); }),
            "--jobs must be between 0 (every core) and 4096, got 4097");
}

TEST(RunControl, ADeadlineOfZeroNegativeNanOrHugeIsNone) {
  for (double none : {0.0, -1.0, std::nan(""), 2e9, std::numeric_limits<double>::infinity()}) {
    const Deadline d(none);
    EXPECT_FALSE(d.limited()) << none;
    EXPECT_FALSE(d.expired()) << none;
  }
  EXPECT_FALSE(Deadline().limited());
  const Deadline soon(0.05);
  EXPECT_TRUE(soon.limited());
  EXPECT_FALSE(soon.expired());
  EXPECT_GT(soon.seconds_left(), 0.0);
  EXPECT_LE(soon.seconds_left(), 0.05);
  std::this_thread::sleep_for(std::chrono::milliseconds(80));
  EXPECT_TRUE(soon.expired());
  EXPECT_EQ(soon.seconds_left(), 0.0);
  const Deadline later(100);
  EXPECT_EQ(later.sooner(soon).when(), soon.when());
  EXPECT_EQ(Deadline().sooner(later).when(), later.when());
}

TEST(RunControl, PollStopNamesTheFirstReason) {
  StopToken stop;
  EXPECT_FALSE(poll_stop(stop, Deadline(100), false));
  const Deadline past = Deadline::at(Deadline::Clock::now() - std::chrono::seconds(1));
  EXPECT_TRUE(poll_stop(stop, past, false));
  EXPECT_EQ(stop.reason(), StopReason::TimeLimit);
  stop.request(StopReason::Signal);  // the first reason stays
  EXPECT_EQ(stop.reason(), StopReason::TimeLimit);
}

TEST(RunControl, EveryPieceBelongsToExactlyOneShard) {
  for (int count : {1, 2, 3, 7}) {
    for (std::uint64_t i = 0; i < 100; ++i) {
      int owners = 0;
      for (int index = 0; index < count; ++index) owners += ShardSpec{index, count}.owns(i);
      EXPECT_EQ(owners, 1) << i << " of " << count;
    }
  }
  EXPECT_TRUE((ShardSpec{2, 3}.owns(5)));
  EXPECT_FALSE((ShardSpec{2, 3}.owns(6)));
  EXPECT_TRUE((ShardSpec{0, 1}.valid()));
  EXPECT_FALSE((ShardSpec{3, 3}.valid()));
  EXPECT_FALSE((ShardSpec{-1, 3}.valid()));
  EXPECT_FALSE((ShardSpec{0, 0}.valid()));
}

TEST(CheckpointEnvelope, RoundTripsAndRefusesTruncatedCorruptOversizedAndForeignFiles) {
  test::TempDir d;
  const std::string path = d / "ck", body = R"({"state": [1, 2, 3]})";
  write_checkpoint_envelope(path, "TILEKIT-TEST", 2, body);
  EXPECT_EQ(read_checkpoint_envelope(path, "TILEKIT-TEST", 2, 2), body);
  int version = 0;
  EXPECT_EQ(read_checkpoint_envelope(path, "TILEKIT-TEST", 1, 3, &version), body);
  EXPECT_EQ(version, 2);
  EXPECT_TRUE(hidden_entries(d.path).empty());  // the atomic write left no temp file
  const std::string text = test::slurp(path);

  auto refused = [&](const std::string& contents, const std::string& message, std::uint64_t max = kMaxCheckpointBytes) {
    test::write_text(path, contents);
    const std::string m =
        run_control_refusal([&] { read_checkpoint_envelope(path, "TILEKIT-TEST", 2, 2, nullptr, max); });
    EXPECT_NE(m.find(message), std::string::npos) << m;
  };
  refused(text.substr(0, text.size() - 3), "truncated (" + std::to_string(body.size() - 3) + " of");
  std::string corrupt = text;
  corrupt[corrupt.size() - 4] ^= 1;
  refused(corrupt, "corrupt (checksum mismatch)");
  refused(text + "x", "corrupt (1 bytes after the end)");
  refused(seal_checkpoint("TILEKIT-TEST", 3, body), "format version 3 is not supported (this build reads version 2)");
  refused(seal_checkpoint("TILEKIT-OTHER", 2, body), "not a Tilekit checkpoint file of this kind (TILEKIT-TEST)");
  refused(text, "more than the limit of 16 bytes", 16);
  refused("", "not a Tilekit checkpoint file");
  EXPECT_EQ(run_control_refusal([&] { read_checkpoint_envelope(d / "missing", "TILEKIT-TEST", 2, 2); }),
            d / "missing" + ": no such checkpoint");
  EXPECT_NE(run_control_refusal([&] {
              read_checkpoint_envelope(d.path.string(), "TILEKIT-TEST", 2, 2);
            }).find("not a regular file"),
            std::string::npos);
}

TEST(TempFiles, AnAtomicWriterIsRegisteredUntilCommittedAndRemoveAllClearsLeftovers) {
  test::TempDir d;
  const std::size_t before = TempFiles::count();
  {
    AtomicFileWriter w(d / "a.txt");
    w.write("hello");
    EXPECT_EQ(TempFiles::count(), before + 1);
    EXPECT_EQ(hidden_entries(d.path).size(), 1u);
    w.commit();
  }
  EXPECT_EQ(TempFiles::count(), before);
  EXPECT_EQ(test::slurp(d / "a.txt"), "hello");
  {
    AtomicFileWriter w(d / "b.txt");
    w.write("half");
  }  // destroyed before commit: its temp file goes
  EXPECT_EQ(TempFiles::count(), before);
  EXPECT_TRUE(hidden_entries(d.path).empty());
  EXPECT_FALSE(fs::exists(d / "b.txt"));
  // A temp file handed over (finish_temp) and never renamed: what remove_all() is for.
  AtomicFileWriter w(d / "c.txt");
  w.write("orphan");
  const std::string tmp = w.finish_temp();
  EXPECT_TRUE(fs::exists(tmp));
  EXPECT_EQ(TempFiles::remove_all(), before + 1);
  EXPECT_FALSE(fs::exists(tmp));
  EXPECT_TRUE(hidden_entries(d.path).empty());
}

TEST(TempFiles, AnAtomicFolderReplacesTheOldFolderWholeOrLeavesItAsItWas) {
  test::TempDir d;
  const std::string out = d / "set";
  fs::create_directories(out);
  test::write_text(out + "/tile-0000.png", "old");
  test::write_text(out + "/tile-0001.png", "old, stale after a smaller set");
  {
    AtomicFolder f(out);
    test::write_text(f.temp_path() + "/tile-0000.png", "new");
    EXPECT_EQ(hidden_entries(d.path).size(), 1u);
  }  // not committed (a signal, an error): the old set stays, the temp folder goes
  EXPECT_TRUE(hidden_entries(d.path).empty());
  EXPECT_EQ(test::slurp(out + "/tile-0000.png"), "old");
  EXPECT_TRUE(fs::exists(out + "/tile-0001.png"));
  {
    AtomicFolder f(out + "/");
    test::write_text(f.temp_path() + "/tile-0000.png", "new");
    f.commit();
  }
  EXPECT_EQ(test::slurp(out + "/tile-0000.png"), "new");
  EXPECT_FALSE(fs::exists(out + "/tile-0001.png"));
  EXPECT_TRUE(hidden_entries(d.path).empty());
  test::write_text(d / "file", "x");
  EXPECT_NE(run_control_refusal([&] { AtomicFolder f(d / "file"); }).find("is not a folder"), std::string::npos);
}

TEST(Signals, ACaughtSignalIsOneInterruptedLineAndEndsWithItsCatcher) {
  EXPECT_EQ(signal_name(SIGTERM), "SIGTERM");
  EXPECT_EQ(signal_name(SIGINT), "SIGINT");
  EXPECT_EQ(interrupted_message(SIGINT, "checkpoint written to c"), "interrupted by SIGINT: checkpoint written to c");
  {
    SignalCatcher catcher;
    EXPECT_NO_THROW(throw_if_interrupted());
    ASSERT_EQ(std::raise(SIGTERM), 0);
    EXPECT_EQ(SignalCatcher::caught(), SIGTERM);
    try {
      throw_if_interrupted();
      ADD_FAILURE() << "no Interrupted";
    } catch (const Interrupted& e) {
      EXPECT_STREQ(e.what(), "interrupted by SIGTERM: nothing kept");
    }
  }
  EXPECT_EQ(SignalCatcher::caught(), 0);  // a later run in this process does not see it
  EXPECT_NO_THROW(throw_if_interrupted());
}
