#include "cluster/mpi_work.hpp"

#include "base/error.hpp"

#ifndef TILEKIT_HAVE_MPI

namespace tilekit::cluster {

bool mpi_built() { return false; }

std::shared_ptr<WorkSource> start_mpi_work() {
  throw InputError("this tilekit was built without MPI (install Open MPI, libopenmpi-dev, and build again)");
}

}  // namespace tilekit::cluster

#else

#include <fmt/format.h>
#include <mpi.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <mutex>
#include <thread>
#include <vector>

namespace tilekit::cluster {

bool mpi_built() { return true; }

namespace {

enum Tag : int { kRequest = 1, kJob = 2, kDone = 3, kBye = 4 };

// Serialises every MPI call of the process (MPI_THREAD_SERIALIZED).
std::mutex& mpi_mutex() {
  static std::mutex mu;
  return mu;
}

void pause() { std::this_thread::sleep_for(std::chrono::microseconds(200)); }

// Waits for `req` without MPI's busy wait: test, sleep, test.
void wait_for(MPI_Request& req) {
  for (;;) {
    int done = 0;
    {
      std::lock_guard lock(mpi_mutex());
      MPI_Test(&req, &done, MPI_STATUS_IGNORE);
    }
    if (done) return;
    pause();
  }
}

// A job as integers: [has, index, solutions, orbits, nodes, path length, var, value, ...].
std::vector<std::int64_t> encode(const WorkItem* job) {
  if (!job) return {0};
  std::vector<std::int64_t> v = {1,
                                 std::int64_t(job->index),
                                 std::int64_t(job->counted.solutions),
                                 std::int64_t(job->counted.orbits),
                                 std::int64_t(job->counted.nodes),
                                 std::int64_t(job->resume.size())};
  for (const Decision& d : job->resume) {
    v.push_back(d.var);
    v.push_back(d.value);
  }
  return v;
}

bool decode(const std::vector<std::int64_t>& v, WorkItem& job) {
  if (v.empty() || v[0] == 0) return false;
  if (v.size() < 6 || v.size() != 6 + 2 * std::size_t(v[5])) throw InputError("MPI: a malformed job message");
  job.index = std::uint64_t(v[1]);
  job.counted = {std::uint64_t(v[2]), std::uint64_t(v[3]), std::uint64_t(v[4])};
  job.resume.clear();
  for (std::size_t i = 6; i < v.size(); i += 2) job.resume.push_back({int(v[i]), int(v[i + 1])});
  return true;
}

class MpiWork final : public WorkSource {
 public:
  MpiWork() {
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (!initialised) {
      int provided = 0;
      MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided);
      if (provided < MPI_THREAD_SERIALIZED) throw InputError("MPI: this MPI library cannot serve several threads");
      owns_mpi_ = true;
    }
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks_);
    finished_ = ranks_ == 1;  // until finish(): an error before it aborts the job
  }
  ~MpiWork() override {
    // Left without finish() (an error on this rank): the others would wait for it forever.
    if (!finished_ && ranks_ > 1) MPI_Abort(MPI_COMM_WORLD, 2);
    if (owns_mpi_) MPI_Finalize();
  }

  int rank() const override { return rank_; }
  int ranks() const override { return ranks_; }

  void start(std::uint64_t subproblems, std::uint64_t hash, std::vector<WorkItem> jobs) override {
    std::uint64_t mine[2] = {subproblems, hash}, roots[2] = {subproblems, hash};
    {
      MPI_Request req;
      {
        std::lock_guard lock(mpi_mutex());
        MPI_Ibcast(roots, 2, MPI_UINT64_T, 0, MPI_COMM_WORLD, &req);
      }
      wait_for(req);
    }
    if (roots[0] != mine[0] || roots[1] != mine[1])
      throw InputError(fmt::format("MPI rank {}: its subproblem list ({} subproblems) differs from the root's ({})",
                                   rank_, mine[0], roots[0]));
    if (rank_ != 0) return;
    {
      std::lock_guard lock(queue_mu_);
      queue_.assign(std::make_move_iterator(jobs.begin()), std::make_move_iterator(jobs.end()));
    }
    remote_done_ = 0;
    totals_ = {};
    any_stopped_ = false;
    if (ranks_ > 1) dispatcher_ = std::thread([this] { dispatch(); });
  }

