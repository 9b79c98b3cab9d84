// tilekit cluster submit|status: a sharded `tilekit pack` as a Slurm job array.
// submit writes pack-array.sbatch, merge.sbatch and submit.sh into the run directory and
// queues them (sbatch); status reads the run directory (no Slurm needed) and shows each
// shard's attempts, checkpoint and result, and the merged count.
#include <fmt/format.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/atomic_file.hpp"
#include "checkpoints/checkpoint.hpp"
#include "cli/cluster_scripts.hpp"
#include "cli/command.hpp"
#include "base/error.hpp"
#include "base/json_input.hpp"
#include "base/parse.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit::cli {
namespace fs = std::filesystem;
namespace {

struct SubmitArgs {
  std::string command = "pack";  // or "enumerate": tilekit aperiodic enumerate
  std::string kind, method, mode = "all", run_dir, tilekit, job_name, sbatch = "sbatch";
  int colors = 0;
  std::string seed;
  std::vector<std::string> pack_extra;
  bool dry_run = false;
  int signal_seconds = 0;  // 0 = default_signal_seconds(--time)
  std::string merge_time;  // "" = --time
  ClusterPlan plan;
};

// A JSON file of the run directory through the checked reader (base/json_input.hpp); nullopt
// when it is absent. `what` names it in messages.
std::optional<nlohmann::json> read_json(const fs::path& p, std::string_view what) {
  std::error_code ec;
  if (!fs::exists(p, ec)) return std::nullopt;
  return read_json_file(p.string(), what);
}

// The same for the files the job scripts write (a kill may cut one short): an unreadable one
// counts as not written yet, and only an object is one.
std::optional<nlohmann::json> read_shard_json(const fs::path& p) {
  try {
    auto j = read_json(p, "shard result");
    if (j && j->is_object()) return j;
  } catch (const InputError&) {
  }
  return std::nullopt;
}

// run.json as `cluster submit` wrote it: shards, pack_args and submissions checked.
struct RunFile {
  nlohmann::json doc;
  int shards = 0;
  std::vector<std::string> pack_args;
  nlohmann::json submissions = nlohmann::json::array();
  bool pack = true;  // the shards run `tilekit pack` (else `aperiodic enumerate`)
};
std::optional<RunFile> read_run_file(const fs::path& p) {
  auto doc = read_json(p, "cluster run file");
  if (!doc) return std::nullopt;
  RunFile r;
  r.doc = *doc;
  const JsonIn j(r.doc, p.string());
  r.shards = int(j.at("shards").integer(1, kMaxShards));
  const JsonIn args = j.at("pack_args");
  for (std::size_t i = 0, n = args.array(0, 4096); i < n; ++i) r.pack_args.push_back(args[i].string(4096));
  if (auto s = j.find("submissions")) {
    s->array();
    r.submissions = s->raw();
  }
  if (auto c = j.find("command")) {
    std::vector<std::string> words;
    for (std::size_t i = 0, n = c->array(1, 8); i < n; ++i) words.push_back((*c)[i].string(64));
    r.pack = words == std::vector<std::string>{"pack"};
  }
  return r;
}

// A member of a shard's result file if it has the given JSON type, else null.
nlohmann::json member(const std::optional<nlohmann::json>& j, const char* key, bool (nlohmann::json::*is)() const noexcept) {
  if (!j) return nullptr;
  auto it = j->find(key);
  return it != j->end() && ((*it).*is)() ? *it : nlohmann::json(nullptr);
}

ClusterPlan make_plan(const SubmitArgs& o) {
  ClusterPlan p = o.plan;
  const bool enumerate = o.command == "enumerate";
  if (enumerate) {
    // `tilekit aperiodic enumerate` shards like pack (aperiodic/enumerate.hpp); its options come
    // with --pack-arg.
    if (!o.kind.empty() || o.colors != 0 || !o.method.empty() || !o.seed.empty())
      throw InputError("--command enumerate takes no --kind, --colors, --method or --seed (use --pack-arg)");
    p.command = {"aperiodic", "enumerate"};
    p.pack_args.clear();
  } else if (o.command == "pack") {
    if (o.kind != "wang" && o.kind != "corner" && o.kind != "window")
      throw InputError("--kind must be wang, corner or window");
    const bool has_window = std::any_of(o.pack_extra.begin(), o.pack_extra.end(),
                                        [](const std::string& a) { return a.rfind("--window=", 0) == 0; });
    if (o.kind == "window" && !has_window)
      throw InputError("--kind window needs --pack-arg=--window=KxL (and --pack-arg=--size=RxS)");
    if (o.colors < 1) throw InputError("--colors must be at least 1");
    p.pack_args = {"--kind", o.kind, "--colors", std::to_string(o.colors)};
    if (!o.method.empty()) p.pack_args.insert(p.pack_args.end(), {"--method", o.method});
    p.pack_args.insert(p.pack_args.end(), {"--mode", o.mode});
    if (!o.seed.empty()) p.pack_args.insert(p.pack_args.end(), {"--seed", o.seed});
  } else {
    throw InputError(fmt::format("--command must be pack or enumerate, got '{}'", o.command));
  }
  for (const auto& a : o.pack_extra) {
    for (const char* own : {"--shard", "--checkpoint", "--checkpoint-every", "--resume", "--db", "--threads", "--json",
                            "--portfolio-stats"})
      if (a == own || a.rfind(std::string(own) + "=", 0) == 0)
        throw InputError(fmt::format("--pack-arg {}: the job script sets it per shard", a));
    p.pack_args.push_back(a);
  }
  const std::string run_dir = !o.run_dir.empty() ? o.run_dir
                              : enumerate        ? std::string("tilekit-run-enumerate")
                                                 : fmt::format("tilekit-run-{}{}-{}", o.kind, o.colors, o.mode);
  p.run_dir = fs::absolute(run_dir).lexically_normal().string();
  if (p.run_dir.size() > 1 && p.run_dir.back() == '/') p.run_dir.pop_back();
  if (o.tilekit.empty()) {
    const char* path = std::getenv("PATH");
    p.tilekit = default_job_binary(path ? path : "", "/proc/self/exe");
  } else {
    p.tilekit = fs::absolute(o.tilekit).string();
    if (!fs::is_regular_file(p.tilekit) || ::access(p.tilekit.c_str(), X_OK) != 0)
      throw InputError(fmt::format("--tilekit {}: not an executable file", o.tilekit));
  }
  p.job_name = !o.job_name.empty() ? o.job_name
               : enumerate           ? std::string("tk-enumerate")
                                     : fmt::format("tk-{}{}", o.kind, o.colors);
  p.merge_time = o.merge_time.empty() ? p.time : o.merge_time;
  p.signal_seconds = o.signal_seconds > 0 ? o.signal_seconds : default_signal_seconds(parse_slurm_time(p.time));
  check_plan(p);
  return p;
}

nlohmann::json run_record(const ClusterPlan& p) {
  return {{"format", "tilekit-cluster-run"}, {"version", 1},         {"tilekit", p.tilekit},
          {"shards", p.shards},              {"command", p.command},     {"pack_args", p.pack_args},
          {"cpus_per_task", p.cpus_per_task},
          {"time", p.time},                  {"signal_seconds", p.signal_seconds},
          {"max_requeues", p.max_requeues},  {"checkpoint_every", p.checkpoint_every},
          {"partition", p.partition},        {"submissions", nlohmann::json::array()}};
}

// Runs `command` through the shell; returns its stdout, or throws with `what` on failure.
std::string run_capture(const std::string& command, const std::string& what) {
  FILE* f = ::popen(command.c_str(), "r");
  if (!f) throw InputError(fmt::format("{}: cannot run '{}'", what, command));
  std::string out;
  char buf[4096];
  while (std::size_t n = std::fread(buf, 1, sizeof buf, f)) out.append(buf, n);
  int status = ::pclose(f);
  int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
  if (code == 127) throw NotFound(fmt::format("{}: '{}' not found (not a Slurm host? --dry-run prints the scripts)", what, command));
  if (code != 0) throw InputError(fmt::format("{}: '{}' failed with exit code {}", what, command, code));
  return out;
}

std::string sbatch(const std::string& sbatch_cmd, const std::vector<std::string>& args) {
  std::string cmd = shell_quote(sbatch_cmd) + " --parsable";
  for (const auto& a : args) cmd += " " + shell_quote(a);
  std::string out = run_capture(cmd, "sbatch");
  std::string id = out.substr(0, out.find_first_of(";\n"));
  if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
    throw InputError(fmt::format("sbatch printed '{}', not a job id", out));
  return id;
}

void write_script(const fs::path& path, const std::string& text) {
  write_file_atomic(path.string(), text);
  fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                  fs::perm_options::add);
}

