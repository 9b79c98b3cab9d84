#pragma once
// The parallel driver: splits a model's search tree into subproblems (decision prefixes at an
// adaptive depth), runs them on OpenMP threads with dynamic scheduling, and keeps enough
// state to checkpoint and resume at any moment (Gecode-style recomputation: a running
// subproblem is just its decision path).
//
//  - count/all: every subproblem of this shard is exhausted; counts are sums of per-subproblem
//    counts, so they do not depend on the thread count or the schedule.
//  - first: subproblems in DFS order (tiling problems), or, with `restarts`, every thread
//    runs randomised dives with Luby-sequence node limits (packing problems); the first
//    solution stops every thread.
//  - shards: subproblem i belongs to shard i mod N; the subproblem list depends only on the
//    model and N, so shards 0..N-1 together cover the tree exactly once. With restarts, shard I
//    runs the dives r = I, I+N, I+2N, ... (each seeded by r), so shards never repeat a dive.
//  - a monitor thread prints progress, writes checkpoints every `checkpoint_every` seconds,
//    and stops the workers on a signal or the time limit (then writes a final checkpoint).
//    The first checkpoint is written before any work, so a run killed at once can resume.
//  - scale-out (run_settings.hpp): with `run.trace` every subproblem (dive) run is a line of the
//    trace (run_trace.hpp); with `run.work` the workers take their subproblems from a WorkSource
//    (several processes of one MPI job) instead of the shard's list; the source may ask a worker
//    to give away the untried alternatives of its oldest open level (work stealing, see
//    work_source.hpp for what a checkpoint keeps of a split subproblem).
//  - statistics (search_stats.hpp): each worker's SubtreeSearch counts in plain integers; a
//    worker adds them to the run's total once, when it leaves (under stats_mu_).
//
// Over 400 lines on purpose: ParallelSearch is one class template whose workers, monitor,
// progress and checkpoint writer share its state (counters, the subproblem cursor, the stop
// token); split across files it would be read in pieces. The subproblem split is in
// subproblems.hpp.
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cassert>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "base/error.hpp"
#include "base/parallel.hpp"
#include "base/progress.hpp"
#include "base/signals.hpp"
#include "solver/dfs.hpp"
#include "solver/knuth_estimate.hpp"
#include "solver/luby.hpp"
#include "solver/model.hpp"
#include "solver/problem.hpp"
#include "solver/search_state.hpp"
#include "solver/subproblems.hpp"

namespace tilekit {

struct ParallelConfig {
  SearchMode mode = SearchMode::Count;
  // Threads, seed, time limit, shard, checkpoint interval, progress and signals (stop on
  // SignalCatcher::caught() with catch_signals). The checkpoint files are the caller's: `save`
  // and `resume` below.
  RunSettings run;
  std::string title = "search";
  bool restarts = false;              // first mode: Luby restarts from the root
  std::uint64_t restart_base = 2000;  // nodes per Luby unit
  // First mode with restarts: stop after this many dives (0: no bound), neither found nor complete
  // (the map filler's blocks grow when one fails; solver/fill_search.hpp).
  std::uint64_t max_dives = 0;
  std::size_t subproblem_target = 1024;
  std::uint64_t estimate_probes = 0;  // Knuth probes before the search (0 = none)
  std::string fingerprint;
  std::function<void(const SearchState&)> save;  // empty: no checkpoints
  const SearchState* resume = nullptr;
  std::function<void()> flush;  // called before each checkpoint is saved
};

struct ParallelOutcome {
  SearchCounters counts;  // finished subproblems + in-flight progress (+ restart nodes)
  bool complete = false, interrupted = false, timed_out = false, found = false;
  int signal = 0;
  double seconds = 0;        // this run
  double total_seconds = 0;  // including the runs this one resumed
  std::uint64_t subproblems = 0, shard_subproblems = 0, subproblems_done = 0, restarts = 0;
  std::size_t checkpoints_written = 0;
  TreeEstimate estimate;
  SearchStats stats;  // this run: counters, restarts, time per phase (not setup: solve() adds it)
};

template <SearchModel M>
class ParallelSearch {
 public:
  using Leaf = std::function<void(const M&, SearchCounters&)>;

