#include "cluster/split.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/input.hpp"
#include "checkpoints/checkpoint.hpp"
#include "cluster/run_directory.hpp"
#include "solver/search_state.hpp"

namespace tilekit::cluster {
namespace fs = std::filesystem;
namespace {

fs::path round_file(const fs::path& dir, int round) {
  return dir / "units" / fmt::format("round-{}.tsv", round);
}

// Shard `shard`'s checkpoint merged with every part's file beside it.
SearchState merged_state(const fs::path& dir, int shard) {
  const std::string path = shard_file(dir, shard, ".ckpt").string();
  SearchState st = read_checkpoint(path);
  for (const std::string& f : rank_checkpoint_files(path)) {
    try {
      merge_search_states(st, read_checkpoint(f));
    } catch (const InputError& e) {
      throw InputError(fmt::format("checkpoint {}: {}", f, e.what()));
    }
  }
  return st;
}

bool file_exists(const fs::path& p) {
  std::error_code ec;
  return fs::exists(p, ec);
}

}  // namespace

long long unit_id(int round, int task) {
  return (long long)round * kMaxRoundUnits + task;
}

std::vector<SplitUnit> read_round(const fs::path& dir, int round, int shards) {
  std::vector<SplitUnit> out;
  if (round == 0) {
    for (int i = 0; i < shards; ++i)
      if (file_exists(shard_file(dir, i, ".split.json")) && !file_exists(shard_file(dir, i, ".done.json")))
        out.push_back({i, ShardPart{}});
    return out;
  }
  const fs::path file = round_file(dir, round);
  const std::string text = read_input_file(file.string(), "split round file", kMaxShardFileBytes);
  std::size_t line_no = 0;
  for (std::size_t begin = 0; begin < text.size();) {
    const std::size_t end = std::min(text.find('\n', begin), text.size());
    const std::string line = text.substr(begin, end - begin);
    begin = end + 1;
    ++line_no;
    if (line.empty()) continue;
    long long s = -1, j = -1, k = 0;
    char extra = 0;
    if (std::sscanf(line.c_str(), "%lld %lld %lld %c", &s, &j, &k, &extra) != 3 || s < 0 || s >= shards || k < 1 ||
        k > kMaxShards || j < 0 || j >= k)
      throw InputError(fmt::format("{} line {}: expected SHARD PART PARTS with SHARD < {} and PART < PARTS, got '{}'",
                                   file.string(), line_no, shards, line.substr(0, 80)));
    out.push_back({int(s), ShardPart{int(j), int(k)}});
    if (out.size() > std::size_t(kMaxRoundUnits)) throw InputError(fmt::format("{}: too many units", file.string()));
  }
  return out;
}

RoundPlan next_round(const fs::path& dir, int after_round, int ways) {
  if (ways < 2 || ways > 1000) throw InputError(fmt::format("`split_ways` must be 2..1000, got {}", ways));
  if (after_round < 0 || after_round >= 1000) throw InputError(fmt::format("round {} out of range", after_round));
  const auto run = read_run_file(dir / "run.json");
  if (!run) throw NotFound(fmt::format("{}: no run.json (not a `tilekit cluster submit` run directory)", dir.string()));
  const int shards = run->shards;
  const std::vector<SplitUnit> last = read_round(dir, after_round, shards);
  std::map<int, std::vector<ShardPart>> by_shard;
  for (const SplitUnit& u : last) by_shard[u.shard].push_back(u.part);

  RoundPlan plan;
  plan.round = after_round + 1;
  for (const auto& [shard, parts] : by_shard) {
    const ShardSpec spec{shard, shards};
    const SearchState st = merged_state(dir, shard);
    std::vector<std::uint64_t> open;  // the shard's unfinished subproblems
    std::uint64_t owned = 0;
    for (std::uint64_t i = 0; i < st.subproblem_count; ++i) {
      if (!spec.owns(i)) continue;
      ++owned;
      if (i >= st.finished.size() || !st.finished[i]) open.push_back(i);
    }
    plan.unfinished += open.size();
    const auto owns_open = [&](const ShardPart& p) {
      return std::any_of(open.begin(), open.end(), [&](std::uint64_t i) { return p.owns(i, spec); });
    };
    if (open.empty()) {  // every subproblem of the shard is finished: its result, from the state
      nlohmann::json done = {{"solutions", st.finished_counts.solutions},
                             {"orbits", st.finished_counts.orbits},
                             {"nodes", st.finished_counts.nodes},
                             {"subproblems", owned},
                             {"subproblems_done", owned},
                             {"complete", true},
                             {"timed_out", false},
                             {"shard", fmt::format("{}/{}", shard, shards)},
                             {"split_rounds", after_round},
                             {"total_seconds", st.seconds}};
      write_file_atomic(shard_file(dir, shard, ".done.json").string(), done.dump() + "\n");
      plan.completed.push_back(shard);
      continue;
    }
    std::set<std::pair<int, int>> seen;  // a unit listed twice in a round file runs once
    for (const ShardPart& p : parts) {
      if (!owns_open(p) || !seen.insert({p.part, p.parts}).second) continue;
      if (std::int64_t(p.parts) * ways > kMaxShards) {
        plan.units.push_back({shard, p});
        continue;
      }
      for (int m = 0; m < ways; ++m)
        if (const ShardPart q = p.refined(m, ways); owns_open(q)) plan.units.push_back({shard, q});
    }
  }
  if (plan.units.size() > std::size_t(kMaxRoundUnits))
    throw InputError(fmt::format("round {} would have {} units, more than {}", plan.round, plan.units.size(),
                                 kMaxRoundUnits));
  if (!plan.units.empty()) {
    std::string text;
    for (const SplitUnit& u : plan.units) text += fmt::format("{} {} {}\n", u.shard, u.part.part, u.part.parts);
    fs::create_directories(dir / "units");
    write_file_atomic(round_file(dir, plan.round).string(), text);
  }
  return plan;
}

nlohmann::json to_json(const RoundPlan& p) {
  nlohmann::json units = nlohmann::json::array();
  for (const SplitUnit& u : p.units)
    units.push_back({{"shard", u.shard}, {"part", u.part.part}, {"parts", u.part.parts}});
  return {{"round", p.round},
          {"units", p.units.size()},
          {"unit_list", units},
          {"completed_shards", p.completed},
          {"unfinished_subproblems", p.unfinished}};
}

}  // namespace tilekit::cluster