void run_submit(const SubmitArgs& o, const Context& ctx) {
  ClusterPlan p = make_plan(o);
  const std::vector<std::pair<std::string, std::string>> scripts = {
      {"pack-array.sbatch", pack_array_script(p)}, {"merge.sbatch", merge_script(p)}, {"submit.sh", submit_script(p)}};
  fs::path dir(p.run_dir);
  if (o.dry_run) {
    nlohmann::json js = nlohmann::json::object();
    for (const auto& [name, text] : scripts) js[(dir / name).string()] = text;
    emit(ctx,
         {{"dry_run", true}, {"run_dir", p.run_dir}, {"shards", p.shards}, {"tilekit", p.tilekit}, {"scripts", js}},
         [&] {
           for (const auto& [name, text] : scripts) fmt::print("==> {} <==\n{}\n", (dir / name).string(), text);
           fmt::print("(dry run: nothing written or queued; without --dry-run, submit.sh's two sbatch calls run)\n");
         });
    return;
  }

  // A run directory holds one run: resubmitting the same run resumes it, another is refused.
  nlohmann::json record = run_record(p);
  if (auto old = read_run_file(dir / "run.json")) {
    for (const char* key : {"shards", "pack_args"})
      if (old->doc[key] != record[key])
        throw InputError(fmt::format("{} holds a different run ({}: {} vs {}); pick another --run-dir",
                                     p.run_dir, key, old->doc[key].dump(), record[key].dump()));
    record["submissions"] = old->submissions;
  } else if (fs::exists(dir) && !fs::is_empty(dir)) {
    throw InputError(fmt::format("{} exists and is not a Tilekit run directory", p.run_dir));
  }
  fs::create_directories(dir / "shards");
  fs::create_directories(dir / "logs");
  for (const auto& [name, text] : scripts) write_script(dir / name, text);
  write_file_atomic((dir / "run.json").string(), record.dump(2) + "\n");

  std::string array = sbatch(o.sbatch, {(dir / "pack-array.sbatch").string()});
  std::string merge = sbatch(o.sbatch, {"--dependency=afterok:" + array, (dir / "merge.sbatch").string()});
  auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char when[32];
  std::strftime(when, sizeof when, "%FT%TZ", std::gmtime(&now));
  record["submissions"].push_back({{"array_job", array}, {"merge_job", merge}, {"time", when}});
  write_file_atomic((dir / "run.json").string(), record.dump(2) + "\n");
  emit(ctx,
       {{"run_dir", p.run_dir},
        {"shards", p.shards},
        {"tilekit", p.tilekit},
        {"array_job", array},
        {"merge_job", merge},
        {"submissions", record["submissions"].size()}},
       [&] {
         fmt::print("submitted {} shards to Slurm: array job {}, merge job {} (afterok:{})\n", p.shards,
                    array, merge, array);
         fmt::print("the jobs run {}\nrun directory: {}\nprogress: tilekit cluster status --run-dir {}\n", p.tilekit,
                    p.run_dir, shell_quote(p.run_dir));
       });
}