  ParallelSearch(const M& root, ParallelConfig cfg, Leaf leaf)
      : root_(root), cfg_(std::move(cfg)), leaf_(std::move(leaf)) {
    if (cfg_.run.threads < 1) throw InputError(fmt::format("threads must be at least 1, got {}", cfg_.run.threads));
  }

  ParallelOutcome run() {
    start_ = std::chrono::steady_clock::now();
    deadline_ = Deadline(cfg_.run.time_limit, start_);
    ParallelOutcome out;
    if (cfg_.estimate_probes) {
      // The time limit ends the estimate but is not yet the run's stop: the search gets its slice.
      out.estimate = knuth_estimate(root_, cfg_.estimate_probes, cfg_.run.seed,
                                    [this] { return poll_stop(false) || deadline_.expired(); });
      stats_.estimate_seconds = elapsed();
    }
    estimate_ = out.estimate.nodes;
    prior_seconds_ = cfg_.resume ? cfg_.resume->seconds : 0;
    if (cfg_.mode == SearchMode::First && cfg_.restarts) {
      run_restarts(out);
    } else {
      run_subproblems(out);
    }
    out.seconds = elapsed();
    out.total_seconds = prior_seconds_ + out.seconds;
    out.found = found_.load();
    out.checkpoints_written = checkpoints_;
    out.signal = signal_;
    out.stats = stats_;
    out.stats.restarts = out.restarts;
    out.stats.checkpoints = checkpoints_;
    return out;
  }

 private:
  struct Job {
    std::uint64_t index = 0;
    std::vector<Decision> resume;
    SearchCounters counted;
    std::vector<Decision> piece;  // a piece of subproblem `index` given away by a split: its path
  };
  struct Slot {
    std::mutex mu;
    bool active = false;
    bool record = true;  // a piece's snapshot is not a checkpoint record (work_source.hpp)
    InFlightSubproblem snap;
    std::uint64_t epoch = 0;
    std::atomic<std::uint64_t> live_nodes{0};
    std::atomic<std::uint64_t> dive{kNoDive};  // first mode with restarts: the dive in progress
  };
  static constexpr std::uint64_t kNoDive = ~std::uint64_t(0);
  struct Control {
    ParallelSearch& s;
    Slot& slot;
    std::uint64_t index;
    std::uint64_t seen_epoch;
    std::uint64_t node_limit = 0;
    bool hit_limit = false;
    // The trace's pieces (run_trace.hpp): a new one starts at every node at most piece_depth deep
    // (an inner node above that depth is a piece of one node).
    std::size_t piece_depth = 0;  // 0: no pieces
    std::uint64_t piece_nodes = 0;
    std::chrono::steady_clock::time_point piece_start{};
    std::vector<std::pair<std::uint64_t, double>> pieces{};
    // Work stealing (solver/dfs.hpp's split_wanted/give): the source's flag, and whether this job
    // gave alternatives away.
    std::atomic<bool>* split_flag = nullptr;
    bool gave = false;
    bool split_wanted() const { return split_flag && split_flag->load(std::memory_order_relaxed); }
    bool give(std::vector<std::vector<Decision>> children) {
      if (!split_flag->exchange(false)) return false;  // another worker took the request
      s.cfg_.run.work->give(index, std::move(children));
      gave = true;
      return true;
    }
    void cut_piece(std::uint64_t nodes) {
      const auto now = std::chrono::steady_clock::now();
      if (nodes > piece_nodes)
        pieces.emplace_back(nodes - piece_nodes, std::chrono::duration<double>(now - piece_start).count());
      piece_nodes = nodes;
      piece_start = now;
    }
    bool at_node(const std::vector<Decision>& path, const SearchCounters& c) {
      if ((c.nodes & 1023) == 0) {
        slot.live_nodes.store(c.nodes, std::memory_order_relaxed);
        // The monitor thread keeps the time limit, but on a busy machine it may not run before a
        // short search ends: the workers look at the clock too.
        if (s.deadline_.expired()) s.stop_.request(StopReason::TimeLimit);
      }
      if (path.size() <= piece_depth) cut_piece(c.nodes);
      if (s.stop_.requested()) {
        publish(path, c, s.epoch_.load());
        return false;
      }
      std::uint64_t e = s.epoch_.load(std::memory_order_relaxed);
      if (e != seen_epoch) {
        publish(path, c, e);
        seen_epoch = e;
      }
      if (node_limit && c.nodes >= node_limit) {
        hit_limit = true;
        return false;
      }
      return true;
    }
    void publish(const std::vector<Decision>& path, const SearchCounters& c, std::uint64_t e) {
      std::lock_guard lock(slot.mu);
      slot.snap.index = index;
      slot.snap.path = path;
      slot.snap.counted = c;
      slot.epoch = e;
    }
    void leaf(const M& m, SearchCounters& c) { s.on_leaf(m, c); }
  };

