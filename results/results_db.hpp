#pragma once
// The SQLite results store every command writes to. A contract shared by `pack`, the aperiodic
// engine, points, texture and the `db`/`atlas` commands, and by the databases already written: it
// may grow (new members, new columns with defaults, through a migration) but what is here keeps
// its meaning, so old databases still open and merge.
//
// Solutions are unique by `solution_hash` (hash of kind, colours, rows, cols, cells), so a
// merge of the same shard twice changes nothing and the 203,520 C=2 Wang packings stay
// 203,520 rows. `canonical_hash` identifies the orbit under the symmetry group (many rows
// may share it).
//
// The schema (tables runs, solutions, tilesets, conversions, tilekit_meta) is documented in
// README.md ("Results database") for people who query it with plain `sqlite3`.
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "tilesets/tile.hpp"
#include "tilesets/tile_grid.hpp"

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
  std::string host, started_at, finished_at;
  std::string version;  // the build that ran it; "" = this one (base/version.hpp version_line())
  // Globally unique id of the run (begin_run() makes one when empty); merges use it so that a
  // run merged twice is stored once.
  std::string uid;
};

struct SolutionRecord {
  std::int64_t id = 0, run_id = 0;
  Tiling tiling;              // kind, colours, rows, cols, torus, cells
  std::string method;         // "search", "construct", ...
  std::string canonical_hash; // orbit id under symmetry ("" if not computed)
  std::uint64_t orbit_size = 0;
  bool validated = false;
  nlohmann::json group;       // imposed automorphism group, or null
  std::string solution_hash;  // filled in when read back (computed on write)
  std::string created_at;     // filled in when read back
};

// A tile set stored for the aperiodic engine (e.g. the source and result of a conversion).
struct TilesetRecord {
  std::int64_t id = 0;
  std::string name, kind;       // kind: "wang" or "corner"
  std::uint64_t tiles = 0;
  std::uint32_t colours = 0;
  std::string content_hash;     // the caller's hash of the tiles (identifies the set)
  std::string source;           // where it came from (paper, conversion, file)
  std::string text;             // the tile-set file text
  std::string created_at;
};

// One aperiodic conversion (thesis ch. 8): tile set -> tile set by a method.
struct ConversionRecord {
  std::int64_t id = 0;
  std::int64_t source_set = 0, result_set = 0;  // tilesets.id
  std::string method;
  std::uint64_t tiles_before = 0, tiles_after = 0;
  std::uint32_t colours = 0;
  std::string soundness;        // e.g. "sound", "unsound", "unknown"
  nlohmann::json details;
  std::string created_at;
};

struct DbStats {
  std::uint64_t runs = 0, solutions = 0, distinct_solutions = 0, tilesets = 0, conversions = 0;
};

// Filters for listing solutions (0 / empty = any).
struct SolutionFilter {
  std::optional<TileKind> kind;
  std::uint32_t colours = 0;
  std::int64_t run_id = 0;
  std::size_t limit = 50, offset = 0;  // limit 0 = no limit
};

struct MergeReport {
  std::uint64_t runs = 0, solutions = 0, tilesets = 0, conversions = 0;  // rows newly added
  std::uint64_t solutions_seen = 0;                                       // rows read from inputs
};

struct DbOpenOptions {
  bool create = true;            // create a missing file (and its directory)
  bool read_only = false;        // never write; an older schema is an error instead of a migration
  bool integrity_check = true;   // PRAGMA integrity_check on open (O(size); lookups may skip it)
  int busy_timeout_ms = 120000;  // a second writer waits this long instead of failing
};

class ResultsDb {
 public:
  static constexpr int kSchemaVersion = 1;
  static constexpr std::int32_t kApplicationId = 0x544B4954;  // "TKIT" (PRAGMA application_id)

