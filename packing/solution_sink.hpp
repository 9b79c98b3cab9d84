#pragma once
// Stores the solutions of a pack run in the results database in batches. flush() is what the
// engine calls before each checkpoint, so a checkpoint never covers a solution the database
// lacks; every solution arrives validated (solve() checks each one before emitting it).
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "results/results_db.hpp"
#include "solver/problem.hpp"
#include "solver/symmetry.hpp"

namespace tilekit {

class SolutionSink {
 public:
  SolutionSink(ResultsDb& db, std::int64_t run_id, const TilingProblem& p);
  void add(const Tiling& t);
  void flush();
  std::size_t added() const { return added_; }
  nlohmann::json group;           // the imposed group of the solutions added from now on (null: none)
  std::string method = "search";  // how the solutions added from now on were found
  // Called once, with the first solution, just before it is stored: the command's own file of it
  // (`pack --out`), so that the database is written last and a failed write leaves it without it.
  std::function<void(const Tiling&)> before_first_store;

 private:
  ResultsDb& db_;
  std::int64_t run_id_;
  std::optional<PackingSymmetry> sym_;
  std::vector<SolutionRecord> batch_;
  std::vector<TileIndex> last_normal_;
  std::string last_hash_;
  std::uint64_t last_orbit_ = 0;
  std::size_t added_ = 0;
};

}  // namespace tilekit
