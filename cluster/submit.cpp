#include "cluster/submit.hpp"

#include <fmt/format.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "cluster/job_scripts.hpp"
#include "cluster/run_directory.hpp"

namespace tilekit::cluster {
namespace fs = std::filesystem;
namespace {

// Runs `command` through the shell; returns its stdout, or throws with `what` on failure.
std::string run_capture(const std::string& command, const std::string& what) {
  FILE* f = ::popen(command.c_str(), "r");
  if (!f) throw InputError(fmt::format("{}: cannot run '{}'", what, command));
  std::string out;
  char buf[4096];
  while (std::size_t n = std::fread(buf, 1, sizeof buf, f)) out.append(buf, n);
  int status = ::pclose(f);
  int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
  if (code == 127)
    throw NotFound(fmt::format("{}: '{}' not found (not a Slurm host? `dry_run` prints the scripts)", what, command));
  if (code != 0) throw InputError(fmt::format("{}: '{}' failed with exit code {}", what, command, code));
  return out;
}

void write_script(const fs::path& path, const std::string& text) {
  write_file_atomic(path.string(), text);
  fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec, fs::perm_options::add);
}

// The run file to write for `p` in `dir`: a new one, or the one there with its submissions when
// it describes the same run (the same shards and shard arguments).
nlohmann::json resumed_record(const ClusterPlan& p, const fs::path& dir) {
  nlohmann::json record = run_record(p);
  if (auto old = read_run_file(dir / "run.json")) {
    // An MPI run resumes on any number of nodes and ranks (the root merges the ranks' files).
    const auto is_mpi = [](const nlohmann::json& j) { return j.contains("mpi") && !j["mpi"].is_null(); };
    if (is_mpi(old->doc) != is_mpi(record))
      throw InputError(fmt::format("{} holds {} run; pick another `run_dir`", p.run_dir,
                                   is_mpi(old->doc) ? "an MPI" : "a job-array"));
    for (const char* key : {"shards", "pack_args"})
      if (old->doc[key] != record[key])
        throw InputError(fmt::format("{} holds a different run ({}: {} vs {}); pick another `run_dir`", p.run_dir, key,
                                     old->doc[key].dump(), record[key].dump()));
    record["submissions"] = old->submissions;
  } else if (fs::exists(dir) && !fs::is_empty(dir)) {
    throw InputError(fmt::format("{} exists and is not a Tilekit run directory", p.run_dir));
  }
  return record;
}

std::string utc_now() {
  auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char when[32];
  std::strftime(when, sizeof when, "%FT%TZ", &tm);
  return when;
}

}  // namespace

std::string sbatch(const std::string& sbatch_cmd, const std::vector<std::string>& args) {
  std::string cmd = shell_quote(sbatch_cmd) + " --parsable";  // sbatch's: not a tilekit flag
  for (const auto& a : args) cmd += " " + shell_quote(a);
  std::string out = run_capture(cmd, "sbatch");
  std::string id = out.substr(0, out.find_first_of(";\n"));
  if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
    throw InputError(fmt::format("sbatch printed '{}', not a job id", out));
  return id;
}

// A first submission that fails before its array job is queued (sbatch missing or refusing)
// leaves nothing behind: the run directory it made is removed, or, when the directory was there
// (empty) before, what it wrote into it. A later submission of the same run keeps its files.
Submission submit_run(const ClusterPlan& p, const std::string& sbatch_command) {
  const fs::path dir(p.run_dir);
  nlohmann::json record = resumed_record(p, dir);
  std::error_code ec;
  const bool fresh = !fs::exists(dir / "run.json", ec), had_dir = fs::exists(dir, ec);
  std::vector<fs::path> made{dir / "shards", dir / "logs", dir / "run.json"};
  Submission out;
  try {
    fs::create_directories(dir / "shards");
    fs::create_directories(dir / "logs");
    for (const JobScript& s : job_scripts(p)) made.push_back(dir / s.name), write_script(dir / s.name, s.text);
    write_file_atomic((dir / "run.json").string(), record.dump(2) + "\n");
    out.array_job = sbatch(sbatch_command, {(dir / (p.mpi ? "pack-mpi.sbatch" : "pack-array.sbatch")).string()});
  } catch (...) {
    if (fresh && !had_dir) fs::remove_all(dir, ec);
    if (fresh && had_dir)
      for (const fs::path& f : made) fs::remove_all(f, ec);
    throw;
  }
  if (p.mpi) {  // one job, no merge: rank 0 writes the run's one database
    record["submissions"].push_back({{"mpi_job", out.array_job}, {"time", utc_now()}});
    write_file_atomic((dir / "run.json").string(), record.dump(2) + "\n");
    out.submissions = record["submissions"].size();
    return out;
  }
  const std::string after = "--dependency=afterok:" + out.array_job;  // sbatch's: not a tilekit flag
  try {
    out.merge_job = sbatch(sbatch_command, {after, (dir / "merge.sbatch").string()});
  } catch (...) {  // the array job is queued: its run file says so, and the error goes on
    record["submissions"].push_back({{"array_job", out.array_job}, {"merge_job", nullptr}, {"time", utc_now()}});
    write_file_atomic((dir / "run.json").string(), record.dump(2) + "\n");
    throw;
  }
  record["submissions"].push_back({{"array_job", out.array_job}, {"merge_job", out.merge_job}, {"time", utc_now()}});
  write_file_atomic((dir / "run.json").string(), record.dump(2) + "\n");
  out.submissions = record["submissions"].size();
  return out;
}

}  // namespace tilekit::cluster