  double elapsed() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

  void on_leaf(const M& m, SearchCounters& c) {
    if (cfg_.mode == SearchMode::First) {
      if (found_.exchange(true)) return;
      leaf_(m, c);
      stop_.request(StopReason::Found);
      return;
    }
    leaf_(m, c);
  }

  // ---- count / all / first-in-order: subproblems ----
  void run_subproblems(ParallelOutcome& out) {
    std::uint64_t split_nodes = 0;
    // Nothing stops the split (at most kMaxSplitSubproblems, a fraction of a second): a signal or a
    // time limit is looked at once it is done and the first checkpoint is written, so that a run
    // stopped at any moment, even before its search began, leaves a checkpoint to resume from, and
    // even slices shorter than the split get past it.
    const double split_start = elapsed();
    subs_ = split_subproblems(root_, cfg_.subproblem_target, split_nodes);
    stats_.split_seconds = elapsed() - split_start;
    stats_.nodes += split_nodes;
    std::uint64_t hash = hash_subproblems(subs_);
    out.subproblems = subs_.size();
    finished_.assign(subs_.size(), false);
    finished_each_.assign(subs_.size(), SearchCounters{});
    std::vector<Job> jobs;
    if (const SearchState* r = cfg_.resume) {
      if (r->subproblem_count != subs_.size() || r->subproblem_hash != hash)
        throw InputError(
            "checkpoint does not match this search: its subproblems differ (different problem or options)");
      try {  // a state made in memory gets the same structural checks as one read from a file
        check_search_state(*r, subs_.size(), cfg_.run.shard.index, cfg_.run.shard.count);
      } catch (const InputError& e) {
        throw InputError(fmt::format("checkpoint is inconsistent: {}", e.what()));
      }
      finished_ = r->finished;
      finished_counts_ = r->finished_counts;
      for (std::uint64_t i = 0, k = 0; i < finished_.size(); ++i)
        if (finished_[i]) finished_each_[i] = r->finished_each[k++];
      for (const InFlightSubproblem& f : r->in_flight) jobs.push_back({f.index, f.path, f.counted, {}});
    }
    for (std::uint64_t i = 0; i < subs_.size(); ++i) {
      if (!mine(i)) continue;
      ++out.shard_subproblems;
      if (finished_[i]) continue;
      bool inflight = std::any_of(jobs.begin(), jobs.end(), [&](const Job& j) { return j.index == i; });
      if (!inflight) jobs.push_back({i, {}, {}, {}});
    }
    // In first mode keep DFS order; a resumed in-flight job goes where its index says.
    std::stable_sort(jobs.begin(), jobs.end(), [](const Job& a, const Job& b) { return a.index < b.index; });
    assert(std::adjacent_find(jobs.begin(), jobs.end(),
                              [](const Job& a, const Job& b) { return a.index == b.index; }) == jobs.end());
    if (WorkSource* w = cfg_.run.work.get()) {  // the root hands these out to every process
      std::vector<WorkItem> items;
      for (Job& j : jobs) items.push_back({j.index, std::move(j.resume), j.counted, {}});
      jobs.clear();
      w->start(subs_.size(), hash, std::move(items), [this] { return stop_.requested(); });
    }
    jobs_ = std::move(jobs);
    split_nodes_ = split_nodes;
    shard_total_ = out.shard_subproblems;
    trace_search(subs_.size(), split_nodes);
    checkpoint(true);  // the first checkpoint, before any work

    run_workers([this](int tid) { worker_subproblems(tid); });

    {
      std::lock_guard lock(mu_);
      absorb_splits();
    }
    out.counts = finished_counts_;
    out.counts.nodes += split_nodes_;
    for (auto& s : slots_)
      if (s->active && s->record) {
        out.counts.solutions += s->snap.counted.solutions;
        out.counts.orbits += s->snap.counted.orbits;
        out.counts.nodes += s->snap.counted.nodes;
      }
    out.subproblems_done = done_in_shard();
    assert(out.subproblems_done <= out.shard_subproblems);
    if (WorkSource* w = cfg_.run.work.get()) {  // every process's counts, summed on the root
      bool complete = false;
      SearchCounters mine = out.counts;
      if (w->rank() != 0) mine.nodes -= split_nodes_;  // every rank splits; the root's split is counted
      out.counts = w->finish(mine, stop_.requested(), complete);
      if (complete) out.subproblems_done = out.shard_subproblems;  // by all ranks together
      finalize(out, complete);
      return;
    }
    finalize(out, out.subproblems_done == out.shard_subproblems);
  }

