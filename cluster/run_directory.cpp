#include "cluster/run_directory.hpp"

#include <fmt/format.h>

#include "base/error.hpp"
#include "base/input.hpp"
#include "base/json_input.hpp"
#include "base/parse.hpp"

namespace tilekit::cluster {
namespace fs = std::filesystem;

namespace {

// A JSON file of the run directory through the checked readers; nullopt when it is absent.
// `what` names it in messages.
std::optional<nlohmann::json> read_json(const fs::path& p, std::string_view what, std::uint64_t max_bytes) {
  std::error_code ec;
  if (!fs::exists(p, ec)) return std::nullopt;
  return parse_json_input(read_input_file(p.string(), what, max_bytes), p.string());
}

}  // namespace

std::optional<RunFile> read_run_file(const fs::path& p) {
  auto doc = read_json(p, "cluster run file", kMaxRunFileBytes);
  if (!doc) return std::nullopt;
  RunFile r;
  r.doc = *doc;
  const JsonIn j(r.doc, p.string());
  r.shards = int(j.at("shards").integer(1, kMaxShards));
  const JsonIn args = j.at("pack_args");
  for (std::size_t i = 0, n = args.array(0, kMaxShardArgs); i < n; ++i)
    r.pack_args.push_back(args[i].string(kMaxShardArgBytes));
  if (auto s = j.find("submissions")) {
    s->array();
    r.submissions = s->raw();
  }
  if (auto sp = j.find("split")) r.split_ways = int(sp->at("ways").integer(2, 1000));
  if (auto m = j.find("mpi")) r.mpi_ranks = int(m->at("ntasks").integer(1, kMaxShards));
  if (auto c = j.find("command")) {
    std::vector<std::string> words;
    for (std::size_t i = 0, n = c->array(1, 8); i < n; ++i) words.push_back((*c)[i].string(64));
    r.pack = words == std::vector<std::string>{"pack"};
  }
  return r;
}

nlohmann::json run_record(const ClusterPlan& p) {
  return {{"format", "tilekit-cluster-run"},
          {"version", 1},
          {"tilekit", p.tilekit},
          {"shards", p.shards},
          {"command", p.command},
          {"pack_args", p.pack_args},
          {"cpus_per_task", p.cpus_per_task},
          {"time", p.time},
          {"signal_seconds", p.signal_seconds},
          {"max_requeues", p.max_requeues},
          {"checkpoint_every", p.checkpoint_every},
          {"partition", p.partition},
          {"split", p.split_after > 0 ? nlohmann::json{{"after", p.split_after}, {"ways", p.split_ways}}
                                      : nlohmann::json(nullptr)},
          {"mpi", p.mpi ? nlohmann::json{{"nodes", p.nodes},
                                         {"ntasks", p.ntasks},
                                         {"launcher", p.launcher},
                                         {"srun_mpi", p.srun_mpi}}
                        : nlohmann::json(nullptr)},
          {"submissions", nlohmann::json::array()}};
}

std::optional<nlohmann::json> read_job_result(const fs::path& p) {
  try {
    auto j = read_json(p, "shard result", kMaxShardFileBytes);
    if (j && j->is_object()) return j;
  } catch (const InputError&) {
  }
  return std::nullopt;
}

fs::path shard_file(const fs::path& dir, int shard, std::string_view ext) {
  return dir / "shards" / fmt::format("shard-{}{}", shard, ext);
}

}  // namespace tilekit::cluster
