#pragma once
// One way to run work on threads (pbrt-v4's ParallelFor, OpenMP underneath), stopped through
// the run control's StopToken (base/run_control.hpp: why a run stops, the first reason winning).
// Long loops check `stop.requested()`; signals reach a run through the monitor that polls
// SignalCatcher (base/signals.hpp) and requests StopReason::Signal, or through
// throw_if_interrupted() in a loop body, which ends the loop like any exception.
#include <fmt/format.h>
#include <omp.h>

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <mutex>

#include "base/error.hpp"
#include "base/run_control.hpp"

namespace tilekit {

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
