#include "cluster/part_work.hpp"

#include <deque>
#include <functional>
#include <mutex>
#include <utility>

namespace tilekit::cluster {
namespace {

class PartWork final : public WorkSource {
 public:
  PartWork(const ShardSpec& shard, const ShardPart& part) : shard_(shard), part_(part) {}
  int rank() const override { return 0; }
  int ranks() const override { return 1; }
  void start(std::uint64_t, std::uint64_t, std::vector<WorkItem> jobs, std::function<bool()>) override {
    std::lock_guard lock(mu_);
    queue_.clear();
    for (WorkItem& j : jobs)
      if (part_.owns(j.index, shard_)) queue_.push_back(std::move(j));
  }
  bool next(WorkItem& job) override {
    std::lock_guard lock(mu_);
    if (queue_.empty()) return false;
    job = std::move(queue_.front());
    queue_.pop_front();
    return true;
  }
  // One process: no work is given away, so every job is finished where it ran.
  void done(std::uint64_t, bool, const SearchCounters&) override {}
  std::atomic<bool>* split_flag() override { return nullptr; }
  void give(std::uint64_t, std::vector<std::vector<Decision>>) override {}
  std::vector<std::pair<std::uint64_t, SearchCounters>> completed_splits() override { return {}; }
  WorkStats stats() override { return {}; }
  std::vector<WorkItem> queued_resumed() override {
    std::lock_guard lock(mu_);
    std::vector<WorkItem> out;
    for (const WorkItem& j : queue_)
      if (!j.resume.empty()) out.push_back(j);
    return out;
  }
  SearchCounters finish(const SearchCounters& mine, bool stopped, bool& complete) override {
    std::lock_guard lock(mu_);
    complete = !stopped && queue_.empty();
    return mine;
  }

 private:
  ShardSpec shard_;
  ShardPart part_;
  std::mutex mu_;
  std::deque<WorkItem> queue_;
};

}  // namespace

std::shared_ptr<WorkSource> part_work(const ShardSpec& shard, const ShardPart& part) {
  return std::make_shared<PartWork>(shard, part);
}

}  // namespace tilekit::cluster
