#pragma once
// What the solver benchmarks share (bench_solver, bench_impose, bench_parallel): process CPU
// seconds (getrusage: every thread of the process), the median of a sample and the load average,
// so that every bench reports its figures the same way.
#include <sys/resource.h>

#include <algorithm>
#include <fstream>
#include <vector>

namespace tilekit::bench {

inline double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// The upper median of the sample (0 when empty).
inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

// The one-minute load average of the machine (/proc/loadavg; 0 where there is none).
inline double loadavg() {
  std::ifstream in("/proc/loadavg");
  double l = 0;
  in >> l;
  return l;
}

}  // namespace tilekit::bench
