// The shared progress reporter: log lines on a non-terminal stderr, nothing when disabled.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <functional>

#include "tests/cli_runner.hpp"
#include "base/progress.hpp"

using namespace tilekit;

namespace {

// Runs f with stderr redirected to a file; returns what was written.
std::string capture_stderr(const std::function<void()>& f) {
  test::TempDir d;
  std::string path = d / "err";
  std::fflush(stderr);
  int saved = ::dup(2);
  int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ::dup2(fd, 2);
  ::close(fd);
  f();
  std::fflush(stderr);
  ::dup2(saved, 2);
  ::close(saved);
  return test::slurp(path);
}

}  // namespace

TEST(ProgressReporter, LogsLinesWithFractionEtaAndDetailWhenNotATerminal) {
  std::string out = capture_stderr([] {
    ProgressReporter p("pack test", 4, true, 0.0);
    p.add(1);
    p.set_detail("12 nodes");
    p.add(1);
    p.finish();
  });
  EXPECT_NE(out.find("pack test  25.0%"), std::string::npos) << out;
  EXPECT_NE(out.find(" 50.0%"), std::string::npos) << out;
  EXPECT_NE(out.find("ETA "), std::string::npos) << out;
  EXPECT_NE(out.find("12 nodes"), std::string::npos) << out;
  EXPECT_EQ(out.find('\r'), std::string::npos);  // no terminal redraws in a log
}

TEST(ProgressReporter, ThrottlesLogLinesAndIsSilentWhenDisabled) {
  std::string out = capture_stderr([] {
    ProgressReporter p("slow", 1000, true, 3600.0);
    for (int i = 0; i < 1000; ++i) p.add(1);
  });
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1);  // only the final line
  std::string none = capture_stderr([] {
    ProgressReporter p("off", 10, false, 0.0);
    p.add(5);
  });
  EXPECT_TRUE(none.empty());
}

TEST(ProgressReporter, FormatsDurations) {
  EXPECT_EQ(ProgressReporter::format_duration(12.34), "12.3s");
  EXPECT_EQ(ProgressReporter::format_duration(185), "3m05s");
  EXPECT_EQ(ProgressReporter::format_duration(3 * 3600 + 120), "3h02m");
  EXPECT_EQ(ProgressReporter::format_duration(5 * 86400 + 7200), "5d02h");
  EXPECT_EQ(ProgressReporter::format_duration(-1), "?");
}
