#pragma once
// The SQLite results store every command writes to. INTERFACE CONTRACT shared by the solver
// front end (`pack`), the aperiodic engine and the `db`/`atlas` commands; the database owner
// may extend it (new members, new columns with defaults) but not change what is here.
//
// Solutions are unique by `solution_hash` (hash of kind, colours, rows, cols, cells), so a
// merge of the same shard twice changes nothing and the 203,520 C=2 Wang packings stay
// 203,520 rows. `canonical_hash` identifies the orbit under the symmetry group (many rows
// may share it).
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "tilesets/tile.hpp"
#include "tilesets/tiling.hpp"

struct sqlite3;

namespace tilekit {

struct RunRecord {
  std::int64_t id = 0;
  std::string command;       // e.g. "pack", "aperiodic verify"
  nlohmann::json params;     // the command's parameters
  std::string status;        // "running", "complete", "incomplete", "interrupted", "failed"
  std::uint64_t solutions = 0, nodes = 0;
  std::optional<std::uint64_t> orbits;
  double seconds = 0;
  int threads = 1;
  std::string host, version, started_at, finished_at;
};

struct SolutionRecord {
  std::int64_t id = 0, run_id = 0;
  Tiling tiling;              // kind, colours, rows, cols, torus, cells
  std::string method;         // "search", "construct", ...
  std::string canonical_hash; // orbit id under symmetry ("" if not computed)
  std::uint64_t orbit_size = 0;
  bool validated = false;
  nlohmann::json group;       // imposed automorphism group, or null
};

class ResultsDb {
 public:
  // Opens or creates (create=true) a Tilekit database and migrates it to the current schema.
  // Throws InputError (exit 2) for a file that is not Tilekit's or is corrupt; such a file is
  // never modified.
  explicit ResultsDb(const std::string& path, bool create = true);
  ~ResultsDb();
  ResultsDb(const ResultsDb&) = delete;
  ResultsDb& operator=(const ResultsDb&) = delete;

  // Per-user default: $TILEKIT_DB, else $XDG_DATA_HOME/tilekit/results.sqlite, else
  // ~/.local/share/tilekit/results.sqlite. The directory is created on first use.
  static std::string default_path();

  std::int64_t begin_run(const RunRecord& run);  // returns the run id
  void finish_run(const RunRecord& run);         // updates status, counts, timings by run.id
  // Returns false if an identical solution (same solution_hash) is already stored.
  bool add_solution(const SolutionRecord& s);
  // Many at once in one transaction; returns how many were new.
  std::size_t add_solutions(const std::vector<SolutionRecord>& batch);
  // Any stored, validated solution for this kind/colours/shape (e.g. a packing for the atlas).
  std::optional<SolutionRecord> find_solution(TileKind kind, std::uint32_t colours, int rows, int cols);

  const std::string& path() const { return path_; }
  sqlite3* handle() const { return db_; }

 private:
  std::string path_;
  sqlite3* db_ = nullptr;
};

// Hash of (kind, colours, rows, cols, torus, cells): 16 hex digits, stable across runs and machines.
std::string solution_hash(const Tiling& t);

}  // namespace tilekit
