#include "cluster/status.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <string_view>

#include "base/error.hpp"
#include "base/input.hpp"
#include "base/json_input.hpp"
#include "checkpoints/checkpoint.hpp"
#include "cluster/run_directory.hpp"
#include "base/run_control.hpp"
#include "solver/search_state.hpp"

namespace tilekit::cluster {
namespace fs = std::filesystem;
namespace {

// A member of a job's result file if it has the given JSON type.
template <class T>
std::optional<T> member(const std::optional<nlohmann::json>& j, const char* key,
                        bool (nlohmann::json::*is)() const noexcept) {
  if (!j) return std::nullopt;
  auto it = j->find(key);
  if (it == j->end() || !((*it).*is)()) return std::nullopt;
  return it->get<T>();
}

// One line of an attempts file: its exit code, or nullopt when it is no attempt line (another
// JSON value, or a line cut short by a kill).
std::optional<std::int64_t> attempt_exit(std::string_view line) {
  try {
    const auto a = parse_json_input(line, "attempt");
    const auto exit = a.is_object() ? a.find("exit") : a.end();
    if (exit == a.end() || !exit->is_number_integer()) return std::nullopt;
    if (exit->is_number_unsigned() &&
        exit->get<std::uint64_t>() > std::uint64_t(std::numeric_limits<std::int64_t>::max()))
      return std::nullopt;
    return exit->get<std::int64_t>();
  } catch (const InputError&) {
    return std::nullopt;
  }
}

// Seconds since `path` was last written; nullopt when it cannot be told (the file is gone).
std::optional<std::int64_t> age_seconds(const fs::path& path) {
  std::error_code ec;
  const auto written = fs::last_write_time(path, ec);
  if (ec) return std::nullopt;
  return std::chrono::duration_cast<std::chrono::seconds>(fs::file_time_type::clock::now() - written).count();
}

template <class T>
nlohmann::json or_null(const std::optional<T>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

}  // namespace

ShardProgress checkpoint_progress(const fs::path& file, const ShardSpec& shard, bool with_rank_files) {
  ShardProgress p;
  SearchState st;
  try {
    st = read_checkpoint(file.string());
    // An MPI run: each rank's file holds what it ran (merging is idempotent, as on --resume).
    if (with_rank_files)
      for (const std::string& f : rank_checkpoint_files(file.string())) merge_search_states(st, read_checkpoint(f));
  } catch (const std::exception& e) {
    p.error = e.what();
    return p;
  }
  for (std::uint64_t k = 0; k < st.subproblem_count; ++k) {
    if (!shard.owns(k)) continue;
    ++p.subproblems;
    if (k < st.finished.size() && st.finished[k]) ++p.subproblems_done;
  }
  SearchCounters c = st.finished_counts;
  for (const auto& f : st.in_flight) c += f.counted;
  p.solutions = c.solutions;
  p.nodes = c.nodes;
  p.seconds = st.seconds;
  p.fraction = p.subproblems ? double(p.subproblems_done) / double(p.subproblems) : 0.0;
  // What is left: each open subproblem as large as the mean finished one (less what the open
  // ones counted already), at the node rate of the run so far.
  p.open = p.subproblems - p.subproblems_done;
  if (p.subproblems_done > 0) {
    std::uint64_t counted_open = 0, finished_nodes = 0;
    for (const auto& f : st.in_flight)
      if (shard.owns(f.index)) counted_open += f.counted.nodes;
    for (std::uint64_t k = 0, each = 0; k < st.finished.size() && each < st.finished_each.size(); ++k)
      if (st.finished[k]) {
        if (shard.owns(k)) finished_nodes += st.finished_each[each].nodes;
        ++each;
      }
    const double mean = double(finished_nodes) / double(p.subproblems_done);
    p.remaining_nodes = std::max(0.0, double(p.open) * mean - double(counted_open));
  }
  if (p.seconds > 0 && p.nodes > 0) p.node_rate = double(p.nodes) / p.seconds;
  if (p.open == 0)
    p.eta_seconds = 0.0;
  else if (p.remaining_nodes && p.node_rate > 0)
    p.eta_seconds = *p.remaining_nodes / p.node_rate;
  return p;
}

void read_attempts(const fs::path& path, ShardStatus& s) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return;  // no attempt yet
  std::string text;
  try {
    text = read_input_file(path.string(), "shard attempts file", kMaxShardFileBytes);
  } catch (const InputError& e) {
    s.attempts_error = e.what();
    return;
  }
  for (std::size_t begin = 0; begin < text.size();) {
    const std::size_t end = std::min(text.find('\n', begin), text.size());
    if (auto exit = attempt_exit(std::string_view(text).substr(begin, end - begin))) {
      ++s.attempts;
      if (*exit == 3) ++s.checkpointed_exits;
      s.last_exit = *exit;
    }
    begin = end + 1;
  }
}

ShardStatus shard_status(const fs::path& dir, const ShardSpec& shard, bool pack, bool mpi) {
  ShardStatus s;
  s.shard = shard.index;
  read_attempts(shard_file(dir, shard.index, ".attempts"), s);
  const auto done = read_job_result(shard_file(dir, shard.index, ".done.json"));
  const fs::path ckpt = shard_file(dir, shard.index, ".ckpt");
  std::error_code ec;
  if (fs::exists(ckpt, ec)) s.checkpoint_age_seconds = age_seconds(ckpt);
  const bool has_ckpt = s.checkpoint_age_seconds.has_value();
  s.state = done                                                                    ? "done"
            : fs::exists(shard_file(dir, shard.index, ".split.json"), ec)            ? "split"
            : has_ckpt                                                              ? "checkpointed"
            : s.attempts || fs::exists(shard_file(dir, shard.index, ".sqlite"), ec) ? "started"
                                                                                    : "pending";
  s.solutions = member<std::uint64_t>(done, "solutions", &nlohmann::json::is_number_unsigned);
  s.complete = member<bool>(done, "complete", &nlohmann::json::is_boolean);
  s.done_nodes = member<std::uint64_t>(done, "nodes", &nlohmann::json::is_number_unsigned);
  if (has_ckpt) {
    if (pack) {
      s.progress = checkpoint_progress(ckpt, shard, mpi);
    } else {
      s.progress = ShardProgress{};
      s.progress->error = "an enumerate checkpoint (progress lines: the shard's log)";
    }
  }
  return s;
}

RunStatus read_run_status(const std::string& run_dir) {
  RunStatus r;
  const fs::path dir = fs::absolute(run_dir);
  auto run = read_run_file(dir / "run.json");
  if (!run) throw NotFound(fmt::format("{}: no run.json (not a `tilekit cluster submit` run directory)", dir.string()));
  r.run_dir = dir.string();
  r.shards = run->shards;
  r.pack_args = run->pack_args;
  r.pack = run->pack;
  r.submissions = run->submissions;
  r.mpi_ranks = run->mpi_ranks;
  for (int i = 0; i < r.shards; ++i) {
    ShardStatus s = shard_status(dir, ShardSpec{i, r.shards}, r.pack, r.mpi_ranks > 0 || run->split_ways > 0);
    int& count = s.state == "done"                                  ? r.done
                 : s.state == "checkpointed" || s.state == "split" ? r.checkpointed
                 : s.state == "started"      ? r.started
                                             : r.pending;
    ++count;
    if (s.solutions) r.solutions_in_done_shards += *s.solutions;
    r.per_shard.push_back(std::move(s));
  }
  // Across the run: work done and outstanding (nodes), and when the last shard ends.
  bool known = r.pack, all_done = true;
  double outstanding = 0, eta = 0;
  for (const ShardStatus& s : r.per_shard) {
    if (s.state == "done") {
      r.work_done_nodes += s.done_nodes.value_or(0);
      continue;
    }
    all_done = false;
    const ShardProgress* p = s.progress && s.progress->error.empty() ? &*s.progress : nullptr;
    if (p) r.work_done_nodes += p->nodes;
    if (!p || !p->remaining_nodes || !p->eta_seconds) {
      known = false;  // a shard not started, or none of its subproblems finished yet
      continue;
    }
    outstanding += *p->remaining_nodes;
    eta = std::max(eta, *p->eta_seconds);
  }
  if (all_done) {
    r.work_outstanding_nodes = 0.0;
    r.eta_seconds = 0.0;
  } else if (known) {
    r.work_outstanding_nodes = outstanding;
    r.eta_seconds = eta;
  }
  const auto merged = read_job_result(dir / "merged.json");
  r.merged_solutions = member<std::uint64_t>(merged, "solutions", &nlohmann::json::is_number_unsigned);
  r.merged_orbits = member<std::uint64_t>(merged, "distinct_solutions", &nlohmann::json::is_number_unsigned);
  return r;
}

nlohmann::json to_json(const ShardProgress& p) {
  if (!p.error.empty()) return {{"error", p.error}};
  return {{"subproblems", p.subproblems},
          {"subproblems_done", p.subproblems_done},
          {"solutions", p.solutions},
          {"nodes", p.nodes},
          {"seconds", p.seconds},
          {"fraction", p.fraction},
          {"open_subproblems", p.open},
          {"remaining_nodes", or_null(p.remaining_nodes)},
          {"node_rate", p.node_rate},
          {"eta_seconds", or_null(p.eta_seconds)}};
}

nlohmann::json to_json(const ShardStatus& s) {
  nlohmann::json j = {{"shard", s.shard},
                      {"attempts", s.attempts},
                      {"checkpointed_exits", s.checkpointed_exits},
                      {"last_exit", or_null(s.last_exit)},
                      {"state", s.state},
                      {"solutions", or_null(s.solutions)},
                      {"complete", or_null(s.complete)},
                      {"checkpoint_age_seconds", or_null(s.checkpoint_age_seconds)},
                      {"progress", s.progress ? to_json(*s.progress) : nlohmann::json(nullptr)}};
  if (!s.attempts_error.empty()) j["attempts_error"] = s.attempts_error;
  return j;
}

nlohmann::json to_json(const RunStatus& r) {
  nlohmann::json shards = nlohmann::json::array();
  for (const ShardStatus& s : r.per_shard) shards.push_back(to_json(s));
  return {{"run_dir", r.run_dir},
          {"shards", r.shards},
          {"mpi_ranks", r.mpi_ranks ? nlohmann::json(r.mpi_ranks) : nlohmann::json(nullptr)},
          {"pack_args", r.pack_args},
          {"done", r.done},
          {"checkpointed", r.checkpointed},
          {"started", r.started},
          {"pending", r.pending},
          {"solutions_in_done_shards", r.solutions_in_done_shards},
          {"merged_solutions", or_null(r.merged_solutions)},
          {"merged_orbits", or_null(r.merged_orbits)},
          {"work_done_nodes", r.work_done_nodes},
          {"work_outstanding_nodes", or_null(r.work_outstanding_nodes)},
          {"eta_seconds", or_null(r.eta_seconds)},
          {"submissions", r.submissions},
          {"per_shard", shards}};
}

}  // namespace tilekit::cluster
