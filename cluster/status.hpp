#pragma once
// The status of a cluster run, read from its run directory alone (no Slurm needed): each
// shard's attempts, checkpoint and result, and the merged count.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "base/parse.hpp"

namespace tilekit::cluster {

// A shard's progress from its checkpoint: of the subproblems it owns (ShardSpec::owns, base/run_control.hpp, the
// engine's definition), how many are done; the counts of the finished ones plus what the
// in-flight ones counted so far. `error` instead when the checkpoint cannot be read.
struct ShardProgress {
  std::string error;  // non-empty: the reason, and no counts
  std::uint64_t subproblems = 0, subproblems_done = 0, solutions = 0, nodes = 0;
  double seconds = 0, fraction = 0;
  // Work outstanding, estimated: each open subproblem (unfinished, `open` of them) as large as
  // the mean finished one of this shard, less what the open ones counted already; unset until
  // one subproblem finished. node_rate = nodes / seconds so far; eta_seconds = remaining_nodes /
  // node_rate (0 when nothing is open).
  std::uint64_t open = 0;
  std::optional<double> remaining_nodes;
  double node_rate = 0;
  std::optional<double> eta_seconds;
};

struct ShardStatus {
  int shard = 0;
  std::string state;           // done, split (past its share, cluster/split.hpp), checkpointed, started or pending
  int attempts = 0;            // attempt lines in shard-I.attempts
  int checkpointed_exits = 0;  // of them, those that ended with exit 3
  std::optional<std::int64_t> last_exit;
  std::string attempts_error;              // non-empty: shard-I.attempts exists but cannot be read (why)
  std::optional<std::uint64_t> solutions;  // from shard-I.done.json
  std::optional<bool> complete;
  std::optional<std::uint64_t> done_nodes;  // from shard-I.done.json
  std::optional<std::int64_t> checkpoint_age_seconds;  // set when shard-I.ckpt exists
  std::optional<ShardProgress> progress;               // set when shard-I.ckpt exists
};

struct RunStatus {
  std::string run_dir;  // absolute
  int shards = 0;
  std::vector<std::string> pack_args;
  bool pack = true;  // shards of `tilekit pack` (else `aperiodic enumerate`)
  int mpi_ranks = 0;  // an MPI run (`cluster submit --mpi`): its ranks; it is shard 0 of 1
  int done = 0, checkpointed = 0, started = 0, pending = 0;
  std::uint64_t solutions_in_done_shards = 0;
  // From merged.json (`db stats`): solutions stored, each once, and how many of them differ up
  // to symmetry; unset until the merge job wrote it.
  std::optional<std::uint64_t> merged_solutions, merged_orbits;
  // Across the run: nodes searched (done shards' results, the others' checkpoints), nodes
  // outstanding (the shards' estimates) and the ETA: when the slowest unfinished shard ends at its
  // own node rate so far (a job array ends with its slowest shard). Unset while a shard has no
  // estimate yet (not started, or none of its subproblems finished); 0 when every shard is done.
  std::uint64_t work_done_nodes = 0;
  std::optional<double> work_outstanding_nodes, eta_seconds;
  nlohmann::json submissions = nlohmann::json::array();
  std::vector<ShardStatus> per_shard;
};

// Progress of `shard` from the checkpoint file at `path` (a pack shard's); `with_rank_files`: an
// MPI run's, merged with every `path`.rank-R beside it (checkpoints/checkpoint.hpp).
ShardProgress checkpoint_progress(const std::filesystem::path& path, const ShardSpec& shard,
                                  bool with_rank_files = false);

// Attempts of shard-I.attempts: one JSON line per attempt with an integer "exit"; lines cut short
// by a kill are skipped. Sets attempts, checkpointed_exits and last_exit, or attempts_error.
void read_attempts(const std::filesystem::path& path, ShardStatus& status);

// Shard `shard` of the run in `run_dir` (`pack`: its checkpoints are pack's).
ShardStatus shard_status(const std::filesystem::path& run_dir, const ShardSpec& shard, bool pack, bool mpi = false);

// The run in `run_dir`. Throws NotFound when it has no run.json, InputError when that is broken.
RunStatus read_run_status(const std::string& run_dir);

// What `cluster status --json` prints.
nlohmann::json to_json(const ShardProgress& progress);
nlohmann::json to_json(const ShardStatus& shard);
nlohmann::json to_json(const RunStatus& run);

}  // namespace tilekit::cluster