  // Opens or creates (create=true) a Tilekit database and migrates it to the current schema.
  // Throws InputError (exit 2) for a file that is not Tilekit's or is corrupt; such a file is
  // never modified.
  explicit ResultsDb(const std::string& path, bool create = true);
  ResultsDb(const std::string& path, const DbOpenOptions& options);
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
  // A whole finished run in one transaction: the run row (run.id is set), its solutions (their
  // run_id is set) and its final counts; a kill leaves all of it or none. Returns the number added.
  std::size_t add_run_with_solutions(RunRecord& run, std::vector<SolutionRecord>& batch);
  // Any stored, validated solution for this kind/colours/shape (e.g. a packing for the atlas).
  std::optional<SolutionRecord> find_solution(TileKind kind, std::uint32_t colours, int rows, int cols);

  // Tile sets and conversions for the aperiodic engine. Both are idempotent: the same
  // (name, content_hash) or (source_set, method, result_set) returns the existing id (a
  // conversion's sizes, soundness and details are updated to the new values).
  std::int64_t add_tileset(const std::string& name, TileKind kind, std::uint64_t tiles, std::uint32_t colours,
                           const std::string& content_hash, const std::string& source, const std::string& text);
  std::int64_t add_conversion(std::int64_t source_set, const std::string& method, std::int64_t result_set,
                              std::uint64_t tiles_before, std::uint64_t tiles_after, std::uint32_t colours,
                              const std::string& soundness, const nlohmann::json& details);

  // Queries (db_query.cpp).
  DbStats stats() const;
  std::optional<RunRecord> run(std::int64_t id) const;
  std::optional<SolutionRecord> solution(std::int64_t id) const;
  std::optional<TilesetRecord> tileset(std::int64_t id) const;
  std::optional<ConversionRecord> conversion(std::int64_t id) const;
  std::vector<RunRecord> list_runs(std::size_t limit = 50, std::size_t offset = 0) const;
  // Without cells unless `with_cells`.
  std::vector<SolutionRecord> list_solutions(const SolutionFilter& f, bool with_cells = false) const;
  std::vector<TilesetRecord> list_tilesets(std::size_t limit = 50, std::size_t offset = 0) const;
  std::vector<ConversionRecord> list_conversions(std::size_t limit = 50, std::size_t offset = 0) const;

  // Export (db_export.cpp): the whole database as one JSON document
  // {"tilekit_results": schema_version, "runs":[...], "tilesets":[...], "conversions":[...],
  // "solutions":[...]}, streamed; or one table as CSV with a header line.
  void export_json(std::ostream& out) const;
  void export_csv(std::ostream& out, const std::string& table) const;

  // Merge (db_merge.cpp): adds every row of each input (a Tilekit database file or a JSON
  // export) that is not already here, in one transaction: all inputs or nothing. Runs are
  // matched by uid, tile sets by (name, content_hash), conversions by (source, method,
  // result), solutions by solution_hash, or by canonical_hash too with `distinct_orbits`.
  // Idempotent. Throws InputError (nothing written) for a foreign or corrupt input.
  // `progress`: report on stderr (base/progress.hpp) when the inputs hold many solutions.
  MergeReport merge(const std::vector<std::string>& inputs, bool distinct_orbits = false, bool progress = false);
  // The checks merge() makes on its inputs, without a target (so a command can refuse bad
  // inputs before it creates the target file).
  static void check_merge_inputs(const std::vector<std::string>& inputs);
  // The checks of one JSON export's text (every row converted and checked), as merge() makes
  // them; for the fuzz harness. Throws InputError naming `origin` and the JSON path.
  static void check_export(std::string_view text, const std::string& origin);

  const std::string& path() const { return path_; }
  sqlite3* handle() const { return db_; }
  bool read_only() const { return read_only_; }

 private:
  void open_connection(bool read_only, int busy_timeout_ms);
  std::size_t insert_solutions(const std::vector<SolutionRecord>& batch);  // inside a transaction
  void migrate();
  std::string path_;
  sqlite3* db_ = nullptr;
  bool read_only_ = false;
};

// Hash of (kind, colours, rows, cols, torus, cells): 16 hex digits, stable across runs and machines.
std::string solution_hash(const Tiling& t);

}  // namespace tilekit
