#pragma once
// How a long job runs, as opposed to what it computes: the pieces every long command shares
// (pack, aperiodic enumerate and verify, points tiles and generate, texture tiles), each held
// one way and checked in one place:
//   - threads: 0 means every core (OMP_NUM_THREADS when set), 1..kMaxThreads that many
//     (resolve_threads, the one place a thread count is defaulted);
//   - a Deadline: a time limit of 0, or one beyond kMaxTimeLimitSeconds, is none; expired() is
//     the one time-limit check;
//   - ShardSpec: shard `index` of `count`; owns(i) is the one rule of which work a shard does;
//   - StopToken: why a run stops (found, signal, time limit, error), the first reason winning.
// Signals, the temporary files a signal must not leave behind and the one line an interrupted
// job prints are base/signals.hpp; the checkpoint envelope is base/checkpoint_envelope.hpp.
#include <atomic>
#include <chrono>
#include <cstdint>

namespace tilekit {

// ---- threads ----

// The most threads any command accepts: far above any machine Tilekit runs on, far below what
// makes the OpenMP runtime fail to create a team (100000 threads crash libgomp).
inline constexpr int kMaxThreads = 4096;

// The thread count of a run asked for `requested` threads: 0 = every core (OMP_NUM_THREADS when
// set), else 1..kMaxThreads (an InputError naming `flag` otherwise: a RequestError when it is a field between backquotes, base/error.hpp). The one place a thread count is
// defaulted: every command and library that takes a thread count calls it.
int resolve_threads(std::int64_t requested, const char* flag = "`threads`");

// Throws InputError unless 1 <= threads <= kMaxThreads (0 is refused: a team needs a thread).
int checked_thread_count(std::int64_t threads, const char* flag = "`threads`");

// ---- time ----

// Time limits beyond this (about 31 years) are none: a deadline that far ahead would overflow
// the clock's 64-bit nanoseconds and fall in the past.
inline constexpr double kMaxTimeLimitSeconds = 1e9;

// The end of a run's time. Default: none. `expired()` is the one time-limit check of the code
// base; a job that splits its time (aperiodic verify's two routes) hands out sooner Deadlines.
class Deadline {
 public:
  using Clock = std::chrono::steady_clock;
  Deadline() = default;
  // `seconds` after `from`; none for 0, a negative or NaN value, or one beyond kMaxTimeLimitSeconds.
  // (A library's tolerance: every `--time-limit` flag refuses a negative, NaN or infinite value
  // before a run starts, cli/numeric_flags.hpp, and 0 means none there too.)
  explicit Deadline(double seconds, Clock::time_point from = Clock::now());
  static Deadline at(Clock::time_point when) {
    Deadline d;
    d.when_ = when;
    return d;
  }
  bool limited() const { return when_ != Clock::time_point::max(); }
  bool expired() const { return limited() && Clock::now() >= when_; }
  // Seconds left (0 once expired); a huge number when there is no limit.
  double seconds_left() const;
  Clock::time_point when() const { return when_; }
  // The earlier of the two.
  Deadline sooner(const Deadline& other) const { return other.when_ < when_ ? other : *this; }

 private:
  Clock::time_point when_ = Clock::time_point::max();
};

// ---- shards ----

// The most shards a run may split into: far above Slurm's usual MaxArraySize (1001) and any
// useful subproblem count per shard (a search splits into about a thousand subproblems).
inline constexpr std::int64_t kMaxShards = 1'000'000;

// Shard `index` of `count` (0-based): the one rule of which piece of work a shard does.
struct ShardSpec {
  int index = 0, count = 1;
  // Piece `i` (a subproblem, a dive, a first step of an enumeration) belongs to this shard.
  bool owns(std::uint64_t i) const { return i % std::uint64_t(count) == std::uint64_t(index); }
  bool valid() const { return count >= 1 && count <= kMaxShards && index >= 0 && index < count; }
  bool operator==(const ShardSpec&) const = default;
};

// Part `part` of `parts` of a shard: the work unit of an adaptively split job array (cluster/
// split.hpp). A shard that ran past its time budget leaves its unfinished pieces to a follow-up
// array, whose task J of K takes the pieces i of the shard with (i / count) % K == J. Splitting
// a part again is a finer part of the same shard: part J of K split L ways gives parts J + K*M
// of K*L (M < L), each a subset of part J; so the parts of one round never overlap.
struct ShardPart {
  int part = 0, parts = 1;
  bool owns(std::uint64_t i, const ShardSpec& shard) const {
    return shard.owns(i) && (i / std::uint64_t(shard.count)) % std::uint64_t(parts) == std::uint64_t(part);
  }
  // Sub-part `m` of this part split `ways` ways.
  ShardPart refined(int m, int ways) const { return {part + parts * m, parts * ways}; }
  bool valid() const { return parts >= 1 && parts <= kMaxShards && part >= 0 && part < parts; }
  bool operator==(const ShardPart&) const = default;
};

// ---- stopping ----

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

// The one poll of a long loop: requests StopReason::Signal on a caught signal (with
// `catch_signals`), StopReason::TimeLimit once `deadline` expired; true when `stop` is requested
// (for whatever reason, also one set by another thread).
bool poll_stop(StopToken& stop, const Deadline& deadline, bool catch_signals);

}  // namespace tilekit
