#pragma once
// One way to run work on threads (pbrt-v4's ParallelFor, OpenMP underneath) and one way to
// stop it: a StopToken that records why a run stops (found, signal, time limit, error), the
// first reason winning. Long loops check `stop.requested()`; signals reach a run through the
// monitor that polls SignalCatcher (base/signals.hpp) and requests StopReason::Signal.
#include <fmt/format.h>
#include <omp.h>

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <mutex>

#include "base/error.hpp"

namespace tilekit {

enum class StopReason : int { None = 0, Found, Signal, TimeLimit, Error, Exhausted, Cancelled };

class StopToken {
 public:
  bool requested() const noexcept { return reason_.load(std::memory_order_relaxed) != 0; }
  StopReason reason() const noexcept { return StopReason(reason_.load()); }
  // Sets the reason unless one is set already; true when this call set it.
  bool request(StopReason why) noexcept {
    int expected = 0;
    return reason_.compare_exchange_strong(expected, int(why));
  }

 private:
  std::atomic<int> reason_{0};
};

// The most threads any command accepts: far above any machine Tilekit runs on, far below what
// makes the OpenMP runtime fail to create a team (100000 threads crash libgomp).
inline constexpr int kMaxThreads = 4096;

// The thread count of a run that does not name one: OMP_NUM_THREADS, else every core.
inline int default_thread_count() { return omp_get_max_threads(); }

// Throws InputError unless 1 <= threads <= kMaxThreads; `what` names the value (the request
// field `threads`: a RequestError, base/error.hpp).
inline int checked_thread_count(std::int64_t threads, std::string_view what = "`threads`") {
  if (threads < 1 || threads > kMaxThreads)
    throw_input_error(what, fmt::format("{} must be between 1 and {}, got {}", what, kMaxThreads, threads));
  return int(threads);
}

// Ends the idle OpenMP threads of the calling thread's pool. OpenMP keeps a team's threads for
// the next parallel region, and libgomp's default wait policy has each of them spin first (300,000
// pause loops, GOMP_SPINCOUNT, about 10-20 ms of a core on the machines measured) before it
// sleeps: a short search ended that way burns a core while the caller validates, stores and
// prints alone (a quarter of a C=4 `pack` run's CPU, BENCHMARKS.md). A soft pause (OpenMP 5.0
// omp_pause_resource) lets them exit instead; the next region starts new ones (tens of
// microseconds each), so call it where a caller goes on alone for a while (the end of a search),
// not between back-to-back regions. A no-op inside a parallel region, and when the user chose a
// wait policy (OMP_WAIT_POLICY or GOMP_SPINCOUNT set).
inline void release_idle_threads() {
  static const bool chosen = std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT");
  if (!chosen && omp_get_level() == 0) omp_pause_resource(omp_pause_soft, omp_get_initial_device());
}

// Runs body(thread) once on each of `threads` threads (a team whose members take their own
// work). The first exception a member throws is rethrown after the whole team has ended;
// with a `stop` token it also requests StopReason::Error so that the others end early.
template <class F>
void parallel_team(int threads, F&& body, StopToken* stop = nullptr) {
  checked_thread_count(threads);  // the one backstop: no team beyond kMaxThreads reaches libgomp
  std::exception_ptr error;
  std::mutex error_mu;
#pragma omp parallel num_threads(threads)
  {
    try {
      body(omp_get_thread_num());
    } catch (...) {
      std::lock_guard lock(error_mu);
      if (!error) error = std::current_exception();
      if (stop) stop->request(StopReason::Error);
    }
  }
  if (error) std::rethrow_exception(error);
}

// Runs body(i) for every i in [0, n) on `threads` threads, dynamically scheduled one index at
// a time (uneven work such as torus shapes or rows). Once `stop` is requested no new index
// starts. Exceptions as in parallel_team.
template <class F>
void parallel_for(std::int64_t n, int threads, F&& body, StopToken* stop = nullptr) {
  StopToken local;
  StopToken& token = stop ? *stop : local;
  std::atomic<std::int64_t> next{0};
  parallel_team(
      threads,
      [&](int) {
        for (std::int64_t i; !token.requested() && (i = next.fetch_add(1)) < n;) body(i);
      },
      &token);
}

}  // namespace tilekit
