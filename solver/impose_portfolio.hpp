#pragma once
// The search portfolio of `tilekit pack --method auto|search` (issue 7, DESIGN.md "impose an
// automorphism"): the plain search (solve()) plus candidate imposed groups, run in parallel on
// all threads in time slices that double each round, first found wins. Which groups work is
// learned across runs: per (kind, colours, group) the tries, successes and the median time to a
// success are kept in a small JSON file and order the next portfolio.
#include <atomic>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "solver/impose_solve.hpp"

namespace tilekit {

// The spec the portfolio uses for the plain (unconstrained) search.
inline constexpr const char* kPlainSearch = "plain";

// Candidate groups for the complete packing of `kind` over C colours, all valid (checked with
// ImposedGroup::build), in a default order (largest cyclic groups first):
//   translations of order k (k | C, k > 1) paired with a permutation made of k-cycles, and
//   products of two such generators with commuting permutations (k1 * k2 | C for corner; for
//   Wang also one generator on the horizontal and one on the vertical colours).
std::vector<std::string> candidate_groups(TileKind kind, std::uint32_t colours);

struct GroupStats {
  std::uint64_t tries = 0, successes = 0;
  std::vector<double> success_seconds;  // most recent last, at most 64 kept
  double median_seconds() const;        // of successful tries; 0 when none
};

// Per-group statistics in a JSON file {"version":1,"groups":{"corner/4/SPEC":{...}}}.
class PortfolioStats {
 public:
  // $TILEKIT_PORTFOLIO_STATS, else $XDG_DATA_HOME/tilekit/portfolio-stats.json, else
  // ~/.local/share/tilekit/portfolio-stats.json.
  static std::string default_path();
  // A missing file is empty; a corrupt one throws InputError naming it.
  static PortfolioStats load(const std::string& path);
  // Atomic write (temp file, fsync, rename); creates the directory.
  void save(const std::string& path) const;

  void record(TileKind kind, std::uint32_t colours, const std::string& spec, bool success, double seconds);
  std::optional<GroupStats> find(TileKind kind, std::uint32_t colours, const std::string& spec) const;
  // Candidates ordered for a run: proven groups by median time to success, then untried ones in
  // their given order, then tried-but-never-successful ones by fewest tries.
  std::vector<std::string> order(TileKind kind, std::uint32_t colours, const std::vector<std::string>& specs) const;
  // {"path":..., "groups":[{"kind","colors","group","tries","successes","median_seconds"}...]}
  nlohmann::json report() const;
  void merge(const PortfolioStats& other);  // adds other's counts (used before saving)

 private:
  nlohmann::json groups_ = nlohmann::json::object();
};

struct PortfolioOptions {
  std::string stats_path;           // "" = PortfolioStats::default_path(); "-" = do not persist
  double first_slice = 0.25;        // seconds per candidate in round 0; doubles each round
  // Candidates to use: group specs, "plain" (= solve()), "sat:SPEC" (the group's subspace as CNF
  // for cadical, impose_sat.hpp). Empty = candidate_groups() plus "plain".
  std::vector<std::string> specs;
  bool include_plain = true;        // add the plain search when specs is empty
  const std::atomic<bool>* stop = nullptr;  // external stop (signals): ends the run, nothing found
};

struct PortfolioResult {
  bool found = false;
  std::string spec;                 // winning candidate ("plain" for solve())
  SearchResult result;              // of the winning run (found[0] = the validated packing)
  nlohmann::json group;             // winning group's to_json(), null for the plain search
  std::uint64_t nodes = 0;          // all runs together
  double seconds = 0;
  nlohmann::json runs = nlohmann::json::array();  // per candidate: tries, nodes, seconds, found
};

// Runs the portfolio for the complete packing of `kind` over C colours with options.threads
// workers until a packing is found or options.time_limit (0 = none) passes.
PortfolioResult run_portfolio(TileKind kind, std::uint32_t colours, const SearchOptions& options,
                              const PortfolioOptions& portfolio = {});

}  // namespace tilekit
