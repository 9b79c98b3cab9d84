#pragma once
// Splitting a model's search tree into subproblems (decision prefixes) and fingerprinting the
// list. The list is a deterministic function of the model and the target, which is what makes
// shards (subproblem i belongs to shard i mod N) and checkpoints (a subproblem is its index)
// meaningful across runs and machines. Used by ParallelSearch (parallel_search.hpp).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "base/hash.hpp"
#include "solver/model.hpp"
#include "solver/search_state.hpp"

namespace tilekit {

// A subproblem list is a deterministic function of the model and the target. It always runs to
// the end (at most kMaxSplitSubproblems entries), so that a stopped run still has a list to
// checkpoint.
template <SearchModel M>
std::vector<std::vector<Decision>> split_subproblems(const M& root, std::size_t target, std::uint64_t& nodes) {
  std::vector<std::vector<Decision>> level{{}};
  std::vector<int> values;
  for (;;) {
    std::vector<std::vector<Decision>> next;
    bool expanded = false;
    for (std::size_t i = 0; i < level.size(); ++i) {
      if (next.size() + (level.size() - i) >= target) {  // enough: keep the rest unexpanded
        next.insert(next.end(), level.begin() + std::ptrdiff_t(i), level.end());
        break;
      }
      M m = root;
      for (const Decision& d : level[i]) m.assign(d.var, d.value);
      int var = m.branch(values);
      if (var < 0) {
        next.push_back(level[i]);
        continue;
      }
      expanded = true;
      ++nodes;
      for (int v : values) {
        if (m.assign(var, v)) {
          next.push_back(level[i]);
          next.back().push_back({var, v});
        }
        m.unassign(var, v);
      }
    }
    level = std::move(next);
    if (!expanded || level.size() >= target || level.empty()) return level;
  }
}

inline std::uint64_t hash_subproblems(const std::vector<std::vector<Decision>>& subs) {
  StableHash h;
  for (const auto& s : subs) {
    h.add(s.size());
    for (const Decision& d : s) h.add(std::uint64_t(std::uint32_t(d.var)) << 32 | std::uint32_t(d.value));
  }
  return h.fnv();
}

}  // namespace tilekit
