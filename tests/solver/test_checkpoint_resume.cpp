// Checkpoints: the file format (atomic, versioned, checksummed), and resuming a stopped search
// gives exactly the uninterrupted result; shards partition the search.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "checkpoints/checkpoint.hpp"
#include "solver/cell_model.hpp"
#include "solver/knuth_estimate.hpp"
#include "solver/solve.hpp"
#include "tests/cli_runner.hpp"
#include "base/error.hpp"
#include "tilesets/tile_set_io.hpp"
#include "tilesets/validator.hpp"

using namespace tilekit;
using tilekit::test::TempDir;

namespace {

SearchState sample_state() {
  SearchState s;
  s.fingerprint = R"({"mode":"count"})";
  s.subproblem_count = 10;
  s.subproblem_hash = 0xdeadbeef12345678ull;
  s.finished = {true, false, true, true, false, false, false, false, false, true};
  s.finished_counts = {12, 3, 456};
  s.finished_each = {{3, 1, 100}, {3, 1, 100}, {3, 1, 100}, {3, 0, 156}};
  s.in_flight.push_back({4, {{0, 1}, {5, 7}, {6, 2}}, {1, 0, 17}});
  s.restarts = 9;
  s.restart_nodes = 99;
  s.seconds = 1.5;
  return s;
}

std::string expect_input_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return {};
}

TilingProblem corner2_tilings(int rows, int cols) {
  TilingProblem p;
  p.set = complete_corner_set(2);
  p.rows = rows, p.cols = cols, p.torus = true;
  return p;
}

}  // namespace

TEST(CheckpointFile, RoundTripsEveryField) {
  SearchState s = sample_state();
  SearchState t = decode_checkpoint(encode_checkpoint(s), "x");
  EXPECT_EQ(t.fingerprint, s.fingerprint);
  EXPECT_EQ(t.subproblem_count, 10u);
  EXPECT_EQ(t.subproblem_hash, s.subproblem_hash);
  EXPECT_EQ(t.finished, s.finished);
  EXPECT_EQ(t.finished_counts, s.finished_counts);
  EXPECT_EQ(t.finished_each, s.finished_each);
  ASSERT_EQ(t.in_flight.size(), 1u);
  EXPECT_EQ(t.in_flight[0].path, s.in_flight[0].path);
  EXPECT_EQ(t.in_flight[0].counted, s.in_flight[0].counted);
  EXPECT_EQ(t.restarts, 9u);
  EXPECT_EQ(t.seconds, 1.5);
}

TEST(CheckpointFile, CorruptTruncatedForeignAndFutureFilesAreInputErrors) {
  std::string good = encode_checkpoint(sample_state());
  std::string flipped = good;
  flipped[flipped.size() - 10] ^= 1;
  EXPECT_NE(expect_input_error([&] { decode_checkpoint(flipped, "f"); }).find("checksum"), std::string::npos);
  EXPECT_NE(expect_input_error([&] { decode_checkpoint(good.substr(0, good.size() - 5), "f"); }).find("truncated"),
            std::string::npos);
  EXPECT_NE(expect_input_error([&] { decode_checkpoint("hello world\n", "f"); }).find("not a Tilekit checkpoint"),
            std::string::npos);
  std::string future = good;
  future.replace(future.find(" 3\n"), 3, " 4\n");  // this build writes version 3
  EXPECT_NE(expect_input_error([&] { decode_checkpoint(future, "f"); }).find("version 4"), std::string::npos);
  EXPECT_EQ(expect_input_error([&] { read_checkpoint("/nonexistent/ckpt"); }), "/nonexistent/ckpt: no such checkpoint");
}

TEST(CheckpointFile, WriteIsAtomicAndLeavesNoTemporaryFiles) {
  TempDir d;
  write_checkpoint(d / "c", sample_state());
  write_checkpoint(d / "c", sample_state());
  EXPECT_EQ(read_checkpoint(d / "c").finished_counts.nodes, 456u);
  int files = 0;
  for (auto& e : std::filesystem::directory_iterator(d.path)) files += e.is_regular_file();
  EXPECT_EQ(files, 1);
}

TEST(Resume, TimeSlicedRunsSumToTheUninterruptedCount) {
  // Every corner colouring of the 4x5 torus's pegs is a tiling of the complete set: 2^20.
  TempDir d;
  auto p = corner2_tilings(4, 5);
  SearchOptions o;
  o.mode = SearchMode::Count;
  o.run.threads = 2;
  SearchResult whole = solve_checkpointed(p, o);
  ASSERT_TRUE(whole.complete);
  ASSERT_EQ(whole.solutions, 1u << 20);
  // Each slice gets a tenth of the uninterrupted time, so sanitizer builds slice as often as
  // Release does (a fixed 20 ms ran out of slices under ASan at 97 % of the count).
  o.run.checkpoint_path = d / "ckpt";
  o.run.time_limit = std::max(0.02, whole.seconds / 10);
  o.run.checkpoint_every = o.run.time_limit / 4;
  SearchResult r = solve_checkpointed(p, o);
  int slices = 1;
  o.run.resume_path = o.run.checkpoint_path;
  while (!r.complete && slices < 1000) {
    o.run.threads = 1 + slices % 2;  // the thread count may change between runs
    r = solve_checkpointed(p, o);
    ++slices;
  }
  EXPECT_TRUE(r.complete);
  EXPECT_GT(slices, 2);
  EXPECT_EQ(r.solutions, whole.solutions);
  std::printf("uninterrupted %.3f s; %d slices of %.3f s\n", whole.seconds, slices, o.run.time_limit);
}

