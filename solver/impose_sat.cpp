#include "solver/impose_sat.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <unordered_map>

#include "base/error.hpp"

namespace tilekit {
namespace {

struct Cnf {
  int next_var = 1;
  std::uint64_t clauses = 0;
  std::string text;
  void clause(std::initializer_list<int> lits) {
    for (int l : lits) fmt::format_to(std::back_inserter(text), "{} ", l);
    text += "0\n";
    ++clauses;
  }
  void clause(const std::vector<int>& lits) {
    for (int l : lits) fmt::format_to(std::back_inserter(text), "{} ", l);
    text += "0\n";
    ++clauses;
  }
  // At most one of lits: sequential counter (Sinz 2005), 3n clauses, n - 1 auxiliaries.
  void at_most_one(const std::vector<int>& lits) {
    const std::size_t n = lits.size();
    if (n < 2) return;
    if (n <= 6) {
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j) clause({-lits[i], -lits[j]});
      return;
    }
    int prev = 0;
    for (std::size_t i = 0; i + 1 < n; ++i) {
      int s = next_var++;
      clause({-lits[i], s});
      if (prev) {
        clause({-prev, s});
        clause({-lits[i], -prev});
      }
      prev = s;
    }
    clause({-lits[n - 1], -prev});
  }
};

}  // namespace

std::string symmetric_cnf(const FundamentalDomain& m, std::uint64_t* variables, std::uint64_t* clauses) {
  Cnf cnf;
  std::vector<int> first_var(std::size_t(m.num_sites));
  for (int s = 0; s < m.num_sites; ++s) {
    first_var[std::size_t(s)] = cnf.next_var;
    cnf.next_var += int(m.site_colours[std::size_t(s)]);
  }
  auto x = [&](int s, int v) { return first_var[std::size_t(s)] + v; };
  for (int s = 0; s < m.num_sites; ++s) {
    std::vector<int> lits;
    for (int v = 0; v < int(m.site_colours[std::size_t(s)]); ++v) lits.push_back(x(s, v));
    cnf.clause(lits);
    cnf.at_most_one(lits);
  }
  std::unordered_map<std::uint64_t, int> w;  // (cell, orbit) -> variable
  std::vector<std::vector<int>> per_orbit(std::size_t(m.num_orbits));
  for (std::size_t c = 0; c < m.cells.size(); ++c) {
    const auto& slots = m.cells[c];
    std::vector<int> sites;
    for (const auto& sl : slots)
      if (std::find(sites.begin(), sites.end(), sl.site) == sites.end()) sites.push_back(sl.site);
    std::vector<int> val(sites.size(), 0);
    for (;;) {
      std::uint32_t idx = 0;
      for (const auto& sl : slots) {
        int v = val[std::size_t(std::find(sites.begin(), sites.end(), sl.site) - sites.begin())];
        idx += sl.weight * m.perm_tables[std::size_t(sl.perm)][std::size_t(v)];
      }
      std::vector<int> lits;
      for (std::size_t k = 0; k < sites.size(); ++k) lits.push_back(-x(sites[k], val[k]));
      int orbit = m.orbit_of[idx];
      if (orbit >= 0 && m.packing) {
        auto key = std::uint64_t(c) * std::uint64_t(m.num_orbits) + std::uint64_t(orbit);
        auto [it, fresh] = w.try_emplace(key, 0);
        if (fresh) {
          it->second = cnf.next_var++;
          per_orbit[std::size_t(orbit)].push_back(it->second);
        }
        lits.push_back(it->second);
        cnf.clause(lits);
      } else if (orbit < 0) {
        cnf.clause(lits);  // this window is not a tile of the set
      }
      std::size_t k = 0;
      while (k < sites.size() && ++val[k] == int(m.site_colours[std::size_t(sites[k])])) val[k++] = 0;
      if (k == sites.size()) break;
    }
  }
  if (m.packing) {
    // Each orbit on at most one cell, and (redundant, for propagation) on at least one; each
    // cell shows exactly one orbit, so w[cell][.] is exactly the cell's window orbit.
    for (const auto& lits : per_orbit) {
      cnf.at_most_one(lits);
      cnf.clause(lits);
    }
    std::vector<std::vector<int>> per_cell(m.cells.size());
    for (const auto& [key, var] : w) per_cell[std::size_t(key / std::uint64_t(m.num_orbits))].push_back(var);
    for (auto& lits : per_cell) {
      std::sort(lits.begin(), lits.end());
      cnf.at_most_one(lits);
    }
  }
  if (variables) *variables = std::uint64_t(cnf.next_var - 1);
  if (clauses) *clauses = cnf.clauses;
  return fmt::format("p cnf {} {}\n", cnf.next_var - 1, cnf.clauses) + cnf.text;
}

