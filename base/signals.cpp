#include "base/signals.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstring>
#include <new>

#include "base/error.hpp"
#include "base/temp_files.hpp"

namespace tilekit {

namespace {
std::atomic<int> g_caught{0};  // written only by the handler (async-signal-safe)
static_assert(std::atomic<int>::is_always_lock_free);
extern "C" void on_stop_signal(int sig) {
  g_caught.store(sig, std::memory_order_relaxed);
}
constexpr int kSignals[] = {SIGTERM, SIGINT, SIGUSR1};
struct sigaction g_previous[3];
std::atomic<int> g_depth{0};  // nested catchers: only the outermost installs and restores
}  // namespace

SignalCatcher::SignalCatcher() {
  if (g_depth++ > 0) return;
  g_caught.store(0);
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  for (int i = 0; i < 3; ++i) sigaction(kSignals[i], &sa, &g_previous[i]);
}

SignalCatcher::~SignalCatcher() {
  if (--g_depth > 0) return;
  for (int i = 0; i < 3; ++i) sigaction(kSignals[i], &g_previous[i], nullptr);
  g_caught.store(0);  // the run it belonged to is over: no later loop may read it as its own
}

void SignalCatcher::catch_for_process() {
  // Built in static storage and never destroyed, so the handlers stay to the very end of the
  // process; no heap allocation, so LeakSanitizer has nothing to report.
  alignas(SignalCatcher) static unsigned char storage[sizeof(SignalCatcher)];
  [[maybe_unused]] static SignalCatcher* forever = new (storage) SignalCatcher;
}

namespace {
extern "C" void on_exit_signal(int sig) {
  TempFiles::remove_all_in_signal_handler();
  const char* line = sig == SIGTERM ? "tilekit: interrupted by SIGTERM: nothing kept\n"
                                    : "tilekit: interrupted by SIGINT: nothing kept\n";
  [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, line, std::strlen(line));
  ::_exit(3);
}
}  // namespace

void exit_on_signal_after_cleanup() {
  struct sigaction sa {};
  sa.sa_handler = on_exit_signal;
  sigemptyset(&sa.sa_mask);
  sigaddset(&sa.sa_mask, SIGTERM);
  sigaddset(&sa.sa_mask, SIGINT);
  sigaction(SIGTERM, &sa, nullptr);
  sigaction(SIGINT, &sa, nullptr);
}

int SignalCatcher::caught() {
  return g_caught.load(std::memory_order_relaxed);
}

std::string signal_name(int sig) {
  switch (sig) {
    case SIGTERM:
      return "SIGTERM";
    case SIGINT:
      return "SIGINT";
    case SIGUSR1:
      return "SIGUSR1";
    default:
      return fmt::format("signal {}", sig);
  }
}

std::string interrupted_message(int sig, std::string_view kept) {
  return fmt::format("interrupted by {}: {}", signal_name(sig), kept);
}

void throw_if_interrupted() {
  if (const int sig = SignalCatcher::caught()) throw Interrupted(interrupted_message(sig, "nothing kept"));
}

}  // namespace tilekit
