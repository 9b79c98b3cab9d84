#pragma once
// Adaptive splitting of a job array (`cluster submit --split-after S`), where MPI is not at hand.
// Round 0 is the array of N shards, each run stopped after S seconds (`pack --time-limit`); a shard
// that ran past that share leaves its checkpoint (its finished subproblems, and its open ones at
// their decision paths) and shard-I.split.json. The merge job then calls next_round(): for every
// shard of the last round's units, the shard's checkpoint merged with all its parts' files
// (shard-I.ckpt.rank-*, merge_search_states: idempotent) says what is unfinished; a unit that
// still owns unfinished subproblems is split `ways` ways (ShardPart::refined, base/run_control.hpp)
// into the units of the next round, written to units/round-R.tsv ("SHARD PART PARTS" per line),
// which the next array's task T runs as `pack --shard I/N --part J/K --resume shard-I.ckpt`
// (cluster/part_work.hpp), writing shard-I.ckpt.rank-<unit_id(R, T)>. A shard with nothing
// unfinished is complete: its result, from the merged state, goes to shard-I.done.json, and the
// merge job merges as for any array once every shard is.
//
// Granularity: the subproblems of the engine's split (about a thousand per search); a subproblem
// that is open when its unit stops is resumed whole, at its path, by one unit of the next round
// (its subtree is not cut further).
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "base/run_control.hpp"

namespace tilekit::cluster {

// One work unit of a round: part `part` of shard `shard` of the run.
struct SplitUnit {
  int shard = 0;
  ShardPart part;
  bool operator==(const SplitUnit&) const = default;
};

// The most units of one round (unit ids below keep rounds apart).
inline constexpr int kMaxRoundUnits = 10'000'000;

// The id of unit `task` of round `round` (>= 1): its checkpoint is shard-I.ckpt.rank-<id>.
long long unit_id(int round, int task);

// units/round-R.tsv of `run_dir` (round >= 1); round 0 is the shards whose shard-I.split.json
// exists and whose shard-I.done.json does not, each whole (part 0 of 1). Throws InputError on a
// malformed line or a shard out of range.
std::vector<SplitUnit> read_round(const std::filesystem::path& run_dir, int round, int shards);

struct RoundPlan {
  int round = 0;                   // the round the units are for (after_round + 1)
  std::vector<SplitUnit> units;    // written to units/round-R.tsv (none: nothing left to split)
  std::vector<int> completed;      // shards found complete now (their shard-I.done.json written)
  std::uint64_t unfinished = 0;    // unfinished subproblems over the units' shards
};

// Reads the state after round `after_round`, writes the shards found complete and the units of
// the next round (both atomically), and returns them. `ways` >= 2: how many units an unfinished
// unit becomes. A unit already at kMaxShards parts is not split further (it runs again whole).
RoundPlan next_round(const std::filesystem::path& run_dir, int after_round, int ways);

nlohmann::json to_json(const RoundPlan& plan);

}  // namespace tilekit::cluster
