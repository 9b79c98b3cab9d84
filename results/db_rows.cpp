#include "results/db_rows.hpp"

#include <fmt/format.h>

#include <limits>

#include "base/error.hpp"
#include "base/json_input.hpp"
#include "base/parallel.hpp"
#include "tilesets/tile_set.hpp"

namespace tilekit::dbrows {

using sqlitedb::Statement;

namespace {
// A JSON column as stored; a damaged one (not JSON, or nested beyond the limit) reads as
// `fallback`, so that one bad row does not hide the others from `db list` or an export.
nlohmann::json stored_json(const std::string& text, nlohmann::json fallback) {
  try {
    return parse_json_input(text, "stored JSON");
  } catch (const InputError&) {
    return fallback;
  }
}
}  // namespace

const char* const kInsertSolution =
    "INSERT OR IGNORE INTO solutions(run_id, kind, colors, vertical_colors, rows, cols, torus, cells, method, "
    "solution_hash, canonical_hash, orbit_size, validated, group_json, created_at) VALUES (?1, ?2, ?3, ?4, ?5, ?6, "
    "?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14, COALESCE(NULLIF(?15, ''), strftime('%Y-%m-%dT%H:%M:%fZ', 'now')))";

void bind_solution(Statement& s, const SolutionRecord& r, const std::string& hash) {
  const Tiling& t = r.tiling;
  if (t.cells.size() != std::size_t(t.rows) * std::size_t(t.cols))
    throw InputError(fmt::format("solution has {} cells for a {}x{} grid", t.cells.size(), t.rows, t.cols));
  if (r.run_id > 0) s.bind(1, r.run_id);
  s.bind(2, std::string(kind_name(t.kind)))
      .bind(3, std::int64_t(t.colours))
      .bind(4, std::int64_t(t.kind == TileKind::Wang && t.cv() != t.ch() ? t.cv() : 0))
      .bind(5, std::int64_t(t.rows))
      .bind(6, std::int64_t(t.cols))
      .bind(7, std::int64_t(t.torus ? 1 : 0))
      .bind(8, sqlitedb::cells_to_text(t.cells))
      .bind(9, r.method)
      .bind(10, hash)
      .bind(11, r.canonical_hash)
      .bind(12, std::int64_t(r.orbit_size))
      .bind(13, std::int64_t(r.validated ? 1 : 0));
  if (!r.group.is_null()) s.bind(14, r.group.dump());
  s.bind(15, r.created_at);
}

#define TK_SOLUTION_COLUMNS                                                                                        \
  "id, COALESCE(run_id, 0), kind, colors, vertical_colors, rows, cols, torus, method, solution_hash, "            \
  "canonical_hash, orbit_size, validated, group_json, created_at"
const char* const kSelectSolution = "SELECT " TK_SOLUTION_COLUMNS ", cells FROM solutions";
const char* const kSelectSolutionNoCells = "SELECT " TK_SOLUTION_COLUMNS ", '[]' FROM solutions";
#undef TK_SOLUTION_COLUMNS

SolutionRecord read_solution(const Statement& s, bool with_cells) {
  SolutionRecord r;
  r.id = s.int64(0);
  r.run_id = s.int64(1);
  r.tiling.kind = s.text(2) == "wang" ? TileKind::Wang : TileKind::Corner;
  r.tiling.colours = std::uint32_t(s.int64(3));
  r.tiling.vertical_colours = std::uint32_t(s.int64(4));
  r.tiling.rows = int(s.int64(5));
  r.tiling.cols = int(s.int64(6));
  r.tiling.torus = s.int64(7) != 0;
  r.method = s.text(8);
  r.solution_hash = s.text(9);
  r.canonical_hash = s.text(10);
  r.orbit_size = std::uint64_t(s.int64(11));
  r.validated = s.int64(12) != 0;
  if (!s.is_null(13)) r.group = stored_json(s.text(13), nullptr);
  r.created_at = s.text(14);
  if (with_cells) {
    r.tiling.cells = sqlitedb::cells_from_text(s.text(15));
    if (r.tiling.cells.size() != std::size_t(r.tiling.rows) * std::size_t(r.tiling.cols))
      throw InputError(fmt::format("solution {}: {} stored cells for a {}x{} grid (damaged row)", r.id,
                                   r.tiling.cells.size(), r.tiling.rows, r.tiling.cols));
  }
  return r;
}

const char* const kSelectRun =
    "SELECT id, uid, command, params, status, solutions, orbits, nodes, seconds, threads, host, version, "
    "started_at, COALESCE(finished_at, '') FROM runs";

RunRecord read_run(const Statement& s) {
  RunRecord r;
  r.id = s.int64(0);
  r.uid = s.text(1);
  r.command = s.text(2);
  r.params = stored_json(s.text(3), nlohmann::json::object());
  r.status = s.text(4);
  r.solutions = std::uint64_t(s.int64(5));
  if (!s.is_null(6)) r.orbits = std::uint64_t(s.int64(6));
  r.nodes = std::uint64_t(s.int64(7));
  r.seconds = s.real(8);
  r.threads = int(s.int64(9));
  r.host = s.text(10);
  r.version = s.text(11);
  r.started_at = s.text(12);
  r.finished_at = s.text(13);
  return r;
}

const char* const kSelectTileset =
    "SELECT id, name, kind, tiles, colors, content_hash, source, text, created_at FROM tilesets";

TilesetRecord read_tileset(const Statement& s) {
  TilesetRecord r;
  r.id = s.int64(0);
  r.name = s.text(1);
  r.kind = s.text(2);
  r.tiles = std::uint64_t(s.int64(3));
  r.colours = std::uint32_t(s.int64(4));
  r.content_hash = s.text(5);
  r.source = s.text(6);
  r.text = s.text(7);
  r.created_at = s.text(8);
  return r;
}

const char* const kSelectConversion =
    "SELECT id, source_set, method, result_set, tiles_before, tiles_after, colors, soundness, details, created_at "
    "FROM conversions";

ConversionRecord read_conversion(const Statement& s) {
  ConversionRecord r;
  r.id = s.int64(0);
  r.source_set = s.int64(1);
  r.method = s.text(2);
  r.result_set = s.int64(3);
  r.tiles_before = std::uint64_t(s.int64(4));
  r.tiles_after = std::uint64_t(s.int64(5));
  r.colours = std::uint32_t(s.int64(6));
  r.soundness = s.text(7);
  r.details = stored_json(s.text(8), nlohmann::json::object());
  r.created_at = s.text(9);
  return r;
}

nlohmann::json to_json(const RunRecord& r) {
  return {{"id", r.id},
          {"uid", r.uid},
          {"command", r.command},
          {"params", r.params},
          {"status", r.status},
          {"solutions", r.solutions},
          {"orbits", r.orbits ? nlohmann::json(*r.orbits) : nlohmann::json(nullptr)},
          {"nodes", r.nodes},
          {"seconds", r.seconds},
          {"threads", r.threads},
          {"host", r.host},
          {"version", r.version},
          {"started_at", r.started_at},
          {"finished_at", r.finished_at.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.finished_at)}};
}