// Progress of shard i of n from its checkpoint: subproblem k belongs to shard k mod n
// (solver/parallel_search.hpp); counts are those of finished subproblems plus the part of the
// in-flight ones explored so far. null (with a reason) when the file cannot be read.
struct StatusArgs {
  std::string run_dir;
};

nlohmann::json checkpoint_progress(const fs::path& file, int i, int n) {
  SearchState st;
  try {
    st = read_checkpoint(file.string());
  } catch (const std::exception& e) {
    return {{"error", e.what()}};
  }
  std::uint64_t mine = 0, done = 0;
  for (std::uint64_t k = std::uint64_t(i); k < st.subproblem_count; k += std::uint64_t(n)) {
    ++mine;
    if (k < st.finished.size() && st.finished[k]) ++done;
  }
  SearchCounters c = st.finished_counts;
  for (const auto& f : st.in_flight) c += f.counted;
  return {{"subproblems", mine},     {"subproblems_done", done},
          {"solutions", c.solutions}, {"nodes", c.nodes},
          {"seconds", st.seconds},    {"fraction", mine ? double(done) / double(mine) : 0.0}};
}

// Per-shard state from the files the job script writes (pack-array.body.sh).
nlohmann::json shard_status(const fs::path& shards, int i, int n, bool pack) {
  auto f = [&](const char* ext) { return shards / fmt::format("shard-{}{}", i, ext); };
  nlohmann::json s = {{"shard", i}};
  int attempts = 0, interrupted = 0;
  nlohmann::json last_exit = nullptr;
  std::ifstream in(f(".attempts"));
  for (std::string line; std::getline(in, line);) {
    try {
      const auto a = parse_json_input(line, "attempt");
      const auto exit = a.is_object() ? a.find("exit") : a.end();
      if (exit == a.end() || !exit->is_number_integer()) continue;  // not an attempt line
      ++attempts;
      if (*exit == 3) ++interrupted;
      last_exit = *exit;
    } catch (const InputError&) {  // a line cut short by a kill: skip it
    }
  }
  s["attempts"] = attempts;
  s["checkpointed_exits"] = interrupted;
  s["last_exit"] = last_exit;
  auto done = read_shard_json(f(".done.json"));
  bool has_ckpt = fs::exists(f(".ckpt"));
  s["state"] = done ? "done" : has_ckpt ? "checkpointed" : attempts || fs::exists(f(".sqlite")) ? "started" : "pending";
  s["solutions"] = member(done, "solutions", &nlohmann::json::is_number_unsigned);
  s["complete"] = member(done, "complete", &nlohmann::json::is_boolean);
  if (has_ckpt) {
    auto age = fs::file_time_type::clock::now() - fs::last_write_time(f(".ckpt"));
    s["checkpoint_age_seconds"] = std::chrono::duration_cast<std::chrono::seconds>(age).count();
    s["progress"] = pack ? checkpoint_progress(f(".ckpt"), i, n)
                         : nlohmann::json{{"error", "an enumerate checkpoint (progress lines: the shard's log)"}};
  } else {
    s["checkpoint_age_seconds"] = nullptr;
    s["progress"] = nullptr;
  }
  return s;
}

