// The scheduling simulator (cluster/schedule_sim.hpp) on hand-made traces whose makespans are
// known: static i mod P, the dynamic pool, split rounds and stealing of open pieces.
#include <gtest/gtest.h>

#include <string>

#include "base/error.hpp"
#include "cluster/schedule_sim.hpp"
#include "tests/cli_runner.hpp"

namespace tilekit {
namespace {
using test::TempDir;
using test::write_text;

// Units 0..3: one heavy subproblem of 8 pieces of 1 node and three of 1 node.
std::string sim_trace(const TempDir& d) {
  const std::string path = (d.path / "t.jsonl").string();
  write_text(path,
             "{\"type\":\"search\",\"title\":\"t\",\"mode\":\"count\",\"subproblems\":4}\n"
             "{\"type\":\"subproblem\",\"title\":\"t\",\"index\":0,\"nodes\":8,\"seconds\":8,"
             "\"pieces\":[[1,1],[1,1],[1,1],[1,1],[1,1],[1,1],[1,1],[1,1]]}\n"
             "{\"type\":\"subproblem\",\"title\":\"t\",\"index\":1,\"nodes\":1,\"seconds\":1,\"pieces\":[[1,1]]}\n"
             "{\"type\":\"subproblem\",\"title\":\"t\",\"index\":2,\"nodes\":1,\"seconds\":1,\"pieces\":[[1,1]]}\n"
             "{\"type\":\"subproblem\",\"title\":\"t\",\"index\":3,\"nodes\":1,\"seconds\":1,\"pieces\":[[1,1]]}\n");
  return path;
}

TEST(ScheduleSim, StaticPoolAndStealMakespans) {
  TempDir d;
  const cluster::Trace t = cluster::read_trace({sim_trace(d)}, "nodes");
  EXPECT_EQ(t.units.size(), 4u);
  EXPECT_DOUBLE_EQ(t.work(), 11);
  EXPECT_DOUBLE_EQ(t.largest_piece(), 1);
  // 2 workers: static gives worker 0 units 0 and 2 (9 nodes); the pool puts 1, 2, 3 on worker 1.
  EXPECT_DOUBLE_EQ(cluster::simulate(t, cluster::SchedulePolicy::Static, 2).makespan, 9);
  EXPECT_DOUBLE_EQ(cluster::simulate(t, cluster::SchedulePolicy::Pool, 2).makespan, 8);
  // Stealing halves of unit 0's open pieces evens the load: ceil(11 / 2) = 6.
  const cluster::SimResult s = cluster::simulate(t, cluster::SchedulePolicy::Steal, 2);
  EXPECT_DOUBLE_EQ(s.makespan, 6);
  EXPECT_GT(s.steals, 0u);
  EXPECT_DOUBLE_EQ(s.ideal, 5.5);
  // 11 workers: the ideal is one node each; stealing reaches the largest piece.
  EXPECT_DOUBLE_EQ(cluster::simulate(t, cluster::SchedulePolicy::Steal, 11).makespan, 1);
  // Split: the first round cuts at 11/2 and leaves unit 0's unstarted pieces to the next rounds.
  const cluster::SimResult sp = cluster::simulate(t, cluster::SchedulePolicy::Split, 2, 4);
  EXPECT_LT(sp.makespan, 9);
  EXPECT_GE(sp.makespan, 5.5);
  EXPECT_GT(sp.rounds, 1);
}

TEST(ScheduleSim, FirstModeEndsWithTheFoundDive) {
  TempDir d;
  const std::string path = (d.path / "f.jsonl").string();
  write_text(path,
             "{\"type\":\"search\",\"title\":\"f\",\"mode\":\"first\"}\n"
             "{\"type\":\"dive\",\"dive\":0,\"nodes\":4,\"seconds\":1,\"found\":false}\n"
             "{\"type\":\"dive\",\"dive\":1,\"nodes\":2,\"seconds\":1,\"found\":false}\n"
             "{\"type\":\"dive\",\"dive\":2,\"nodes\":3,\"seconds\":1,\"found\":true}\n"
             "{\"type\":\"dive\",\"dive\":3,\"nodes\":9,\"seconds\":1,\"found\":false}\n");
  const cluster::Trace t = cluster::read_trace({path}, "nodes");
  EXPECT_TRUE(t.first);
  EXPECT_DOUBLE_EQ(t.work(), 9);  // up to the found dive
  // static on 2 workers: dives 0 and 2 on worker 0 end at 7; the pool runs dive 2 after dive 1: 5.
  EXPECT_DOUBLE_EQ(cluster::simulate(t, cluster::SchedulePolicy::Static, 2).makespan, 7);
  EXPECT_DOUBLE_EQ(cluster::simulate(t, cluster::SchedulePolicy::Pool, 2).makespan, 5);
  // Without a found dive the run is every dive: static 0+2 = 4+3 = 7 and 1+3 = 2+9 = 11.
  write_text(path,
             "{\"type\":\"search\",\"title\":\"f\",\"mode\":\"first\"}\n"
             "{\"type\":\"dive\",\"dive\":0,\"nodes\":4,\"seconds\":1,\"found\":false}\n"
             "{\"type\":\"dive\",\"dive\":1,\"nodes\":2,\"seconds\":1,\"found\":false}\n"
             "{\"type\":\"dive\",\"dive\":2,\"nodes\":3,\"seconds\":1,\"found\":false}\n"
             "{\"type\":\"dive\",\"dive\":3,\"nodes\":9,\"seconds\":1,\"found\":false}\n");
  const cluster::Trace none = cluster::read_trace({path}, "nodes");
  EXPECT_FALSE(none.found);
  EXPECT_DOUBLE_EQ(cluster::simulate(none, cluster::SchedulePolicy::Static, 2).makespan, 11);
  EXPECT_LE(cluster::simulate(none, cluster::SchedulePolicy::Pool, 2).efficiency, 1.0);
}

TEST(ScheduleSim, RefusesBadTracesAndSettings) {
  TempDir d;
  const std::string bad = (d.path / "bad.jsonl").string();
  write_text(bad, "{\"type\":\"subproblem\",\"index\":0,\"nodes\":-1}\n");
  EXPECT_THROW(cluster::read_trace({bad}, "nodes"), InputError);
  write_text(bad, "not json\n");
  EXPECT_THROW(cluster::read_trace({bad}, "nodes"), InputError);
  EXPECT_THROW(cluster::read_trace({sim_trace(d)}, "joules"), InputError);
  const cluster::Trace t = cluster::read_trace({sim_trace(d)}, "seconds");
  EXPECT_THROW(cluster::simulate(t, cluster::SchedulePolicy::Steal, 0), InputError);
  EXPECT_THROW(cluster::policy_from_name("random"), InputError);
}

}  // namespace
}  // namespace tilekit