// The tiling part is the tiling file format (tilesets/tile_grid.hpp), so `db show ID --json`
// output can be given to `tilekit check`.
nlohmann::json to_json(const SolutionRecord& r, bool with_cells) {
  nlohmann::json j;
  if (with_cells) {
    j = tiling_to_json(r.tiling);
  } else {
    j = {{"kind", std::string(kind_name(r.tiling.kind))},
         {"colors", r.tiling.colours},
         {"rows", r.tiling.rows},
         {"cols", r.tiling.cols},
         {"torus", r.tiling.torus}};
    if (r.tiling.kind == TileKind::Wang && r.tiling.cv() != r.tiling.ch()) {
      j["horizontal_colors"] = r.tiling.ch();
      j["vertical_colors"] = r.tiling.cv();
    }
  }
  j["id"] = r.id;
  j["run_id"] = r.run_id > 0 ? nlohmann::json(r.run_id) : nlohmann::json(nullptr);
  j["method"] = r.method;
  j["solution_hash"] = r.solution_hash;
  j["canonical_hash"] = r.canonical_hash;
  j["orbit_size"] = r.orbit_size;
  j["validated"] = r.validated;
  j["group"] = r.group;
  j["created_at"] = r.created_at;
  return j;
}

nlohmann::json to_json(const TilesetRecord& r) {
  return {{"id", r.id},         {"name", r.name},
          {"kind", r.kind},     {"tiles", r.tiles},
          {"colors", r.colours}, {"content_hash", r.content_hash},
          {"source", r.source}, {"text", r.text},
          {"created_at", r.created_at}};
}

