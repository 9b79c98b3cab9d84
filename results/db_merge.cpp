// `db merge`: folds shard databases (or JSON exports) into one, in a single transaction.
// Every input is opened read-only and checked (or parsed) before anything is written, so a
// bad input leaves both it and the target untouched. Rows are matched by their natural keys
// (run uid, tile set name + content hash, conversion triple, solution hash), which makes a
// second merge of the same input a no-op.
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>

#include "results/db_rows.hpp"
#include "results/results_db.hpp"
#include "base/error.hpp"
#include "base/input.hpp"
#include "base/json_input.hpp"
#include "base/progress.hpp"

namespace tilekit {

using sqlitedb::Statement;

namespace {

// Inserts records into the target, remapping the source's ids to the target's.
class MergeSink {
 public:
  MergeSink(sqlite3* db, bool distinct_orbits, MergeReport& report, ProgressReporter& progress)
      : db_(db),
        run_ins_(db,
                 "INSERT OR IGNORE INTO runs(uid, command, params, status, solutions, orbits, nodes, seconds, threads, "
                 "host, version, started_at, finished_at) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, "
                 "COALESCE(NULLIF(?12, ''), strftime('%Y-%m-%dT%H:%M:%fZ', 'now')), NULLIF(?13, ''))"),
        run_id_(db, "SELECT id FROM runs WHERE uid = ?1"),
        set_ins_(db,
                 "INSERT OR IGNORE INTO tilesets(name, kind, tiles, colors, content_hash, source, text, created_at) "
                 "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, COALESCE(NULLIF(?8, ''), strftime('%Y-%m-%dT%H:%M:%fZ', "
                 "'now')))"),
        set_id_(db, "SELECT id FROM tilesets WHERE name = ?1 AND content_hash = ?2"),
        conv_ins_(db,
                  "INSERT OR IGNORE INTO conversions(source_set, method, result_set, tiles_before, tiles_after, "
                  "colors, soundness, details, created_at) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, "
                  "COALESCE(NULLIF(?9, ''), strftime('%Y-%m-%dT%H:%M:%fZ', 'now')))"),
        sol_ins_(db, distinct_orbits ? distinct_insert() : std::string(dbrows::kInsertSolution)),
        report_(report),
        progress_(progress) {}

  void begin_source() {
    runs_.clear();
    sets_.clear();
  }

  void run(const RunRecord& r) {
    run_ins_.bind(1, r.uid)
        .bind(2, r.command)
        .bind(3, r.params.dump())
        .bind(4, r.status)
        .bind(5, std::int64_t(r.solutions));
    if (r.orbits) run_ins_.bind(6, std::int64_t(*r.orbits));
    run_ins_.bind(7, std::int64_t(r.nodes))
        .bind(8, r.seconds)
        .bind(9, std::int64_t(r.threads))
        .bind(10, r.host)
        .bind(11, r.version)
        .bind(12, r.started_at)
        .bind(13, r.finished_at);
    run_ins_.run();
    report_.runs += std::uint64_t(sqlite3_changes(db_));
    run_id_.bind(1, r.uid);
    if (run_id_.step()) runs_[r.id] = run_id_.int64(0);
    run_id_.reset();
  }

  void tileset(const TilesetRecord& t) {
    set_ins_.bind(1, t.name)
        .bind(2, t.kind)
        .bind(3, std::int64_t(t.tiles))
        .bind(4, std::int64_t(t.colours))
        .bind(5, t.content_hash)
        .bind(6, t.source)
        .bind(7, t.text)
        .bind(8, t.created_at)
        .run();
    report_.tilesets += std::uint64_t(sqlite3_changes(db_));
    set_id_.bind(1, t.name).bind(2, t.content_hash);
    if (set_id_.step()) sets_[t.id] = set_id_.int64(0);
    set_id_.reset();
  }

  void conversion(const ConversionRecord& c, const std::string& origin) {
    auto src = sets_.find(c.source_set), res = sets_.find(c.result_set);
    if (src == sets_.end() || res == sets_.end())
      throw InputError(fmt::format("{}: conversion {} refers to a tile set that is not in the input", origin, c.id));
    conv_ins_.bind(1, src->second)
        .bind(2, c.method)
        .bind(3, res->second)
        .bind(4, std::int64_t(c.tiles_before))
        .bind(5, std::int64_t(c.tiles_after))
        .bind(6, std::int64_t(c.colours))
        .bind(7, c.soundness)
        .bind(8, c.details.dump())
        .bind(9, c.created_at)
        .run();
    report_.conversions += std::uint64_t(sqlite3_changes(db_));
  }

  void solution(SolutionRecord s) {
    auto it = runs_.find(s.run_id);
    s.run_id = it == runs_.end() ? 0 : it->second;
    dbrows::bind_solution(sol_ins_, s, solution_hash(s.tiling));
    sol_ins_.run();
    report_.solutions += std::uint64_t(sqlite3_changes(db_));
    ++report_.solutions_seen;
    progress_.add(1);
  }

 private:
  // Keeps one solution per orbit: skips a row whose canonical hash is already stored.
  static std::string distinct_insert() {
    std::string sql = dbrows::kInsertSolution;
    const auto at = sql.find("VALUES (");
    std::string head = sql.substr(0, at), values = sql.substr(at + 8);
    values.pop_back();  // the closing parenthesis of VALUES (...)
    return head + "SELECT " + values +
           " WHERE ?11 = '' OR NOT EXISTS (SELECT 1 FROM solutions WHERE canonical_hash = ?11)";
  }