  bool next(WorkItem& job) override {
    if (rank_ == 0) return pop(job);
    std::vector<std::int64_t> reply(1);
    std::lock_guard serial(ask_mu_);  // one request of this rank at a time: replies come in order
    {
      std::int64_t zero = 0;
      MPI_Request req;
      {
        std::lock_guard lock(mpi_mutex());
        MPI_Isend(&zero, 1, MPI_INT64_T, 0, kRequest, MPI_COMM_WORLD, &req);
      }
      wait_for(req);
    }
    for (;;) {  // the reply's length is known once it arrives
      int flag = 0;
      MPI_Status st;
      {
        std::lock_guard lock(mpi_mutex());
        MPI_Iprobe(0, kJob, MPI_COMM_WORLD, &flag, &st);
        if (flag) {
          int n = 0;
          MPI_Get_count(&st, MPI_INT64_T, &n);
          reply.assign(std::size_t(n), 0);
          MPI_Recv(reply.data(), n, MPI_INT64_T, 0, kJob, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
          break;
        }
      }
      pause();
    }
    return decode(reply, job);
  }

  std::vector<WorkItem> queued_resumed() override {
    std::vector<WorkItem> out;
    std::lock_guard lock(queue_mu_);
    for (const WorkItem& j : queue_)
      if (!j.resume.empty()) out.push_back(j);
    return out;
  }

  SearchCounters finish(const SearchCounters& mine, bool stopped, bool& complete) override {
    finished_ = true;
    if (rank_ != 0) {
      std::int64_t msg[4] = {stopped ? 1 : 0, std::int64_t(mine.solutions), std::int64_t(mine.orbits),
                             std::int64_t(mine.nodes)};
      MPI_Request req;
      {
        std::lock_guard lock(mpi_mutex());
        MPI_Isend(msg, 4, MPI_INT64_T, 0, kDone, MPI_COMM_WORLD, &req);
      }
      wait_for(req);
      std::int64_t bye = 0;
      {
        std::lock_guard lock(mpi_mutex());
        MPI_Irecv(&bye, 1, MPI_INT64_T, 0, kBye, MPI_COMM_WORLD, &req);
      }
      wait_for(req);
      complete = !stopped && bye == 1;
      return mine;
    }
    if (stopped) closed_ = true;  // hand out nothing more
    stop_dispatcher();            // waits for every other rank's counters
    bool drained;
    {
      std::lock_guard lock(queue_mu_);
      drained = queue_.empty();
    }
    complete = !stopped && !any_stopped_ && drained;
    for (int r = 1; r < ranks_; ++r) {
      std::int64_t bye = complete ? 1 : 0;
      MPI_Request req;
      {
        std::lock_guard lock(mpi_mutex());
        MPI_Isend(&bye, 1, MPI_INT64_T, r, kBye, MPI_COMM_WORLD, &req);
      }
      wait_for(req);
    }
    SearchCounters sum = mine;
    sum += totals_;
    return sum;
  }

 private:
  bool pop(WorkItem& job) {
    std::lock_guard lock(queue_mu_);
    if (queue_.empty() || closed_) return false;
    job = std::move(queue_.front());
    queue_.pop_front();
    return true;
  }

  // The root's dispatcher thread: answers requests and collects the other ranks' counters.
  void dispatch() {
    while (remote_done_ < ranks_ - 1) {
      int flag = 0;
      MPI_Status st;
      {
        std::lock_guard lock(mpi_mutex());
        MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
        if (flag && st.MPI_TAG == kRequest) {
          std::int64_t zero = 0;
          MPI_Recv(&zero, 1, MPI_INT64_T, st.MPI_SOURCE, kRequest, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        } else if (flag && st.MPI_TAG == kDone) {
          std::int64_t msg[4];
          MPI_Recv(msg, 4, MPI_INT64_T, st.MPI_SOURCE, kDone, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
          if (msg[0]) any_stopped_ = true;
          totals_ += SearchCounters{std::uint64_t(msg[1]), std::uint64_t(msg[2]), std::uint64_t(msg[3])};
          ++remote_done_;
          continue;
        } else if (flag) {  // not a message of this protocol: dropped
          int n = 0;
          MPI_Get_count(&st, MPI_BYTE, &n);
          std::vector<char> junk(std::size_t(std::max(n, 1)));
          MPI_Recv(junk.data(), n, MPI_BYTE, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
          continue;
        }
      }
      if (!flag) {
        pause();
        continue;
      }
      WorkItem job;
      const bool has = pop(job);
      std::vector<std::int64_t> reply = encode(has ? &job : nullptr);
      MPI_Request req;
      {
        std::lock_guard lock(mpi_mutex());
        MPI_Isend(reply.data(), int(reply.size()), MPI_INT64_T, st.MPI_SOURCE, kJob, MPI_COMM_WORLD, &req);
      }
      wait_for(req);
    }
  }

  void stop_dispatcher() {
    if (dispatcher_.joinable()) dispatcher_.join();
  }

  int rank_ = 0, ranks_ = 1;
  bool owns_mpi_ = false, finished_ = true;
  std::mutex ask_mu_;
  std::mutex queue_mu_;
  std::deque<WorkItem> queue_;
  std::atomic<bool> closed_{false}, any_stopped_{false};
  int remote_done_ = 0;
  SearchCounters totals_;
  std::thread dispatcher_;
};

}  // namespace

std::shared_ptr<WorkSource> start_mpi_work() { return std::make_shared<MpiWork>(); }

}  // namespace tilekit::cluster

#endif