  std::string owner() const {
    if (cfg_.run.work) return fmt::format("rank {}", cfg_.run.work->rank());
    return fmt::format("{}/{}", cfg_.run.shard.index, cfg_.run.shard.count);
  }

  void trace_search(std::uint64_t subproblems, std::uint64_t split_nodes) {
    if (!cfg_.run.trace) return;
    cfg_.run.trace->add(fmt::format(
        R"({{"type":"search","title":"{}","mode":"{}","subproblems":{},"threads":{},"owner":"{}","split_nodes":{},"resumed":{}}})",
        json_text(cfg_.title), cfg_.mode == SearchMode::First ? "first" : "count", subproblems, cfg_.run.threads, owner(), split_nodes, cfg_.resume != nullptr));
  }

  // `s` with the characters JSON escapes escaped (titles are ASCII words and spaces).
  static std::string json_text(const std::string& s) {
    std::string o;
    for (char ch : s) {
      if (ch == '"' || ch == '\\') o += '\\';
      if (static_cast<unsigned char>(ch) < 0x20) continue;
      o += ch;
    }
    return o;
  }

  // A split subproblem's jobs (what was left of it, a piece) are lines of type "split" and
  // "piece": the scheduling simulator replays whole subproblems only.
  void trace_subproblem(const Job& job, const SearchCounters& c, double seconds, Control& ctl) {
    std::string path, pieces;
    const char* type = !job.piece.empty() ? "piece" : ctl.gave ? "split" : "subproblem";
    for (const Decision& d : job.piece.empty() ? subs_[job.index] : job.piece)
      path += fmt::format("{}{}={}", path.empty() ? "" : " ", d.var, d.value);
    for (const auto& [n, t] : ctl.pieces) pieces += fmt::format("{}[{},{:.6g}]", pieces.empty() ? "" : ",", n, t);
    cfg_.run.trace->add(fmt::format(
        R"({{"type":"{}","title":"{}","index":{},"path":"{}","owner":"{}","nodes":{},"seconds":{:.6g},"solutions":{},"resumed":{},"pieces":[{}]}})",
        type, json_text(cfg_.title), job.index, path, owner(), c.nodes - job.counted.nodes, seconds,
        c.solutions - job.counted.solutions, !job.resume.empty(), pieces));
  }

  bool mine(std::uint64_t i) const { return cfg_.run.shard.owns(i); }

  std::uint64_t done_in_shard() const {
    std::uint64_t n = 0;
    for (std::uint64_t i = 0; i < finished_.size(); ++i) n += mine(i) && finished_[i];
    return n;
  }

