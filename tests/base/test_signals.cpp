// SignalCatcher (base/signals.hpp): SIGTERM, SIGINT and SIGUSR1 set the flag instead of ending
// the process, a nested catcher only joins the outer one, and the outermost restores the
// handlers that were there before.
#include <gtest/gtest.h>

#include <csignal>

#include "base/signals.hpp"

using namespace tilekit;

namespace {

volatile std::sig_atomic_t g_previous_saw = 0;
extern "C" void previous_handler(int sig) {
  g_previous_saw = sig;
}

// Installs previous_handler for the three signals; restores the originals when destroyed.
struct PreviousHandlers {
  struct sigaction saved[3];
  static constexpr int kSignals[3] = {SIGTERM, SIGINT, SIGUSR1};
  PreviousHandlers() {
    struct sigaction sa {};
    sa.sa_handler = previous_handler;
    sigemptyset(&sa.sa_mask);
    for (int i = 0; i < 3; ++i) sigaction(kSignals[i], &sa, &saved[i]);
  }
  ~PreviousHandlers() {
    for (int i = 0; i < 3; ++i) sigaction(kSignals[i], &saved[i], nullptr);
  }
};

void (*handler_of(int sig))(int) {
  struct sigaction now {};
  sigaction(sig, nullptr, &now);
  return now.sa_handler;
}

}  // namespace

TEST(SignalCatcher, SeesEachStopSignalAndRestoresThePreviousHandler) {
  PreviousHandlers previous;
  for (int sig : {SIGTERM, SIGINT, SIGUSR1}) {
    {
      SignalCatcher catcher;
      EXPECT_EQ(SignalCatcher::caught(), 0) << "a new catcher starts clear";
      EXPECT_NE(handler_of(sig), &previous_handler);
      ASSERT_EQ(std::raise(sig), 0);  // the process lives on: the catcher took it
      EXPECT_EQ(SignalCatcher::caught(), sig);
    }
    EXPECT_EQ(handler_of(sig), &previous_handler) << sig;
    g_previous_saw = 0;
    ASSERT_EQ(std::raise(sig), 0);
    EXPECT_EQ(g_previous_saw, sig) << "the restored handler runs again";
  }
}

TEST(SignalCatcher, ANestedCatcherJoinsAndOnlyTheOutermostRestores) {
  PreviousHandlers previous;
  {
    SignalCatcher outer;
    {
      SignalCatcher inner;
      ASSERT_EQ(std::raise(SIGUSR1), 0);
      EXPECT_EQ(SignalCatcher::caught(), SIGUSR1);
    }
    EXPECT_NE(handler_of(SIGTERM), &previous_handler) << "the inner catcher restored too early";
    EXPECT_EQ(SignalCatcher::caught(), SIGUSR1) << "the flag outlives the inner catcher";
    ASSERT_EQ(std::raise(SIGTERM), 0);
    EXPECT_EQ(SignalCatcher::caught(), SIGTERM);
  }
  EXPECT_EQ(handler_of(SIGTERM), &previous_handler);
  EXPECT_EQ(handler_of(SIGINT), &previous_handler);
  EXPECT_EQ(handler_of(SIGUSR1), &previous_handler);
}

TEST(SignalCatcher, ANewOutermostCatcherClearsAnOldSignal) {
  PreviousHandlers previous;
  {
    SignalCatcher first;
    ASSERT_EQ(std::raise(SIGINT), 0);
    EXPECT_EQ(SignalCatcher::caught(), SIGINT);
  }
  SignalCatcher second;
  EXPECT_EQ(SignalCatcher::caught(), 0);
}
