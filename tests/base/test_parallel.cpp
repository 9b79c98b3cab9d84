// The one parallel helper (base/parallel.hpp): parallel_for runs every index exactly once for
// any thread count and size, a stop token ends it early, and the first exception wins.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

#include "base/error.hpp"
#include "base/parallel.hpp"

using namespace tilekit;

TEST(ParallelFor, EveryIndexRunsExactlyOnceForSeveralThreadCountsAndSizes) {
  for (int threads : {1, 2, 3, 8}) {
    for (std::int64_t n : {0, 1, 2, 7, 64, 1000, 4099}) {
      std::vector<std::atomic<int>> runs(static_cast<std::size_t>(n));
      parallel_for(n, threads, [&](std::int64_t i) {
        ASSERT_GE(i, 0);
        ASSERT_LT(i, n);
        runs[std::size_t(i)].fetch_add(1);
      });
      int wrong = 0;
      for (auto& r : runs) wrong += r.load() != 1;
      EXPECT_EQ(wrong, 0) << threads << " threads, n = " << n;
    }
  }
}

TEST(ParallelFor, AStopTokenStopsNewIndices) {
  for (int threads : {1, 2, 4}) {
    StopToken stop;
    std::atomic<std::int64_t> ran{0};
    const std::int64_t n = 1000000, stop_at = 100;
    parallel_for(
        n, threads,
        [&](std::int64_t) {
          if (ran.fetch_add(1) + 1 == stop_at) stop.request(StopReason::Cancelled);
        },
        &stop);
    EXPECT_EQ(stop.reason(), StopReason::Cancelled);
    // Only the indices already taken when the stop came still run: at most one per thread.
    EXPECT_GE(ran.load(), stop_at);
    EXPECT_LE(ran.load(), stop_at + threads) << threads << " threads";
  }
}

TEST(ParallelFor, AStopRequestedBeforehandRunsNothing) {
  StopToken stop;
  stop.request(StopReason::Signal);
  std::atomic<int> ran{0};
  parallel_for(
      100, 4, [&](std::int64_t) { ++ran; }, &stop);
  EXPECT_EQ(ran.load(), 0);
  EXPECT_EQ(stop.reason(), StopReason::Signal);  // the first reason stays
}

TEST(ParallelFor, TheFirstExceptionIsRethrownAndStopsTheOthers) {
  StopToken stop;
  std::atomic<std::int64_t> ran{0};
  EXPECT_THROW(parallel_for(
                   1000000, 4,
                   [&](std::int64_t i) {
                     ++ran;
                     if (i == 10) throw InputError("index 10");
                   },
                   &stop),
               InputError);
  EXPECT_EQ(stop.reason(), StopReason::Error);
  EXPECT_LT(ran.load(), 1000000);
}

TEST(ParallelTeam, EveryMemberRunsOnceWithItsOwnNumber) {
  for (int threads : {1, 2, 5}) {
    std::vector<std::atomic<int>> seen(static_cast<std::size_t>(threads));
    parallel_team(threads, [&](int t) { seen[std::size_t(t)].fetch_add(1); });
    for (int t = 0; t < threads; ++t) EXPECT_EQ(seen[std::size_t(t)].load(), 1) << t;
  }
}

TEST(StopToken, TheFirstReasonWins) {
  StopToken s;
  EXPECT_FALSE(s.requested());
  EXPECT_TRUE(s.request(StopReason::TimeLimit));
  EXPECT_FALSE(s.request(StopReason::Signal));
  EXPECT_EQ(s.reason(), StopReason::TimeLimit);
}