bool sat_solver_available() {
  return std::system("command -v cadical >/dev/null 2>&1") == 0;
}

namespace {

// A temporary file removed when it goes out of scope.
struct TempFile {
  std::string path;
  explicit TempFile(const char* stem) {
    path = (std::filesystem::temp_directory_path() / (std::string(stem) + "-XXXXXX")).string();
    int fd = ::mkstemp(path.data());
    if (fd < 0) throw InputError(fmt::format("cannot create a temporary file {}", path));
    ::close(fd);
  }
  ~TempFile() { ::unlink(path.c_str()); }
};

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream b;
  b << in.rdbuf();
  return b.str();
}

}  // namespace

SatOutcome solve_symmetric_sat(const FundamentalDomain& model, double time_limit, std::uint64_t seed,
                               const std::function<bool()>& stop) {
  if (!sat_solver_available()) throw InputError("the SAT formulation needs `cadical` on PATH (Debian package cadical)");
  const auto t0 = std::chrono::steady_clock::now();
  SatOutcome out;
  TempFile cnf("tilekit-sat"), answer("tilekit-sat-out");
  {
    std::ofstream f(cnf.path, std::ios::binary);
    f << symmetric_cnf(model, &out.variables, &out.clauses);
    if (!f) throw InputError(fmt::format("cannot write the temporary CNF file {}", cnf.path));
  }
  const int limit = std::max(1, int(std::ceil(time_limit)));
  const std::string seed_arg = fmt::format("--seed={}", seed % 2000000000ULL), limit_arg = std::to_string(limit);
  out.solver = fmt::format("cadical -q -t {} {} {}", limit, seed_arg, cnf.path);
  // The solver runs as a child whose stdout goes to a file; this thread polls it, the time limit
  // and `stop` (signals, a portfolio's end), and ends it early when asked.
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, answer.path.c_str(), O_WRONLY | O_TRUNC, 0600);
  std::vector<std::string> args = {"cadical", "-q", "-t", limit_arg, seed_arg, cnf.path};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  int rc = posix_spawnp(&pid, "cadical", &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) throw InputError(fmt::format("cannot run cadical: {}", std::strerror(rc)));
  bool stopped = false;
  for (int status = 0;;) {
    pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == pid || (r < 0 && errno != EINTR)) break;
    double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!stopped && ((stop && stop()) || secs > time_limit + 2)) {
      ::kill(pid, SIGTERM);
      stopped = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::istringstream in(stopped ? std::string() : read_all(answer.path));
  std::string line;
  std::vector<int> lits;
  while (std::getline(in, line)) {
    if (line.rfind("s SATISFIABLE", 0) == 0)
      out.status = SatOutcome::Status::Satisfiable;
    else if (line.rfind("s UNSATISFIABLE", 0) == 0)
      out.status = SatOutcome::Status::Unsatisfiable;
    else if (line.rfind("v ", 0) == 0) {
      std::istringstream ls(line.substr(2));
      int l;
      while (ls >> l)
        if (l > 0) lits.push_back(l);
    }
  }
  if (out.status == SatOutcome::Status::Satisfiable) {
    out.values.assign(std::size_t(model.num_sites), -1);
    int var = 1;
    std::vector<int> owner_site, owner_value;
    for (int s = 0; s < model.num_sites; ++s)
      for (std::uint32_t v = 0; v < model.site_colours[std::size_t(s)]; ++v, ++var) {
        owner_site.push_back(s);
        owner_value.push_back(int(v));
      }
    for (int l : lits)
      if (l < var) out.values[std::size_t(owner_site[std::size_t(l - 1)])] = owner_value[std::size_t(l - 1)];
    for (int v : out.values)
      if (v < 0) out.status = SatOutcome::Status::Unknown;  // incomplete model output
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace tilekit