nlohmann::json to_json(const ConversionRecord& r) {
  return {{"id", r.id},
          {"source_set", r.source_set},
          {"method", r.method},
          {"result_set", r.result_set},
          {"tiles_before", r.tiles_before},
          {"tiles_after", r.tiles_after},
          {"colors", r.colours},
          {"soundness", r.soundness},
          {"details", r.details},
          {"created_at", r.created_at}};
}

// Rows of a JSON export (`db merge OUT export.json`): every field type- and range-checked,
// every message naming the file and the JSON path (e.g. "x.json: solutions[3].orbit_size: ...").
namespace {
constexpr std::int64_t kMaxId = std::numeric_limits<std::int64_t>::max();
constexpr std::uint64_t kMaxCount = std::uint64_t(std::numeric_limits<std::int64_t>::max());  // SQLite integers
}  // namespace

RunRecord run_from_json(const JsonIn& j) {
  RunRecord r;
  r.id = j.integer_or("id", 0, 0, kMaxId);
  r.uid = j.at("uid").string(256);
  if (r.uid.empty()) throw j.at("uid").error("empty run uid");
  r.command = j.at("command").string();
  if (auto p = j.find("params")) {
    p->object();
    r.params = p->raw();
  } else {
    r.params = nlohmann::json::object();
  }
  r.status = j.string_or("status", "running");
  r.solutions = j.unsigned_or("solutions", 0, kMaxCount);
  if (auto o = j.find("orbits")) r.orbits = o->unsigned_integer(kMaxCount);
  r.nodes = j.unsigned_or("nodes", 0, kMaxCount);
  r.seconds = j.number_or("seconds", 0, 0, 1e15);
  r.threads = int(j.integer_or("threads", 1, 0, kMaxThreads));
  r.host = j.string_or("host", "");
  r.version = j.string_or("version", "");
  r.started_at = j.string_or("started_at", "");
  r.finished_at = j.string_or("finished_at", "");
  return r;
}

SolutionRecord solution_from_json(const JsonIn& j) {
  SolutionRecord r;
  r.tiling = tiling_from_json(j);
  r.id = j.integer_or("id", 0, 0, kMaxId);
  r.run_id = j.integer_or("run_id", 0, 0, kMaxId);
  r.method = j.string_or("method", "");
  r.solution_hash = j.string_or("solution_hash", "");
  r.canonical_hash = j.string_or("canonical_hash", "");
  r.orbit_size = j.unsigned_or("orbit_size", 0, kMaxCount);
  r.validated = j.boolean_or("validated", false);
  if (auto g = j.find("group")) {
    g->object();
    r.group = g->raw();
  }
  r.created_at = j.string_or("created_at", "");
  return r;
}

TilesetRecord tileset_from_json(const JsonIn& j) {
  TilesetRecord r;
  r.id = j.integer_or("id", 0, 0, kMaxId);
  r.name = j.at("name").string();
  r.kind = j.at("kind").string();
  if (r.kind != "wang" && r.kind != "corner") throw j.at("kind").error("expected \"wang\" or \"corner\"");
  r.tiles = j.unsigned_or("tiles", 0, kMaxTiles);
  r.colours = std::uint32_t(j.integer_or("colors", 0, 0, kMaxTileSetColour + 1));
  r.content_hash = j.at("content_hash").string();
  r.source = j.string_or("source", "");
  r.text = j.string_or("text", "");
  r.created_at = j.string_or("created_at", "");
  return r;
}

ConversionRecord conversion_from_json(const JsonIn& j) {
  ConversionRecord r;
  r.id = j.integer_or("id", 0, 0, kMaxId);
  r.source_set = j.at("source_set").integer(0, kMaxId);
  r.method = j.at("method").string();
  r.result_set = j.at("result_set").integer(0, kMaxId);
  r.tiles_before = j.unsigned_or("tiles_before", 0, kMaxCount);
  r.tiles_after = j.unsigned_or("tiles_after", 0, kMaxCount);
  r.colours = std::uint32_t(j.integer_or("colors", 0, 0, std::numeric_limits<std::uint32_t>::max()));
  r.soundness = j.string_or("soundness", "unknown");
  if (auto d = j.find("details")) {
    d->object();
    r.details = d->raw();
  } else {
    r.details = nlohmann::json::object();
  }
  r.created_at = j.string_or("created_at", "");
  return r;
}

}  // namespace tilekit::dbrows
