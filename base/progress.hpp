#pragma once
// One progress reporter for every long-running loop in Tilekit (pbrt's ProgressReporter):
// a bar with an ETA when stderr is a terminal, otherwise one log line every few seconds.
// Always on stderr, so `--json` output on stdout stays one JSON object.
//
//   ProgressReporter p("pack wang C=3", total_work, options.progress);
//   for (...) { ...; p.add(1); }          // thread-safe
//   p.set_detail("1.2M nodes");            // optional text after the bar
//   p.finish();                            // also done by the destructor
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace tilekit {

class ProgressReporter {
 public:
  // `total` may be 0 when unknown (no bar fraction and no ETA until set_total()).
  // `enabled` false makes every call a no-op. `log_every`: seconds between log lines when
  // stderr is not a terminal (a terminal bar redraws at most 10 times a second).
  ProgressReporter(std::string title, double total, bool enabled = true, double log_every = 5.0);
  ~ProgressReporter();
  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;

  void add(double work = 1);  // done += work
  void set(double done);      // done = work
  void set_total(double total);
  void set_detail(std::string detail);
  // Sets done/total and detail at once and redraws if due (for monitors that poll counters).
  void update(double done, double total, std::string detail);
  void finish();  // final line (bar at its last state) and a newline

  double elapsed() const;  // seconds since construction
  // Estimated seconds left from the fraction done so far; negative when unknown.
  double eta() const;

  // "1h02m", "3m05s", "12.3s": how the reporter prints durations.
  static std::string format_duration(double seconds);

 private:
  void maybe_print_locked(bool force);
  std::string line_locked() const;

  std::string title_, detail_;
  double total_, done_ = 0;
  bool enabled_, tty_, finished_ = false;
  double log_every_;
  std::chrono::steady_clock::time_point start_, last_print_;
  bool printed_ = false;
  mutable std::mutex mu_;
};

}  // namespace tilekit
