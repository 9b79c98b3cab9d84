#include "base/run_control.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <cmath>

#include "base/error.hpp"
#include "base/signals.hpp"

namespace tilekit {

int checked_thread_count(std::int64_t threads, const char* flag) {
  if (threads < 1 || threads > kMaxThreads)
    throw_input_error(flag, fmt::format("{} must be between 1 and {}, got {}", flag, kMaxThreads, threads));
  return int(threads);
}

int resolve_threads(std::int64_t requested, const char* flag) {
  if (requested == 0) return omp_get_max_threads();
  if (requested < 0 || requested > kMaxThreads)
    throw_input_error(flag,
                      fmt::format("{} must be between 0 (every core) and {}, got {}", flag, kMaxThreads, requested));
  return int(requested);
}

Deadline::Deadline(double seconds, Clock::time_point from) {
  if (!(seconds > 0) || seconds > kMaxTimeLimitSeconds) return;
  when_ = from + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

double Deadline::seconds_left() const {
  if (!limited()) return 2 * kMaxTimeLimitSeconds;
  return std::max(0.0, std::chrono::duration<double>(when_ - Clock::now()).count());
}

bool poll_stop(StopToken& stop, const Deadline& deadline, bool catch_signals) {
  if (catch_signals && SignalCatcher::caught()) stop.request(StopReason::Signal);
  if (deadline.expired()) stop.request(StopReason::TimeLimit);
  return stop.requested();
}

}  // namespace tilekit
