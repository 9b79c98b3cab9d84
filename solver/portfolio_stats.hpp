#pragma once
// What the portfolio (portfolio.hpp) learns across runs: per (kind, colours, candidate) the
// slices tried, the successes and the recent times to a success, in a small JSON file that
// orders the next portfolio. Shards of a cluster run each write their own file; merge() adds
// them up (`tilekit pack --portfolio-report --portfolio-stats A --portfolio-stats B --out M`).
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "tilesets/tile.hpp"

namespace tilekit {

struct GroupStats {
  std::uint64_t tries = 0, successes = 0;
  std::vector<double> success_seconds;  // most recent last, at most 64 kept
  double median_seconds() const;        // of successful tries; 0 when none
};

// Per-candidate statistics in a JSON file {"version":1,"groups":{"corner/4/SPEC":{...}}}.
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
  // Candidates ordered for a run: proven ones by expected time to a success, then untried ones in
  // their given order, then tried-but-never-successful ones by fewest tries.
  std::vector<std::string> order(TileKind kind, std::uint32_t colours, const std::vector<std::string>& specs) const;
  // {"groups":[{"kind","colors","group","tries","successes","median_seconds"}...]}
  nlohmann::json report() const;
  void merge(const PortfolioStats& other);  // adds other's counts (shards, or before saving)

 private:
  nlohmann::json groups_ = nlohmann::json::object();
};

}  // namespace tilekit
