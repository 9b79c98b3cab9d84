#include "base/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace tilekit {

ProgressReporter::ProgressReporter(std::string title, double total, bool enabled, double log_every)
    : title_(std::move(title)),
      total_(total),
      enabled_(enabled),
      tty_(enabled && ::isatty(STDERR_FILENO) == 1),
      log_every_(log_every),
      start_(std::chrono::steady_clock::now()),
      last_print_(start_) {}

ProgressReporter::~ProgressReporter() {
  finish();
}

void ProgressReporter::add(double work) {
  if (!enabled_) return;
  std::lock_guard lock(mu_);
  done_ += work;
  maybe_print_locked(false);
}

void ProgressReporter::set(double done) {
  if (!enabled_) return;
  std::lock_guard lock(mu_);
  done_ = done;
  maybe_print_locked(false);
}

void ProgressReporter::set_total(double total) {
  std::lock_guard lock(mu_);
  total_ = total;
}

void ProgressReporter::set_detail(std::string detail) {
  std::lock_guard lock(mu_);
  detail_ = std::move(detail);
}

void ProgressReporter::update(double done, double total, std::string detail) {
  if (!enabled_) return;
  std::lock_guard lock(mu_);
  done_ = done;
  total_ = total;
  detail_ = std::move(detail);
  maybe_print_locked(false);
}

double ProgressReporter::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

double ProgressReporter::eta() const {
  double f = total_ > 0 ? done_ / total_ : 0;
  if (f <= 0 || f > 1) return -1;
  return elapsed() * (1 - f) / f;
}

std::string ProgressReporter::format_duration(double s) {
  if (s < 0 || !std::isfinite(s)) return "?";
  if (s < 60) return fmt::format("{:.1f}s", s);
  auto t = static_cast<long long>(s + 0.5);
  if (t < 3600) return fmt::format("{}m{:02}s", t / 60, t % 60);
  if (t < 86400 * 2) return fmt::format("{}h{:02}m", t / 3600, (t / 60) % 60);
  return fmt::format("{}d{:02}h", t / 86400, (t / 3600) % 24);
}

std::string ProgressReporter::line_locked() const {
  std::string s = title_;
  if (total_ > 0) {
    double f = std::clamp(done_ / total_, 0.0, 1.0);
    if (tty_) {
      constexpr int width = 30;
      int fill = static_cast<int>(f * width);
      s += " [" + std::string(std::size_t(fill), '=') + std::string(std::size_t(width - fill), ' ') + "]";
    }
    s += fmt::format(" {:5.1f}%", 100 * f);
  }
  s += " " + format_duration(elapsed());
  if (double e = eta(); e >= 0) s += " ETA " + format_duration(e);
  if (!detail_.empty()) s += "  " + detail_;
  return s;
}

void ProgressReporter::maybe_print_locked(bool force) {
  if (!enabled_ || finished_) return;
  auto now = std::chrono::steady_clock::now();
  double since = std::chrono::duration<double>(now - last_print_).count();
  if (!force && since < (tty_ ? 0.1 : log_every_)) return;
  last_print_ = now;
  printed_ = true;
  std::string line = line_locked();
  if (tty_)
    std::fprintf(stderr, "\r%s\033[K", line.c_str());
  else
    std::fprintf(stderr, "%s\n", line.c_str());
  std::fflush(stderr);
}

void ProgressReporter::finish() {
  if (!enabled_) return;
  std::lock_guard lock(mu_);
  if (finished_) return;
  maybe_print_locked(true);
  if (tty_) std::fprintf(stderr, "\n");
  finished_ = true;
}

}  // namespace tilekit