void run_status(const StatusArgs& a, const Context& ctx) {
  fs::path dir = fs::absolute(a.run_dir);
  auto run = read_run_file(dir / "run.json");
  if (!run) throw NotFound(fmt::format("{}: no run.json (not a `tilekit cluster submit` run directory)", dir.string()));
  const int shards = run->shards;
  nlohmann::json list = nlohmann::json::array();
  std::map<std::string, int> counts;
  std::uint64_t sum = 0;
  for (int i = 0; i < shards; ++i) {
    auto s = shard_status(dir / "shards", i, shards, run->pack);
    counts[s["state"].get<std::string>()]++;
    if (s["solutions"].is_number()) sum += s["solutions"].get<std::uint64_t>();
    list.push_back(s);
  }
  auto merged = read_shard_json(dir / "merged.json");
  nlohmann::json j = {{"run_dir", dir.string()},
                      {"shards", shards},
                      {"pack_args", run->pack_args},
                      {"done", counts["done"]},
                      {"checkpointed", counts["checkpointed"]},
                      {"started", counts["started"]},
                      {"pending", counts["pending"]},
                      {"solutions_in_done_shards", sum},
                      // From merged.json (`db stats`): solutions stored, each once, and how many
                      // of them differ up to symmetry.
                      {"merged_solutions", member(merged, "solutions", &nlohmann::json::is_number_unsigned)},
                      {"merged_orbits", member(merged, "distinct_solutions", &nlohmann::json::is_number_unsigned)},
                      {"submissions", run->submissions},
                      {"per_shard", list}};
  emit(ctx, j, [&] {
    std::string args;
    for (const auto& a : run->pack_args) args += " " + a;
    fmt::print("run {} (tilekit pack{}), {} shards: {} done, {} checkpointed, {} started, {} pending\n",
               dir.string(), args, shards, counts["done"], counts["checkpointed"], counts["started"],
               counts["pending"]);
    fmt::print("{:>5}  {:<12} {:>8} {:>9} {:>9} {:>12}  {}\n", "shard", "state", "attempts", "exit 3s",
               "last exit", "solutions", "checkpoint (progress so far)");
    for (const auto& s : list) {
      std::string ck = "-";
      if (!s["checkpoint_age_seconds"].is_null()) {
        const auto& p = s["progress"];
        ck = p.contains("error")
                 ? fmt::format("unreadable: {}", p["error"].get<std::string>())
                 : fmt::format("{}/{} subproblems ({:.1f}%), {} solutions, {} nodes; written {} s ago",
                               p["subproblems_done"].get<std::uint64_t>(), p["subproblems"].get<std::uint64_t>(),
                               100 * p["fraction"].get<double>(), p["solutions"].get<std::uint64_t>(),
                               p["nodes"].get<std::uint64_t>(), s["checkpoint_age_seconds"].get<long>());
      }
      fmt::print("{:>5}  {:<12} {:>8} {:>9} {:>9} {:>12}  {}\n", s["shard"].get<int>(), s["state"].get<std::string>(),
                 s["attempts"].get<int>(), s["checkpointed_exits"].get<int>(),
                 s["last_exit"].is_null() ? "-" : s["last_exit"].dump(),
                 s["solutions"].is_null() ? "-" : s["solutions"].dump(), ck);
    }
    fmt::print("solutions in done shards: {}\n", sum);
    if (j["merged_solutions"].is_null())
      fmt::print("merged: not yet (the merge job runs when every shard ended with exit 0)\n");
    else
      fmt::print("merged: {} distinct solutions ({} up to symmetry) in {}\n", j["merged_solutions"].dump(),
                 j["merged_orbits"].dump(), (dir / "merged.sqlite").string());
  });
}

