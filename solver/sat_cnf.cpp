#include "solver/sat_cnf.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "base/error.hpp"
#include "base/signals.hpp"
#include "tilesets/validator.hpp"

extern char** environ;

namespace tilekit {

void CnfBuilder::clause(std::initializer_list<int> lits) { clause(std::vector<int>(lits)); }

void CnfBuilder::clause(const std::vector<int>& lits) {
  for (int l : lits) fmt::format_to(std::back_inserter(text_), "{} ", l);
  text_ += "0\n";
  ++clauses_;
}

void CnfBuilder::at_most_one(const std::vector<int>& lits) {
  const std::size_t n = lits.size();
  if (n < 2) return;
  if (n <= 6) {
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) clause({-lits[i], -lits[j]});
    return;
  }
  int prev = 0;  // sequential counter (Sinz 2005): s_i = "one of lits[0..i] is true"
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const int s = new_var();
    clause({-lits[i], s});
    if (prev) {
      clause({-prev, s});
      clause({-lits[i], -prev});
    }
    prev = s;
  }
  clause({-lits[n - 1], -prev});
}

std::string CnfBuilder::dimacs() const { return fmt::format("p cnf {} {}\n", variables(), clauses_) + text_; }

bool sat_solver_available() { return std::system("command -v cadical >/dev/null 2>&1") == 0; }

namespace {

// A temporary file that is removed when this goes out of scope.
struct TempCnf {
  std::string path = (std::filesystem::temp_directory_path() / "tilekit-sat-XXXXXX").string();
  TempCnf(const std::string& text) {
    const int fd = ::mkstemp(path.data());
    if (fd < 0) throw InputError("cannot create a temporary CNF file");
    for (std::size_t done = 0; done < text.size();) {
      const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
      if (n <= 0) {
        ::close(fd);
        ::unlink(path.c_str());
        throw InputError("cannot write the temporary CNF file");
      }
      done += std::size_t(n);
    }
    ::close(fd);
  }
  ~TempCnf() { ::unlink(path.c_str()); }
};

}  // namespace

SatRun run_cadical(const CnfBuilder& cnf, double time_limit, std::uint64_t seed, const std::function<bool()>& stop) {
  if (!sat_solver_available()) throw InputError("SAT search needs `cadical` on PATH (Debian package cadical)");
  const auto t0 = std::chrono::steady_clock::now();
  SatRun out;
  TempCnf file(cnf.dimacs());
  std::vector<std::string> args = {"cadical", "-q",
                                   fmt::format("--seed={}", seed % 2000000000ULL)};  // cadical's: not a tilekit flag
  if (time_limit > 0) args.insert(args.end(), {"-t", std::to_string(std::max(1, int(std::ceil(time_limit))))});
  args.push_back(file.path);
  for (const auto& a : args) out.command += (out.command.empty() ? "" : " ") + a;

  int pipe_fd[2];
  if (::pipe(pipe_fd) != 0) throw InputError("cannot create a pipe for cadical");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fd[1], STDOUT_FILENO);
  posix_spawn_file_actions_addclose(&actions, pipe_fd[0]);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int rc = ::posix_spawnp(&pid, "cadical", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipe_fd[1]);
  if (rc != 0) {
    ::close(pipe_fd[0]);
    throw InputError("cannot start cadical");
  }
  std::string output;
  char buf[1 << 16];
  for (;;) {
    pollfd p{pipe_fd[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, 20);
    if (ready > 0) {
      const ssize_t n = ::read(pipe_fd[0], buf, sizeof buf);
      if (n <= 0) break;  // end of output: cadical finished
      output.append(buf, std::size_t(n));
    } else if (stop && stop()) {
      ::kill(pid, SIGTERM);
      out.stopped = true;
      break;
    }
  }
  ::close(pipe_fd[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (!out.stopped) {
    std::istringstream in(output);
    std::string line;
    out.value.assign(std::size_t(cnf.variables()) + 1, 0);
    std::size_t assigned = 0;
    while (std::getline(in, line)) {
      if (line.rfind("s SATISFIABLE", 0) == 0) out.status = SatRun::Status::Satisfiable;
      else if (line.rfind("s UNSATISFIABLE", 0) == 0) out.status = SatRun::Status::Unsatisfiable;
      else if (line.rfind("v ", 0) == 0) {
        std::istringstream ls(line.substr(2));
        long l;
        while (ls >> l)
          if (l != 0 && std::size_t(std::labs(l)) < out.value.size()) {
            out.value[std::size_t(std::labs(l))] = l > 0;
            ++assigned;
          }
      }
    }
    if (out.status == SatRun::Status::Satisfiable && assigned < cnf.variables())
      out.status = SatRun::Status::Unknown;  // incomplete model output
  }
  if (out.status != SatRun::Status::Satisfiable) out.value.clear();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

SearchResult solve_by_sat(const TilingProblem& problem, const SearchOptions& o, const std::string& fingerprint,
                          const SatNames& names, const std::function<const CnfBuilder&()>& build,
                          const std::function<Tiling(const std::vector<char>&)>& decode) {
  if (o.mode != SearchMode::First)
    throw RequestError("formulation",
                       fmt::format("`formulation` sat finds one {}: use it with `mode` first", names.finds));
  if (o.run.shard.count != 1) throw RequestError("formulation", "`formulation` sat runs as one job: drop `shard`");
  if (o.resume_state && o.resume_state->fingerprint != fingerprint)
    throw InputError("checkpoint does not match this search (different problem, lift, seed or formulation)");
  const double prior = o.resume_state ? o.resume_state->seconds : 0;
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  SearchResult res;
  res.formulation = "sat";
  res.ordering = "cadical";
  res.threads = 1;
  res.fingerprint = fingerprint;
  const CnfBuilder& cnf = build();
  const Deadline deadline(o.run.time_limit, t0);
  StopToken token;
  auto stop = [&] { return o.run.cancelled() || poll_stop(token, deadline, o.run.catch_signals); };
  SatRun run = run_cadical(cnf, deadline.limited() ? std::max(1.0, deadline.seconds_left()) : 0, o.run.seed, stop);
  if (run.status == SatRun::Status::Satisfiable) {
    Tiling a = decode(run.value);
    ValidationReport rep = validate(a, &problem.set);
    if (!rep.packing)
      throw std::logic_error(fmt::format("the {} CNF produced a {} the validator rejects: {}", names.cnf,
                                         names.produced, rep.errors.empty() ? names.invalid : rep.errors.front()));
    if (o.on_solution) o.on_solution(a);
    res.found.push_back(std::move(a));
    res.solutions = 1;
  }
  res.complete = run.status == SatRun::Status::Unsatisfiable;  // the CNF's subspace holds no solution
  res.signal = o.run.catch_signals ? SignalCatcher::caught() : 0;
  res.interrupted = run.stopped && res.signal != 0;
  res.timed_out = run.status == SatRun::Status::Unknown && !res.interrupted;
  res.seconds = elapsed();
  res.total_seconds = prior + res.seconds;
  if (o.save_checkpoint && res.found.empty() && !res.complete) {
    // Nothing of a SAT run survives a kill but its identity and time: a resume starts cadical again.
    SearchState st;
    st.fingerprint = fingerprint;
    st.seconds = res.total_seconds;
    if (o.flush) o.flush();
    o.save_checkpoint(st);
    res.checkpoints = 1;
  }
  return res;
}

}  // namespace tilekit
