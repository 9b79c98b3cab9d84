// Work stealing at the engine level (solver/dfs.hpp, split_wanted/give): a search that gives away
// the untried alternatives of its oldest open level, plus every child it gave searched on its own
// (and the children those gave), counts the whole tree exactly; and a snapshot of a search that
// gave work away, resumed as the whole subproblem, counts it exactly too (what a checkpoint keeps
// of a split subproblem, solver/work_source.hpp).
#include <gtest/gtest.h>

#include <cstdint>
#include <deque>
#include <vector>

#include "solver/cell_model.hpp"
#include "solver/dfs.hpp"
#include "solver/search_state.hpp"
#include "solver/problem.hpp"

using namespace tilekit;

namespace {

// Asks for a split every `every` nodes (0: never) and stops at node `stop_at` (0: never).
struct SplitControl {
  std::uint64_t every = 0, stop_at = 0, seen = 0, gave = 0;
  std::deque<std::vector<Decision>>* given = nullptr;
  std::vector<Decision> stopped_path;
  SearchCounters stopped_counted;
  bool at_node(const std::vector<Decision>& path, const SearchCounters& c) {
    ++seen;
    if (stop_at && seen == stop_at) {
      stopped_path = path, stopped_counted = c;
      return false;
    }
    return true;
  }
  bool split_wanted() const { return every && seen % every == 0; }
  bool give(std::vector<std::vector<Decision>> children) {
    for (auto& c : children) given->push_back(std::move(c));
    ++gave;
    return true;
  }
  void leaf(const CellModel& m, SearchCounters& c) { c.solutions += m.multiplicity(); }
};

CellModel wang2() {
  return CellModel(complete_packing_problem(TileKind::Wang, 2), true, CellModel::Ordering::Static);
}

SearchCounters whole_tree() {
  std::deque<std::vector<Decision>> none;
  SplitControl ctl;
  ctl.given = &none;
  CellModel m = wang2();
  SearchCounters c;
  SubtreeSearch<CellModel> dfs;
  EXPECT_EQ(dfs.run(m, {}, {}, c, ctl), SubtreeOutcome::Exhausted);
  return c;
}

}  // namespace

TEST(WorkSplit, PiecesGivenAwayAndTheRestCountTheWholeTreeOnce) {
  const SearchCounters whole = whole_tree();
  ASSERT_GT(whole.solutions, 0u);
  for (std::uint64_t every : {97u, 1013u, 20011u}) {
    std::deque<std::vector<Decision>> jobs = {{}};  // the root, then every piece given away
    SearchCounters sum;
    std::uint64_t gave = 0, runs = 0;
    SubtreeSearch<CellModel> dfs;
    while (!jobs.empty()) {
      const std::vector<Decision> prefix = std::move(jobs.front());
      jobs.pop_front();
      SplitControl ctl;
      ctl.every = every;
      ctl.given = &jobs;
      CellModel m = wang2();
      SearchCounters c;
      EXPECT_EQ(dfs.run(m, prefix, {}, c, ctl, !prefix.empty()), SubtreeOutcome::Exhausted);
      sum += c;
      gave += ctl.gave;
      ++runs;
    }
    EXPECT_EQ(sum, whole) << "split every " << every << " nodes";
    EXPECT_GT(gave, 0u);
    EXPECT_GT(runs, gave);
  }
}

TEST(WorkSplit, ASnapshotTakenAfterGivingWorkAwayResumesTheWholeSubproblem) {
  const SearchCounters whole = whole_tree();
  // How many nodes the search itself visits when it gives work away every 211 nodes.
  std::uint64_t visited = 0;
  {
    std::deque<std::vector<Decision>> given;
    SplitControl ctl;
    ctl.every = 211;
    ctl.given = &given;
    CellModel m = wang2();
    SearchCounters c;
    SubtreeSearch<CellModel> dfs;
    ASSERT_EQ(dfs.run(m, {}, {}, c, ctl), SubtreeOutcome::Exhausted);
    visited = ctl.seen;
  }
  ASSERT_GT(visited, 1000u);
  for (std::uint64_t stop_at : {visited / 4, visited / 2, visited - 10}) {
    std::deque<std::vector<Decision>> given;
    SplitControl ctl;
    ctl.every = 211;
    ctl.stop_at = stop_at;
    ctl.given = &given;
    CellModel m = wang2();
    SearchCounters c;
    SubtreeSearch<CellModel> dfs;
    ASSERT_EQ(dfs.run(m, {}, {}, c, ctl), SubtreeOutcome::Stopped);
    ASSERT_GT(ctl.gave, 0u);
    // The pieces given away are dropped: the snapshot, resumed with no split, explores them again.
    std::deque<std::vector<Decision>> none;
    SplitControl rest;
    rest.given = &none;
    CellModel m2 = wang2();
    SearchCounters r = ctl.stopped_counted;
    SubtreeSearch<CellModel> again;
    EXPECT_EQ(again.run(m2, {}, ctl.stopped_path, r, rest), SubtreeOutcome::Exhausted);
    EXPECT_EQ(r, whole) << "stopped at node " << stop_at << " of " << visited;
  }
}