  sqlite3* db_;
  Statement run_ins_, run_id_, set_ins_, set_id_, conv_ins_, sol_ins_;
  MergeReport& report_;
  ProgressReporter& progress_;
  std::map<std::int64_t, std::int64_t> runs_, sets_;
};

// One input: a Tilekit database opened read-only, or a JSON export read and checked whole
// (every row converted to a record, every reference resolved) before the target is touched.
struct ExportRows {
  std::vector<RunRecord> runs;
  std::vector<TilesetRecord> tilesets;
  std::vector<ConversionRecord> conversions;
  std::vector<SolutionRecord> solutions;
};
struct Input {
  std::string path;
  std::unique_ptr<ResultsDb> db;
  ExportRows rows;
};

template <class Record, class Convert>
std::vector<Record> export_section(const JsonIn& doc, const char* key, Convert convert) {
  const JsonIn section = doc.at(key);
  const std::size_t n = section.array();
  std::vector<Record> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) out.push_back(convert(section[i]));
  return out;
}

ExportRows read_export(std::string_view text, const std::string& origin) {
  const nlohmann::json doc = parse_json_input(text, origin);
  const JsonIn j(doc, origin);
  if (!j.has("tilekit_results")) throw j.error("not a Tilekit export (JSON without \"tilekit_results\")");
  j.at("tilekit_results").integer(1, ResultsDb::kSchemaVersion);
  ExportRows rows;
  rows.runs = export_section<RunRecord>(j, "runs", dbrows::run_from_json);
  rows.tilesets = export_section<TilesetRecord>(j, "tilesets", dbrows::tileset_from_json);
  rows.conversions = export_section<ConversionRecord>(j, "conversions", dbrows::conversion_from_json);
  rows.solutions = export_section<SolutionRecord>(j, "solutions", dbrows::solution_from_json);
  std::set<std::int64_t> set_ids;
  for (const auto& t : rows.tilesets) set_ids.insert(t.id);
  for (std::size_t i = 0; i < rows.conversions.size(); ++i)
    for (std::int64_t ref : {rows.conversions[i].source_set, rows.conversions[i].result_set})
      if (!set_ids.count(ref))
        throw InputError(
            fmt::format("{}: conversions[{}]: refers to tile set {}, which is not in the export", origin, i, ref));
  return rows;
}

Input open_input(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(fmt::format("{}: no such file to merge", path));
  char first = 0;
  {
    std::ifstream in(path, std::ios::binary);
    in >> std::ws;
    in.get(first);
  }
  Input input{path, nullptr, {}};
  if (first == '{') {
    input.rows = read_export(read_input_file(path, "JSON export"), path);
    return input;
  }
  input.db = std::make_unique<ResultsDb>(path, DbOpenOptions{.create = false, .read_only = true});
  Statement dangling(input.db->handle(),
                     "SELECT id FROM conversions WHERE source_set NOT IN (SELECT id FROM tilesets) OR result_set NOT "
                     "IN (SELECT id FROM tilesets) LIMIT 1");
  if (dangling.step())
    throw InputError(fmt::format("{}: conversion {} refers to a tile set that is not in the database (damaged)", path,
                                 dangling.int64(0)));
  return input;
}

void merge_database(const ResultsDb& src, MergeSink& sink) {
  sqlite3* db = src.handle();
  sqlitedb::exec(db, "BEGIN");  // one snapshot of the input
  {
    Statement runs(db, std::string(dbrows::kSelectRun) + " ORDER BY id");
    while (runs.step()) sink.run(dbrows::read_run(runs));
    Statement sets(db, std::string(dbrows::kSelectTileset) + " ORDER BY id");
    while (sets.step()) sink.tileset(dbrows::read_tileset(sets));
    Statement convs(db, std::string(dbrows::kSelectConversion) + " ORDER BY id");
    while (convs.step()) sink.conversion(dbrows::read_conversion(convs), src.path());
    Statement sols(db, std::string(dbrows::kSelectSolution) + " ORDER BY id");
    while (sols.step()) sink.solution(dbrows::read_solution(sols, true));
  }
  sqlitedb::exec(db, "COMMIT");
}

void merge_export(const Input& in, MergeSink& sink) {
  for (const RunRecord& r : in.rows.runs) sink.run(r);
  for (const TilesetRecord& t : in.rows.tilesets) sink.tileset(t);
  for (const ConversionRecord& c : in.rows.conversions) sink.conversion(c, in.path);
  for (const SolutionRecord& s : in.rows.solutions) sink.solution(s);
}

}  // namespace

void ResultsDb::check_export(std::string_view text, const std::string& origin) { read_export(text, origin); }

void ResultsDb::check_merge_inputs(const std::vector<std::string>& inputs) {
  for (const std::string& p : inputs) open_input(p);
}

MergeReport ResultsDb::merge(const std::vector<std::string>& inputs, bool distinct_orbits, bool progress) {
  if (read_only_) throw InputError(fmt::format("{}: opened read-only, cannot merge into it", path_));
  std::vector<Input> opened;
  for (const std::string& p : inputs) opened.push_back(open_input(p));  // all checks before any write
  std::uint64_t total = 0;
  for (const Input& in : opened) {
    if (in.db) total += in.db->stats().solutions;
    else total += in.rows.solutions.size();
  }
  ProgressReporter reporter(fmt::format("db merge into {}", path_), double(total), progress && total >= 20000);
  reporter.set_detail("solutions read");
  MergeReport report;
  sqlitedb::Transaction tx(db_);
  MergeSink sink(db_, distinct_orbits, report, reporter);
  for (const Input& in : opened) {
    sink.begin_source();
    if (in.db) merge_database(*in.db, sink);
    else merge_export(in, sink);
  }
  tx.commit();
  return report;
}

}  // namespace tilekit