  void worker_subproblems(int tid) {
    Slot& slot = *slots_[std::size_t(tid)];
    SubtreeSearch<M> dfs;
    MergeStats merge{*this, dfs};
    for (;;) {
      Job job;
      if (WorkSource* w = cfg_.run.work.get()) {  // another process may hand it out: ask the source
        WorkItem item;
        if (stop_.requested() || !w->next(item)) return;
        job = {item.index, std::move(item.resume), item.counted, std::move(item.piece)};
      }
      {
        std::lock_guard lock(mu_);
        if (cfg_.run.work && (job.index >= subs_.size() || finished_[job.index]))
          throw InputError(fmt::format("work source handed out subproblem {} twice or out of range", job.index));
        if (!cfg_.run.work) {
          if (next_job_ >= jobs_.size() || stop_.requested()) return;
          job = jobs_[next_job_++];
        }
        std::lock_guard sl(slot.mu);
        slot.active = true;
        slot.record = job.piece.empty();
        slot.snap.index = job.index;
        slot.snap.path = !job.piece.empty() ? job.piece : job.resume.empty() ? subs_[job.index] : job.resume;
        slot.snap.counted = job.counted;
        slot.epoch = epoch_.load();
      }
      Control ctl{*this, slot, job.index, slot.epoch};
      WorkSource* w = cfg_.run.work.get();
      if (w) ctl.split_flag = w->split_flag();
      const std::vector<Decision>& prefix = job.piece.empty() ? subs_[job.index] : job.piece;
      SearchCounters c = job.counted;
      M m = root_;
      const auto t0 = std::chrono::steady_clock::now();
      if (cfg_.run.trace) {
        ctl.piece_depth = prefix.size() + kTracePieceDepth;
        ctl.piece_nodes = c.nodes;
        ctl.piece_start = t0;
      }
      SubtreeOutcome o = dfs.run(m, prefix, job.resume, c, ctl, !job.piece.empty());
      if (o == SubtreeOutcome::Stopped) return;  // the slot keeps the published snapshot
      if (cfg_.run.trace) {
        ctl.cut_piece(c.nodes);
        trace_subproblem(job, c, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), ctl);
      }
      const bool split = !job.piece.empty() || ctl.gave;  // counted by the root once all its jobs are done
      {
        std::lock_guard lock(mu_);
        if (!split) {
          assert(!finished_[job.index] && "a subproblem is finished once");
          finished_[job.index] = true;
          finished_counts_ += c;
          finished_each_[job.index] = c;
        }
        std::lock_guard sl(slot.mu);
        slot.active = false;
        slot.live_nodes.store(0);
      }
      if (w) w->done(job.index, split, c);
    }
  }

  // The root of a run with work stealing: split subproblems whose every piece is done are
  // finished, with the sum of their jobs' counts (mu_ held).
  void absorb_splits() {
    WorkSource* w = cfg_.run.work.get();
    if (!w) return;
    for (const auto& [i, c] : w->completed_splits()) {
      if (i >= finished_.size() || finished_[i]) continue;
      finished_[i] = true;
      finished_counts_ += c;
      finished_each_[i] = c;
    }
  }

  // ---- first mode with restarts ----
  void run_restarts(ParallelOutcome& out) {
    if (const SearchState* r = cfg_.resume) {
      try {
        check_search_state(*r);
      } catch (const InputError& e) {
        throw InputError(fmt::format("checkpoint is inconsistent: {}", e.what()));
      }
      next_restart_ = r->restarts;
      restart_nodes_ = r->restart_nodes;
    }
    checkpoint(true);  // the first checkpoint, before any work
    trace_search(0, 0);
    run_workers([this](int tid) { worker_restarts(tid); });
    out.restarts = next_restart_.load();
    out.counts.nodes = restart_nodes_.load();
    out.counts.solutions = restart_solutions_.load();
    finalize(out, stop_.reason() == StopReason::Exhausted);
  }

