#include "solver/search_state.hpp"

#include <algorithm>

#include <fmt/format.h>

#include <cmath>
#include <unordered_set>

#include "base/error.hpp"
#include "base/run_control.hpp"

namespace tilekit {

namespace {

void check_counters(const SearchCounters& c, const std::string& what) {
  if (c.orbits > c.solutions)
    throw InputError(fmt::format("{} counts {} orbits but only {} solutions", what, c.orbits, c.solutions));
}

}  // namespace

void check_search_state(const SearchState& st, std::uint64_t subproblems, int shard_index, int shard_count) {
  if (st.subproblem_count > kMaxSubproblems)
    throw InputError(fmt::format("{} subproblems is more than the limit of {}", st.subproblem_count, kMaxSubproblems));
  if (subproblems > 0 && st.subproblem_count != subproblems)
    throw InputError(fmt::format("it has {} subproblems but this search has {} (different problem or options)",
                                 st.subproblem_count, subproblems));
  if (st.finished.size() != st.subproblem_count)
    throw InputError(fmt::format("the finished bitmap has {} entries for {} subproblems", st.finished.size(),
                                 st.subproblem_count));
  check_counters(st.finished_counts, "the finished subproblems' total");
  std::uint64_t finished = 0;
  for (std::uint64_t i = 0; i < st.subproblem_count; ++i) {
    if (!st.finished[i]) continue;
    ++finished;
    if (subproblems > 0 && shard_count > 0 && !ShardSpec{shard_index, shard_count}.owns(i))
      throw InputError(fmt::format("finished subproblem {} is not in shard {}/{}", i, shard_index, shard_count));
  }
  if (st.finished_each.size() != finished)
    throw InputError(fmt::format("it holds the counts of {} finished subproblems but {} are marked finished",
                                 st.finished_each.size(), finished));
  SearchCounters sum;
  for (const SearchCounters& c : st.finished_each) {
    check_counters(c, "a finished subproblem");
    // Sums beyond 2^64 would wrap around to a total that matches anything.
    if (__builtin_add_overflow(sum.solutions, c.solutions, &sum.solutions) ||
        __builtin_add_overflow(sum.orbits, c.orbits, &sum.orbits) ||
        __builtin_add_overflow(sum.nodes, c.nodes, &sum.nodes))
      throw InputError("the finished subproblems' counts overflow 64 bits");
  }
  if (sum != st.finished_counts)
    throw InputError(fmt::format("the finished subproblems count {} solutions and {} nodes, but their total says {} "
                                 "and {}",
                                 sum.solutions, sum.nodes, st.finished_counts.solutions, st.finished_counts.nodes));
  std::unordered_set<std::uint64_t> seen;
  for (const InFlightSubproblem& f : st.in_flight) {
    if (f.index >= st.subproblem_count)
      throw InputError(fmt::format("in-flight subproblem {} is out of range (there are {})", f.index,
                                   st.subproblem_count));
    if (st.finished[f.index]) throw InputError(fmt::format("in-flight subproblem {} is also finished", f.index));
    if (!seen.insert(f.index).second) throw InputError(fmt::format("in-flight subproblem {} is listed twice", f.index));
    if (subproblems > 0 && shard_count > 0 && !ShardSpec{shard_index, shard_count}.owns(f.index))
      throw InputError(fmt::format("in-flight subproblem {} is not in shard {}/{}", f.index, shard_index, shard_count));
    if (f.path.size() > kMaxDecisionPath)
      throw InputError(fmt::format("in-flight subproblem {} has a path of {} decisions", f.index, f.path.size()));
    for (const Decision& d : f.path)
      if (d.var < 0 || d.value < 0)
        throw InputError(fmt::format("in-flight subproblem {} has a negative decision ({}, {})", f.index, d.var,
                                     d.value));
    check_counters(f.counted, fmt::format("in-flight subproblem {}", f.index));
  }
  if (st.restarts > kMaxRestarts)
    throw InputError(fmt::format("{} restarts is more than the limit of {}", st.restarts, kMaxRestarts));
  if (!std::isfinite(st.seconds) || st.seconds < 0)
    throw InputError(fmt::format("its time so far ({} s) is not a non-negative number", st.seconds));
}

std::uint64_t counted_nodes(const SearchState& state) {
  std::uint64_t n = state.restart_nodes + state.finished_counts.nodes;
  for (const InFlightSubproblem& f : state.in_flight) n += f.counted.nodes;
  return n;
}

void merge_search_states(SearchState& into, const SearchState& from) {
  if (from.fingerprint != into.fingerprint || from.subproblem_count != into.subproblem_count ||
      from.subproblem_hash != into.subproblem_hash || from.finished.size() != into.finished.size())
    throw InputError("the checkpoints to merge belong to different searches");
  std::vector<SearchCounters> each(into.finished.size());
  auto spread = [&](const SearchState& st) {
    for (std::size_t i = 0, k = 0; i < st.finished.size(); ++i)
      if (st.finished[i]) each[i] = st.finished_each.at(k++);
  };
  spread(from);
  spread(into);  // into's own counts win (they are equal for a deterministic search)
  std::vector<bool> finished(into.finished.size());
  for (std::size_t i = 0; i < finished.size(); ++i) finished[i] = into.finished[i] || from.finished[i];
  std::vector<InFlightSubproblem> flight;
  const std::vector<InFlightSubproblem>* lists[] = {&into.in_flight, &from.in_flight};
  for (const std::vector<InFlightSubproblem>* list : lists)
    for (const InFlightSubproblem& f : *list) {
      if (f.index >= finished.size() || finished[f.index]) continue;
      auto same = std::find_if(flight.begin(), flight.end(), [&](const InFlightSubproblem& g) { return g.index == f.index; });
      if (same == flight.end())
        flight.push_back(f);
      else if (f.counted.nodes > same->counted.nodes)
        *same = f;
    }
  std::sort(flight.begin(), flight.end(),
            [](const InFlightSubproblem& a, const InFlightSubproblem& b) { return a.index < b.index; });
  into.finished = std::move(finished);
  into.finished_each.clear();
  into.finished_counts = {};
  for (std::size_t i = 0; i < into.finished.size(); ++i)
    if (into.finished[i]) {
      into.finished_each.push_back(each[i]);
      into.finished_counts += each[i];
    }
  into.in_flight = std::move(flight);
  into.seconds = std::max(into.seconds, from.seconds);
}

}  // namespace tilekit