TEST(Resume, AllModeAcrossInterruptionsEmitsEveryPackingAndCountsExactly) {
  TempDir d;
  auto p = complete_packing_problem(TileKind::Wang, 2);
  std::set<std::vector<TileIndex>> seen;
  SearchOptions o;
  o.mode = SearchMode::All;
  o.run.threads = 2;
  o.run.checkpoint_path = d / "ckpt";
  o.run.time_limit = 0.05;
  o.run.checkpoint_every = 0.01;
  o.on_solution = [&](const Tiling& t) { seen.insert(t.cells); };
  SearchResult r = solve_checkpointed(p, o);
  o.run.resume_path = o.run.checkpoint_path;
  int slices = 1;
  while (!r.complete && slices < 2000) {
    r = solve_checkpointed(p, o);
    ++slices;
  }
  EXPECT_GT(slices, 1);
  EXPECT_EQ(r.solutions, 203520u);
  EXPECT_EQ(seen.size(), 203520u);
  EXPECT_EQ(r.orbits, solve(p,
                            [] {
                              SearchOptions c;
                              c.mode = SearchMode::Count;
                              return c;
                            }())
                          .orbits);
}

TEST(Resume, MismatchedParametersAreRejectedNamingTheDifference) {
  TempDir d;
  auto p = complete_packing_problem(TileKind::Wang, 2);
  SearchOptions o;
  o.mode = SearchMode::Count;
  o.run.checkpoint_path = d / "ckpt";
  solve_checkpointed(p, o);
  SearchOptions other = o;
  other.run.resume_path = o.run.checkpoint_path;
  other.mode = SearchMode::All;
  EXPECT_NE(expect_input_error([&] { solve_checkpointed(p, other); }).find("mode"), std::string::npos);
  other = o;
  other.run.resume_path = o.run.checkpoint_path;
  other.run.seed = 5;
  EXPECT_NE(expect_input_error([&] { solve_checkpointed(p, other); }).find("seed"), std::string::npos);
  EXPECT_NE(expect_input_error([&] {
              solve_checkpointed(complete_packing_problem(TileKind::Corner, 2), other);
            }).find("does not match"),
            std::string::npos);
}

TEST(Shards, FourShardsTogetherEqualTheWholeCount) {
  auto p = complete_packing_problem(TileKind::Wang, 2);
  SearchOptions o;
  o.mode = SearchMode::Count;
  SearchResult whole = solve(p, o);
  std::uint64_t sum = 0, orbits = 0, subs = 0, total_subs = 0;
  for (int i = 0; i < 4; ++i) {
    o.run.shard = {i, 4};
    SearchResult s = solve(p, o);
    EXPECT_TRUE(s.complete);
    EXPECT_GT(s.solutions, 0u);
    EXPECT_LT(s.solutions, whole.solutions);
    sum += s.solutions, orbits += *s.orbits, subs += s.shard_subproblems;
    total_subs = s.subproblems;
  }
  EXPECT_EQ(subs, total_subs);  // each subproblem in exactly one shard
  EXPECT_EQ(sum, 203520u);
  EXPECT_EQ(orbits, *whole.orbits);
}

// `pack --estimate 2147483648` ran without bound: the stop asked before every probe (the time
// limit, a signal) ends the estimate on the probes made so far.
TEST(KnuthEstimate, AStopEndsTheProbesAndTheEstimateRestsOnThoseMade) {
  auto p = complete_packing_problem(TileKind::Wang, 2);
  CellModel m(p, true, CellModel::Ordering::Static);
  int asked = 0;
  const TreeEstimate e = knuth_estimate(m, std::uint64_t(1) << 40, 1, [&] { return ++asked > 50; });
  EXPECT_EQ(e.probes, 50u);
  EXPECT_EQ(asked, 51);
  EXPECT_GT(e.nodes, 0);
  const TreeEstimate none = knuth_estimate(m, 1000, 1, [] { return true; });
  EXPECT_EQ(none.probes, 0u);
  EXPECT_EQ(none.nodes, 0);
}

TEST(KnuthEstimate, IsWithinAFactorOfTwoOfTheExactTreeSize) {
  auto p = complete_packing_problem(TileKind::Wang, 2);
  CellModel m(p, true, CellModel::Ordering::Static);
  TreeEstimate e = knuth_estimate(m, 2000, 1);
  SearchOptions o;
  o.mode = SearchMode::Count;
  o.subproblems = 1;
  SearchResult r = solve(p, o);
  EXPECT_GT(e.nodes, 0.5 * double(r.nodes));
  EXPECT_LT(e.nodes, 2.0 * double(r.nodes));
  EXPECT_GT(e.leaves * 16, 0.5 * 203520);
  EXPECT_LT(e.leaves * 16, 2.0 * 203520);
  // The logarithmic form (for trees beyond double's range) is the same mean.
  EXPECT_NEAR(e.log10_nodes, std::log10(e.nodes), 1e-9);
}
