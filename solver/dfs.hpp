#pragma once
// Depth-first search of one subtree (one subproblem), iterative so that the decision path of
// the current node is always at hand: that path is what a checkpoint stores, and what
// `resume` replays to continue exactly where a stopped search left off.
//
// Control hooks (inlined; see ParallelSearch for the real ones):
//   bool at_node(const std::vector<Decision>& path, const SearchCounters& counted)
//        called on entering every node, before it is counted; false stops the search (the
//        node at `path` is then the first one not yet explored)
//   void leaf(const M& model, SearchCounters& counted)   at every solution
//   optional, for work stealing (cluster/mpi_work.hpp): bool split_wanted() and
//   bool give(std::vector<std::vector<Decision>> children): when split_wanted() says so on
//        entering a node, the search offers the untried alternatives of its shallowest open
//        level (the oldest open subtree), one child prefix each; when give() takes them the
//        search skips them (another worker explores each as a subtree of its own)
//
// Statistics (solver/search_stats.hpp): the search counts nodes, decisions, conflicts,
// backtracks, leaves and empty domains in stats(), and adds the model's own counters
// (propagations, prunes per rule) after each subtree. Plain integers: one SubtreeSearch per worker.
#include <algorithm>
#include <cassert>
#include <concepts>
#include <cstddef>
#include <vector>

#include "base/error.hpp"
#include "solver/model.hpp"
#include "solver/search_state.hpp"
#include "solver/search_stats.hpp"

namespace tilekit {

enum class SubtreeOutcome { Exhausted, Stopped };

template <SearchModel M>
class SubtreeSearch {
 public:
  // Explores the subtree below `prefix` (decisions replayed from the root of `m`), starting at
  // `resume` when that is longer than the prefix (a path recorded by at_node in an earlier
  // run). `counted` accumulates. Throws InputError when `resume` does not replay (a checkpoint
  // from a different search). With `last_may_fail` (a child given away by give()) a prefix whose
  // last decision fails is an empty subtree, as it is in the search that gave it away.
  template <class Control>
  SubtreeOutcome run(M& m, const std::vector<Decision>& prefix, const std::vector<Decision>& resume,
                     SearchCounters& counted, Control& ctl, bool last_may_fail = false) {
    if constexpr (kModelStats) m.stats() = {};
    const SubtreeOutcome o = explore(m, prefix, resume, counted, ctl, last_may_fail);
    if constexpr (kModelStats) stats_.model += m.stats();
    return o;
  }

  // What this search counted over every subtree it ran (the caller merges workers).
  const SearchStats& stats() const { return stats_; }

 private:
  // A model may count its propagations and prunes (a `ModelStats& stats()` member).
  static constexpr bool kModelStats = requires(M & m) {
    { m.stats() } -> std::same_as<ModelStats&>;
  };

  template <class Control>
  SubtreeOutcome explore(M& m, const std::vector<Decision>& prefix, const std::vector<Decision>& resume,
                         SearchCounters& counted, Control& ctl, bool last_may_fail) {
    path_.clear();
    for (std::size_t i = 0; i < prefix.size(); ++i) {
      path_.push_back(prefix[i]);
      if (m.assign(prefix[i].var, prefix[i].value)) continue;
      if (last_may_fail && i + 1 == prefix.size() && resume.empty()) {
        ++stats_.decisions, ++stats_.conflicts;
        return SubtreeOutcome::Exhausted;
      }
      throw InputError("subproblem prefix does not replay");
    }
    if (!resume.empty() && (resume.size() < prefix.size() || !std::equal(prefix.begin(), prefix.end(), resume.begin())))
      throw InputError("checkpoint path does not start with its subproblem's prefix");
    std::size_t d = 0;  // depth of the current node below the prefix
    for (std::size_t i = prefix.size(); i < resume.size(); ++i, ++d) {
      ensure(d);
      int var = m.branch(values_[d]);
      const auto& vals = values_[d];
      std::size_t j = 0;
      while (j < vals.size() && vals[j] != resume[i].value) ++j;
      if (var != resume[i].var || j == vals.size())
        throw InputError("checkpoint path does not replay in this search (different problem or options)");
      frames_[d] = {var, j + 1};
      path_.push_back(resume[i]);
      if (!m.assign(var, resume[i].value))
        throw InputError("checkpoint path does not replay in this search (different problem or options)");
    }
    bool entering = true;
    for (;;) {
      assert(path_.size() == prefix.size() + d && "the path holds one decision per level below the prefix");
      if (entering) {
        if (!ctl.at_node(path_, counted)) return SubtreeOutcome::Stopped;
        if constexpr (requires { ctl.split_wanted(); }) {
          if (ctl.split_wanted()) give_away(prefix.size(), d, ctl);
        }
        ++counted.nodes;
        ++stats_.nodes;
        ensure(d);
        int var = m.branch(values_[d]);
        if (var < 0) {
          ++stats_.leaves;
          ctl.leaf(m, counted);
          if (d == 0) return SubtreeOutcome::Exhausted;
          --d;
          ++stats_.backtracks;
          Decision x = path_.back();
          path_.pop_back();
          m.unassign(x.var, x.value);
        } else {
          frames_[d] = {var, 0};
          if (values_[d].empty()) stats_.model.prune(Prune::EmptyDomain);
        }
      }
      Frame& f = frames_[d];
      const std::vector<int>& vals = values_[d];
      entering = false;
      while (f.next < vals.size()) {
        int v = vals[f.next++];
        path_.push_back({f.var, v});
        ++stats_.decisions;
        if (m.assign(f.var, v)) {
          entering = true;
          break;
        }
        ++stats_.conflicts;
        m.unassign(f.var, v);
        path_.pop_back();
      }
      if (entering) {
        ++d;
        continue;
      }
      if (d == 0) return SubtreeOutcome::Exhausted;
      --d;
      ++stats_.backtracks;
      Decision x = path_.back();
      path_.pop_back();
      m.unassign(x.var, x.value);
    }
  }

  // The untried alternatives of the shallowest level above depth `d` that has any, offered to
  // ctl.give() as child prefixes; skipped here once taken. Every level above it has none, so the
  // rest of this search is the subtree of the alternative being explored at that level.
  template <class Control>
  void give_away(std::size_t prefix_size, std::size_t d, Control& ctl) {
    for (std::size_t l = 0; l < d; ++l) {
      Frame& f = frames_[l];
      const std::vector<int>& vals = values_[l];
      if (f.next >= vals.size()) continue;
      std::vector<std::vector<Decision>> children;
      for (std::size_t k = f.next; k < vals.size(); ++k) {
        std::vector<Decision> c(path_.begin(), path_.begin() + std::ptrdiff_t(prefix_size + l));
        c.push_back({f.var, vals[k]});
        children.push_back(std::move(c));
      }
      if (ctl.give(std::move(children))) f.next = vals.size();
      return;
    }
  }

  struct Frame {
    int var = 0;
    std::size_t next = 0;
  };
  void ensure(std::size_t d) {
    if (values_.size() <= d) {
      values_.resize(d + 1);
      frames_.resize(d + 1);
    }
  }
  std::vector<std::vector<int>> values_;
  std::vector<Frame> frames_;
  std::vector<Decision> path_;
  SearchStats stats_;
};

}  // namespace tilekit