void add_submit(CLI::App& cluster, Context& ctx) {
  auto* cmd = cluster.add_subcommand(
      "submit",
      "Write the job-array, merge and submit scripts for a sharded `tilekit pack` and queue them with sbatch");
  auto a = std::make_shared<SubmitArgs>();
  cmd->add_option("--command", a->command, "The shard command: pack (default) or enumerate (aperiodic enumerate)");
  cmd->add_option("--kind", a->kind, "pack: tile kind, wang, corner or window (de Bruijn tori: --pack-arg=--window=KxL --pack-arg=--size=RxS; required)");
  cmd->add_option("--colors", a->colors, "pack: number of colours C (required)");
  cmd->add_option("--method", a->method, "Passed to pack: auto, search or construct");
  cmd->add_option("--mode", a->mode, "Passed to pack: first, count or all")->capture_default_str();
  cmd->add_option("--seed", a->seed, "Passed to pack");
  cmd->add_option("--pack-arg", a->pack_extra,
                  "Another argument of the shard command for every shard, e.g. --pack-arg=--max-depth=3 (repeatable)");
  cmd->add_option("--shards", a->plan.shards, "Number of shards = array tasks")->required();
  cmd->add_option("--cpus-per-task", a->plan.cpus_per_task, "Cores per shard (OMP_NUM_THREADS)")->capture_default_str();
  cmd->add_option("--time", a->plan.time, "Wall time of one attempt (Slurm format: M, H:M:S, D-H:M:S)")
      ->capture_default_str();
  cmd->add_option("--partition", a->plan.partition, "Slurm partition (default: the cluster's)");
  cmd->add_option("--checkpoint-every", a->plan.checkpoint_every, "Seconds between checkpoints")->capture_default_str();
  cmd->add_option("--signal-seconds", a->signal_seconds,
                  "USR1 this many seconds before the wall-time limit (default: 120, at most half the limit)");
  cmd->add_option("--max-requeues", a->plan.max_requeues, "Most requeues of one shard task")->capture_default_str();
  cmd->add_option("--merge-time", a->merge_time, "Wall time of the merge job (default: --time)");
  cmd->add_option("--run-dir", a->run_dir,
                  "Run directory on the shared filesystem (default: ./tilekit-run-KINDC-MODE)");
  cmd->add_option("--job-name", a->job_name, "Slurm job name (default: tk-KINDC)");
  cmd->add_option("--tilekit", a->tilekit,
                  "The tilekit binary the jobs run (default: `tilekit` on PATH, else this one)");
  cmd->add_option("--sbatch-arg", a->plan.sbatch_args, "Another #SBATCH directive, e.g. --account=NAME (repeatable)");
  cmd->add_option("--sbatch", a->sbatch, "The sbatch command")->capture_default_str();
  cmd->add_flag("--dry-run", a->dry_run, "Print the scripts; write and queue nothing");
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_submit(*a, ctx); });
}

void add_status(CLI::App& cluster, Context& ctx) {
  auto* cmd = cluster.add_subcommand("status", "Per-shard progress of a run, read from its run directory");
  auto a = std::make_shared<StatusArgs>();
  cmd->add_option("--run-dir", a->run_dir, "The run directory given to submit")->required();
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_status(*a, ctx); });
}

}  // namespace

void add_cluster_commands(CLI::App& app, Context& ctx) {
  auto* cluster = app.add_subcommand("cluster", "Run a sharded `tilekit pack` as a Slurm job array");
  cluster->require_subcommand(1);
  add_submit(*cluster, ctx);
  add_status(*cluster, ctx);
}

}  // namespace tilekit::cli
