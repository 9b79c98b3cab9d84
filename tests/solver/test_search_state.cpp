// Structural validation of resumable search states: a checkpoint with a valid
// checksum but an impossible state (an in-flight subproblem listed twice resumed to 203,904
// solutions instead of 203,520) is refused, whether it comes from a file or from memory.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "base/error.hpp"
#include "solver/luby.hpp"
#include "solver/search_state.hpp"
#include "solver/solve.hpp"
#include "tilesets/tile_set.hpp"

using namespace tilekit;

namespace {

// A consistent state: 8 subproblems, 0 and 1 finished, 2 and 5 in flight.
SearchState good_state() {
  SearchState st;
  st.fingerprint = "{}";
  st.subproblem_count = 8;
  st.finished = {true, true, false, false, false, false, false, false};
  st.finished_counts = {96, 3, 1000};
  st.in_flight = {{2, {{0, 1}, {3, 2}}, {16, 1, 40}}, {5, {{0, 4}}, {0, 0, 7}}};
  return st;
}

std::string problem_of(const SearchState& st, std::uint64_t subproblems = 0, int shard = 0, int shards = 1) {
  try {
    check_search_state(st, subproblems, shard, shards);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SearchStateCheck, AConsistentStatePasses) {
  EXPECT_EQ(problem_of(good_state()), "");
  EXPECT_EQ(problem_of(good_state(), 8), "");
  EXPECT_EQ(problem_of(SearchState{}), "");  // a restart search before its first restart
}

TEST(SearchStateCheck, AnInFlightSubproblemListedTwiceIsRefused) {
  SearchState st = good_state();
  st.in_flight.push_back(st.in_flight[0]);
  EXPECT_EQ(problem_of(st), "in-flight subproblem 2 is listed twice");
}

TEST(SearchStateCheck, IndicesOutOfRangeOrFinishedAreRefused) {
  SearchState st = good_state();
  st.in_flight[1].index = 8;
  EXPECT_EQ(problem_of(st), "in-flight subproblem 8 is out of range (there are 8)");
  st = good_state();
  st.in_flight[1].index = 1;
  EXPECT_EQ(problem_of(st), "in-flight subproblem 1 is also finished");
  st = good_state();
  st.finished.pop_back();
  EXPECT_EQ(problem_of(st), "the finished bitmap has 7 entries for 8 subproblems");
}

TEST(SearchStateCheck, CountersMustBeConsistent) {
  SearchState st = good_state();
  st.finished_counts.orbits = 97;
  EXPECT_EQ(problem_of(st), "the finished subproblems' total counts 97 orbits but only 96 solutions");
  st = good_state();
  st.finished.assign(8, false);
  EXPECT_EQ(problem_of(st), "it counts solutions or nodes for finished subproblems but none is finished");
  st = good_state();
  st.in_flight[0].counted.orbits = 17;
  EXPECT_EQ(problem_of(st), "in-flight subproblem 2 counts 17 orbits but only 16 solutions");
  st = good_state();
  st.in_flight[0].path[1].value = -1;
  EXPECT_EQ(problem_of(st), "in-flight subproblem 2 has a negative decision (3, -1)");
  st = good_state();
  st.seconds = -1;
  EXPECT_EQ(problem_of(st), "its time so far (-1 s) is not a non-negative number");
}

TEST(SearchStateCheck, RestartsAreBounded) {
  SearchState st;
  st.restarts = std::uint64_t(1) << 63;  // made the Luby schedule shift by 64 and loop forever
  st.restart_nodes = 10;
  EXPECT_EQ(problem_of(st), "9223372036854775808 restarts is more than the limit of 1099511627776");
  st.restarts = 0;  // the first dive cut short by a stop: its nodes are counted, it runs again
  EXPECT_EQ(problem_of(st), "");
}

TEST(SearchStateCheck, AgainstTheResumingSearchCountAndShardMustMatch) {
  EXPECT_EQ(problem_of(good_state(), 9), "it has 8 subproblems but this search has 9 (different problem or options)");
  EXPECT_EQ(problem_of(good_state(), 8, 0, 2), "in-flight subproblem 5 is not in shard 0/2");
  SearchState st = good_state();
  st.in_flight = {{4, {}, {}}, {7, {}, {}}};  // both in shard 1/3
  EXPECT_EQ(problem_of(st, 8, 1, 3), "");
  st.in_flight[1].index = 5;
  EXPECT_EQ(problem_of(st, 8, 1, 3), "in-flight subproblem 5 is not in shard 1/3");
}

TEST(SearchStateCheck, TheEngineRefusesABadStateGivenInMemory) {
  // The engine's resume path runs the same check on a state handed to solve() directly: the
  // final state of a real count, with subproblem 0 made unfinished and listed in flight twice.
  TilingProblem p = complete_packing_problem(TileKind::Corner, 2);
  SearchOptions o;
  o.mode = SearchMode::Count;
  o.run.threads = 1;
  SearchState saved;
  o.save_checkpoint = [&](const SearchState& s) { saved = s; };
  solve(p, o);
  ASSERT_GT(saved.subproblem_count, 1u);
  saved.finished[0] = false;
  saved.finished_counts = {};
  saved.finished.assign(saved.finished.size(), false);
  saved.in_flight = {{0, {}, {}}, {0, {}, {}}};
  o.save_checkpoint = nullptr;
  o.resume_state = saved;
  try {
    solve(p, o);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "checkpoint is inconsistent: in-flight subproblem 0 is listed twice");
  }
  saved.in_flight.pop_back();
  o.resume_state = saved;
  EXPECT_EQ(solve(p, o).solutions, 32u);  // the repaired state resumes to the full count
}

TEST(Luby, NoShiftReachesSixtyFourBits) {
  EXPECT_EQ(luby(std::numeric_limits<std::uint64_t>::max()), std::uint64_t(1) << 63);
  EXPECT_EQ(luby((std::uint64_t(1) << 63) + 5), luby(6));
  EXPECT_EQ(luby(0), 1u);
  EXPECT_EQ(luby_limit(std::numeric_limits<std::uint64_t>::max(), 2000), std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(luby_limit(15, 2000), 16000u);
}