  void worker_restarts(int tid) {
    Slot& slot = *slots_[std::size_t(tid)];
    SubtreeSearch<M> dfs;
    MergeStats merge{*this, dfs};
    while (!stop_.requested()) {
      // The k-th dive of this shard is dive r of the whole run: its seed depends on r, its
      // node limit on k (every shard follows the Luby sequence).
      // A checkpoint taken now resumes at the lowest dive in progress (see first_unfinished_dive).
      slot.dive.store(next_restart_.load());
      const std::uint64_t k = next_restart_++;
      if (cfg_.max_dives && k >= cfg_.max_dives) {
        slot.dive.store(kNoDive);
        stop_.request(StopReason::Cancelled);
        break;
      }
      slot.dive.store(k);
      const std::uint64_t r = k * std::uint64_t(cfg_.run.shard.count) + std::uint64_t(cfg_.run.shard.index);
      M m = root_;
      // Seed 0 keeps the natural value order for the first dive (the plain DFS); every other
      // restart, and every restart of a seeded run, shuffles it.
      m.set_value_seed(cfg_.run.seed == 0 && r == 0 ? 0 : mix_seed(cfg_.run.seed * 0x100000001b3ull + r + 1));
      Control ctl{*this, slot, 0, epoch_.load()};
      ctl.node_limit = luby_limit(k + 1, cfg_.restart_base);
      SearchCounters c;
      const auto t0 = std::chrono::steady_clock::now();
      SubtreeOutcome o = dfs.run(m, {}, {}, c, ctl);
      if (cfg_.run.trace)
        cfg_.run.trace->add(fmt::format(
            R"({{"type":"dive","title":"{}","dive":{},"owner":"{}","nodes":{},"seconds":{:.6g},"found":{}}})",
            json_text(cfg_.title), r, owner(), c.nodes,
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), c.solutions > 0));
      // A dive cut short by a stop (time limit, signal, a portfolio slice's end) is not done: a
      // resume runs it again, so the natural-order dive 0 and the long Luby dives are never lost.
      if (!(o == SubtreeOutcome::Stopped && !ctl.hit_limit && stop_.requested())) slot.dive.store(kNoDive);
      restart_nodes_ += c.nodes;
      restart_solutions_ += c.solutions;
      if (o == SubtreeOutcome::Exhausted) stop_.request(StopReason::Exhausted);  // the whole tree, no limit hit
    }
  }

  // The dive a resume starts at: the lowest one in progress or cut short, else the next one.
  std::uint64_t first_unfinished_dive() const {
    std::uint64_t k = next_restart_.load();
    for (const auto& s : slots_) k = std::min(k, s->dive.load());
    return k;
  }

  // ---- shared machinery: threads, monitor, checkpoints, statistics ----
  // A worker's counters join the run's total when it leaves, whichever way it leaves.
  struct MergeStats {
    ParallelSearch& s;
    const SubtreeSearch<M>& dfs;
    ~MergeStats() {
      std::lock_guard lock(s.stats_mu_);
      s.stats_ += dfs.stats();
    }
  };

  // However long the set-up took (the estimate, the split, a resumed state, the first checkpoint),
  // the search itself runs at least this long (or the whole limit, if shorter) before the time
  // limit stops it: a run cut by its limit always got some search done, so the slices of a
  // resumed run, or the units of a split array, always progress.
  static constexpr std::chrono::milliseconds kLeastSearchSlice{20};

  template <class Work>
  void run_workers(Work work) {
    const double search_start = elapsed();
    if (deadline_.limited()) {
      const auto slice = std::min<std::chrono::steady_clock::duration>(
          kLeastSearchSlice, std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                 std::chrono::duration<double>(cfg_.run.time_limit)));
      const auto least = std::chrono::steady_clock::now() + slice;
      if (deadline_.when() < least) deadline_ = Deadline::at(least);
    }
    struct Timed {  // the search phase ends when the workers and the monitor are done
      ParallelSearch& s;
      double start;
      ~Timed() { s.stats_.search_seconds += s.elapsed() - start; }
    } timed{*this, search_start};
    int threads = cfg_.run.threads;
    slots_.clear();
    for (int i = 0; i < threads; ++i) slots_.push_back(std::make_unique<Slot>());
    std::atomic<bool> done{false};
    std::thread monitor([&] { monitor_loop(done); });
    struct JoinMonitor {  // also when a worker's exception leaves parallel_team
      ParallelSearch& s;
      std::atomic<bool>& done;
      std::thread& monitor;
      ~JoinMonitor() {
        {
          std::lock_guard lock(s.monitor_mu_);
          done = true;
        }
        s.monitor_cv_.notify_all();
        monitor.join();
      }
    } join{*this, done, monitor};
    parallel_team(threads, work, &stop_);
    release_idle_threads();  // the caller goes on alone: no idle worker spins meanwhile
  }

  void monitor_loop(std::atomic<bool>& done) {
    ProgressReporter progress(cfg_.title, 0, cfg_.run.progress, 5.0);
    auto last_ckpt = std::chrono::steady_clock::now();
    for (;;) {
      {
        std::unique_lock lock(monitor_mu_);
        // Every 20 ms, or at the deadline if it comes sooner (a limit of a few ms is kept to).
        const auto now = std::chrono::steady_clock::now();
        auto wait = now + std::chrono::milliseconds(20);
        if (deadline_.when() > now && deadline_.when() < wait) wait = deadline_.when();
        monitor_cv_.wait_until(lock, wait, [&] { return done.load(); });
        if (done) break;
      }
      poll_stop();
      auto now = std::chrono::steady_clock::now();
      if (cfg_.save && cfg_.run.checkpoint_every > 0 && !stop_.requested() &&
          std::chrono::duration<double>(now - last_ckpt).count() >= cfg_.run.checkpoint_every) {
        checkpoint(false);
        last_ckpt = std::chrono::steady_clock::now();
      }
      if (cfg_.run.progress) report(progress);
    }
    if (cfg_.run.progress) report(progress);
  }

  // Signals, the time limit (unless `time_limit` is false) and another lane's cancel: requests the
  // stop, and says whether one is requested.
  bool poll_stop(bool time_limit = true) {
    if (cfg_.run.catch_signals && SignalCatcher::caught()) {
      signal_ = SignalCatcher::caught();
      stop_.request(StopReason::Signal);
    }
    if (time_limit && deadline_.expired()) stop_.request(StopReason::TimeLimit);
    if (cfg_.run.cancelled()) stop_.request(StopReason::Cancelled);
    return stop_.requested();
  }

  void report(ProgressReporter& p) {
    std::uint64_t live = 0;
    for (auto& s : slots_) live += s->live_nodes.load(std::memory_order_relaxed);
    double t = elapsed();
    if (cfg_.mode == SearchMode::First && cfg_.restarts) {
      std::uint64_t nodes = restart_nodes_.load() + live;
      p.update(0, 0,
               fmt::format("restart {}, {} nodes, {:.3g} nodes/s", next_restart_.load(), nodes,
                           t > 0 ? double(nodes) / t : 0.0));
      return;
    }
    std::uint64_t done, nodes;
    {
      std::lock_guard lock(mu_);
      done = done_in_shard();
      nodes = finished_counts_.nodes + split_nodes_;
    }
    nodes += live;
    std::string est = estimate_ > 0 ? fmt::format(" of ~{:.3g} (Knuth)", estimate_) : "";
    // Before the first subproblem finishes, the Knuth estimate is the only yardstick.
    bool by_nodes = done == 0 && estimate_ > 0 && cfg_.run.shard.count == 1;
    p.update(by_nodes ? double(nodes) : double(done), by_nodes ? estimate_ : double(shard_total_),
             fmt::format("{}/{} subproblems, {} nodes{}, {:.3g} nodes/s", done, shard_total_, nodes, est,
                         t > 0 ? double(nodes) / t : 0.0));
  }

  // Collects a consistent state: every active worker has published a snapshot for the
  // current epoch (or finished its subproblem), then writes it after flushing the solutions.
  void checkpoint(bool final) {
    if (!cfg_.save) return;
    if (!final) {
      std::uint64_t e = ++epoch_;
      auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
      for (;;) {
        bool all = true;
        for (auto& s : slots_) {
          std::lock_guard sl(s->mu);
          if (s->active && s->epoch != e) all = false;
        }
        if (all || stop_.requested()) break;
        if (std::chrono::steady_clock::now() > deadline) return;  // try again next period
        std::this_thread::sleep_for(std::chrono::microseconds(200));
      }
      if (stop_.requested()) return;  // the final checkpoint follows
    }
    SearchState st;
    st.fingerprint = cfg_.fingerprint;
    {
      std::lock_guard lock(mu_);
      st.subproblem_count = subs_.size();
      st.subproblem_hash = subs_.empty() ? 0 : hash_subproblems(subs_);
      absorb_splits();
      st.finished = finished_;
      st.finished_counts = finished_counts_;
      for (std::size_t i = 0; i < finished_.size(); ++i)
        if (finished_[i]) st.finished_each.push_back(finished_each_[i]);
      for (auto& s : slots_) {
        std::lock_guard sl(s->mu);
        if (s->active && s->record) st.in_flight.push_back(s->snap);
      }
      // Resumed subproblems not yet picked up by a worker keep their paths.
      for (std::size_t j = next_job_; j < jobs_.size(); ++j)
        if (!jobs_[j].resume.empty()) st.in_flight.push_back({jobs_[j].index, jobs_[j].resume, jobs_[j].counted});
      if (cfg_.run.work) {
        for (WorkItem& w : cfg_.run.work->queued_resumed())
          if (!finished_[w.index]) st.in_flight.push_back({w.index, std::move(w.resume), w.counted});
        std::sort(st.in_flight.begin(), st.in_flight.end(),
                  [](const InFlightSubproblem& a, const InFlightSubproblem& b) { return a.index < b.index; });
      }
    }
    st.restarts = first_unfinished_dive();
    st.restart_nodes = restart_nodes_.load();
    st.seconds = prior_seconds_ + elapsed();
    const double write_start = elapsed();
    if (cfg_.flush) cfg_.flush();
    cfg_.save(st);
    if (cfg_.run.trace) cfg_.run.trace->write();
    ++checkpoints_;
    std::lock_guard lock(stats_mu_);  // workers may be merging their counters meanwhile
    stats_.checkpoint_seconds += elapsed() - write_start;
  }

  void finalize(ParallelOutcome& out, bool exhausted) {
    const StopReason why = stop_.reason();
    out.interrupted = why == StopReason::Signal;
    out.timed_out = why == StopReason::TimeLimit;
    out.complete = exhausted && (why == StopReason::None || why == StopReason::Exhausted);
    if (cfg_.mode == SearchMode::First && cfg_.restarts) out.complete = why == StopReason::Exhausted;
    if (cfg_.save) checkpoint(true);
    else if (cfg_.run.trace) cfg_.run.trace->write();
  }

  M root_;
  ParallelConfig cfg_;
  Leaf leaf_;
  std::chrono::steady_clock::time_point start_;
  Deadline deadline_;  // run.time_limit from start_ (base/run_control.hpp)
  double prior_seconds_ = 0, estimate_ = 0;
  StopToken stop_;
  std::atomic<bool> found_{false};
  std::atomic<std::uint64_t> epoch_{0};
  int signal_ = 0;
  std::size_t checkpoints_ = 0;
  std::mutex stats_mu_;  // guards stats_ while workers merge into it
  SearchStats stats_;

  std::mutex mu_;  // guards jobs_, next_job_, finished_, finished_counts_ (taken before a slot's mutex)
  std::vector<std::vector<Decision>> subs_;
  std::vector<Job> jobs_;
  std::size_t next_job_ = 0;
  std::vector<bool> finished_;
  SearchCounters finished_counts_;
  std::vector<SearchCounters> finished_each_;  // per subproblem, what it counted once finished
  std::uint64_t split_nodes_ = 0, shard_total_ = 0;
  std::vector<std::unique_ptr<Slot>> slots_;

  std::atomic<std::uint64_t> next_restart_{0}, restart_nodes_{0}, restart_solutions_{0};

  std::mutex monitor_mu_;
  std::condition_variable monitor_cv_;
};

}  // namespace tilekit
