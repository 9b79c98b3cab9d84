// tilekit db list|stats|show ID|export|merge OUT IN...|add FILE...: the results database.
// Reading commands open the database read-only (readers work while a writer runs); with no
// --db they use the per-user default, created on first use.
#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>

#include "base/atomic_file.hpp"
#include "results/db_rows.hpp"
#include "results/results_db.hpp"
#include "cli/command.hpp"
#include "base/error.hpp"
#include "tilesets/tile_set_io.hpp"
#include "tilesets/validator.hpp"

namespace tilekit::cli {

namespace {

struct DbArgs {
  std::string db;  // "" = ResultsDb::default_path()
  std::string path() const { return db.empty() ? ResultsDb::default_path() : db; }
};

void add_db_option(CLI::App* cmd, DbArgs& a) {
  cmd->add_option("--db", a.db, "Results database file (default: $TILEKIT_DB, else the per-user data directory)");
}

// Read-only; a missing default database is created (embedded default), a missing explicit
// one is "not found" (exit 1) rather than silently created from a typo.
std::unique_ptr<ResultsDb> open_for_reading(const DbArgs& a) {
  return std::make_unique<ResultsDb>(a.path(), DbOpenOptions{.create = a.db.empty(), .read_only = true});
}

nlohmann::json stats_json(const DbStats& s) {
  return {{"runs", s.runs},
          {"solutions", s.solutions},
          {"distinct_solutions", s.distinct_solutions},
          {"tilesets", s.tilesets},
          {"conversions", s.conversions}};
}

const std::vector<std::string> kTables = {"solutions", "runs", "tilesets", "conversions"};

struct ListArgs {
  DbArgs database;
  std::string table = "solutions", kind;
  std::uint32_t colours = 0;
  std::int64_t run_id = 0;
  std::size_t limit = 50, offset = 0;
};

void run_list(const ListArgs& a, const Context& ctx) {
  auto db = open_for_reading(a.database);
  nlohmann::json rows = nlohmann::json::array();
  std::vector<std::string> lines;
  if (a.table == "solutions") {
    SolutionFilter f;
    if (!a.kind.empty())
      f.kind = a.kind == "wang" ? TileKind::Wang : a.kind == "window" ? TileKind::Window : TileKind::Corner;
    f.colours = a.colours;
    f.run_id = a.run_id;
    f.limit = a.limit;
    f.offset = a.offset;
    for (const SolutionRecord& s : db->list_solutions(f)) {
      rows.push_back(dbrows::to_json(s, false));
      lines.push_back(fmt::format("{:>6}  {:<6} C={:<3} {}x{}  {:<10} {}  {}{}", s.id, kind_name(s.tiling.kind),
                                  s.tiling.colours, s.tiling.rows, s.tiling.cols, s.method, s.solution_hash,
                                  s.validated ? "validated" : "unvalidated",
                                  s.canonical_hash.empty() ? "" : "  orbit " + s.canonical_hash));
    }
  } else if (a.table == "runs") {
    for (const RunRecord& r : db->list_runs(a.limit, a.offset)) {
      rows.push_back(dbrows::to_json(r));
      lines.push_back(fmt::format("{:>6}  {:<16} {:<11} {} solutions  {:.3f} s  {} threads  {}  {}", r.id, r.command,
                                  r.status, r.solutions, r.seconds, r.threads, r.started_at, r.params.dump()));
    }
  } else if (a.table == "tilesets") {
    for (const TilesetRecord& t : db->list_tilesets(a.limit, a.offset)) {
      rows.push_back(dbrows::to_json(t));
      lines.push_back(fmt::format("{:>6}  {:<28} {:<6} {} tiles  {} colours  {}", t.id, t.name, t.kind, t.tiles,
                                  t.colours, t.source));
    }
  } else {
    for (const ConversionRecord& c : db->list_conversions(a.limit, a.offset)) {
      rows.push_back(dbrows::to_json(c));
      lines.push_back(fmt::format("{:>6}  set {} --{}--> set {}  {} -> {} tiles  {} colours  {}", c.id, c.source_set,
                                  c.method, c.result_set, c.tiles_before, c.tiles_after, c.colours, c.soundness));
    }
  }
  emit(ctx, {{"db", db->path()}, {"table", a.table}, {"rows", rows}}, [&] {
    fmt::print("{} ({}: {} shown)\n", db->path(), a.table, lines.size());
    for (auto& l : lines) fmt::print("{}\n", l);
  });
}

void add_list(CLI::App& db, Context& ctx) {
  auto* cmd = db.add_subcommand("list", "List stored solutions (or runs, tile sets, conversions), newest last");
  auto a = std::make_shared<ListArgs>();
  add_db_option(cmd, a->database);
  cmd->add_option("--table", a->table, "solutions, runs, tilesets or conversions")
      ->check(CLI::IsMember(kTables))
      ->capture_default_str();
  cmd->add_option("--kind", a->kind, "Only solutions of this kind")->check(CLI::IsMember({"wang", "corner", "window"}));
  cmd->add_option("--colors", a->colours, "Only solutions over this many colours");
  cmd->add_option("--run", a->run_id, "Only solutions of this run id");
  cmd->add_option("--limit", a->limit, "At most this many rows (0 = all)")->capture_default_str();
  cmd->add_option("--offset", a->offset, "Skip this many rows");
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_list(*a, ctx); });
}

void run_stats(const DbArgs& a, const Context& ctx) {
  auto db = open_for_reading(a);
  DbStats s = db->stats();
  nlohmann::json j = stats_json(s);
  j["db"] = db->path();
  emit(ctx, j, [&] {
    fmt::print("{}\n  runs: {}\n  solutions: {} ({} distinct up to symmetry)\n  tile sets: {}\n  conversions: {}\n",
               db->path(), s.runs, s.solutions, s.distinct_solutions, s.tilesets, s.conversions);
  });
}

void add_stats(CLI::App& db, Context& ctx) {
  auto* cmd = db.add_subcommand("stats", "Count runs, solutions (and distinct orbits), tile sets, conversions");
  auto a = std::make_shared<DbArgs>();
  add_db_option(cmd, *a);
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_stats(*a, ctx); });
}

struct DbShowArgs {
  DbArgs database;
  std::int64_t id = 0;
  std::string table = "solutions";
};

void run_db_show(const DbShowArgs& a, const Context& ctx) {
  auto db = open_for_reading(a.database);
  auto missing = [&] { return NotFound(fmt::format("{}: no row {} in table {}", db->path(), a.id, a.table)); };
  if (a.table == "solutions") {
    auto s = db->solution(a.id);
    if (!s) throw missing();
    nlohmann::json j = dbrows::to_json(*s, true);
    if (auto r = s->run_id ? db->run(s->run_id) : std::nullopt) j["run"] = dbrows::to_json(*r);
    emit(ctx, j, [&] {
      fmt::print("solution {}: {} C={} {}x{} {} ({}{}), hash {}{}\n", s->id, kind_name(s->tiling.kind),
                 s->tiling.colours, s->tiling.rows, s->tiling.cols, s->tiling.torus ? "torus" : "bounded", s->method,
                 s->validated ? ", validated" : "", s->solution_hash,
                 s->canonical_hash.empty() ? "" : ", orbit " + s->canonical_hash);
      for (int r = 0; r < s->tiling.rows; ++r) {
        for (int c = 0; c < s->tiling.cols; ++c) fmt::print("{}{}", c ? " " : "  ", s->tiling.at(r, c));
        fmt::print("\n");
      }
    });
  } else if (a.table == "runs") {
    auto r = db->run(a.id);
    if (!r) throw missing();
    nlohmann::json j = dbrows::to_json(*r);
    emit(ctx, j, [&] { fmt::print("{}\n", j.dump(2)); });
  } else if (a.table == "tilesets") {
    auto t = db->tileset(a.id);
    if (!t) throw missing();
    nlohmann::json j = dbrows::to_json(*t);
    emit(ctx, j, [&] {
      fmt::print("tile set {}: {} ({} {} tiles, {} colours, {})\n{}", t->id, t->name, t->tiles, t->kind, t->colours,
                 t->source, t->text);
    });
  } else {
    auto c = db->conversion(a.id);
    if (!c) throw missing();
    nlohmann::json j = dbrows::to_json(*c);
    emit(ctx, j, [&] { fmt::print("{}\n", j.dump(2)); });
  }
}

void add_db_show(CLI::App& db, Context& ctx) {
  auto* cmd = db.add_subcommand("show", "Show one stored row by id (a solution unless --table says otherwise)");
  auto a = std::make_shared<DbShowArgs>();
  cmd->add_option("ID", a->id, "Row id (see `tilekit db list`)")->required();
  cmd->add_option("--table", a->table, "solutions, runs, tilesets or conversions")
      ->check(CLI::IsMember(kTables))
      ->capture_default_str();
  add_db_option(cmd, a->database);
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_db_show(*a, ctx); });
}

struct ExportArgs {
  DbArgs database;
  std::string format = "json", table = "solutions", out;
};

void run_export(const ExportArgs& a, const Context& ctx) {
  if (ctx.json && a.format == "csv" && a.out.empty())
    throw InputError("--json with --format csv needs --out FILE (stdout would not be one JSON object)");
  auto db = open_for_reading(a.database);
  if (a.out.empty()) {
    if (a.format == "json")
      db->export_json(std::cout);
    else
      db->export_csv(std::cout, a.table);
    std::cout.flush();
    return;
  }
  std::ostringstream text;
  if (a.format == "json")
    db->export_json(text);
  else
    db->export_csv(text, a.table);
  write_file_atomic(a.out, text.str());
  DbStats s = db->stats();
  nlohmann::json j = stats_json(s);
  j["db"] = db->path();
  j["out"] = a.out;
  j["format"] = a.format;
  if (a.format == "csv") j["table"] = a.table;
  emit(ctx, j, [&] { fmt::print("exported {} ({}) to {}\n", db->path(), a.format == "csv" ? a.table : "all", a.out); });
}

void add_export(CLI::App& db, Context& ctx) {
  auto* cmd = db.add_subcommand("export", "Export the database as one JSON document, or one table as CSV");
  auto a = std::make_shared<ExportArgs>();
  add_db_option(cmd, a->database);
  cmd->add_option("--format", a->format, "json (everything) or csv (one table)")
      ->check(CLI::IsMember({"json", "csv"}))
      ->capture_default_str();
  cmd->add_option("--table", a->table, "Table for CSV: solutions, runs, tilesets or conversions")
      ->check(CLI::IsMember(kTables))
      ->capture_default_str();
  cmd->add_option("--out", a->out, "Write to this file (atomically) instead of stdout");
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_export(*a, ctx); });
}

struct MergeArgs {
  std::string out;
  std::vector<std::string> inputs;
  bool distinct = false, quiet = false;
};

void run_merge(const MergeArgs& a, const Context& ctx) {
  ResultsDb::check_merge_inputs(a.inputs);  // before the target is created
  const bool existed = std::filesystem::exists(a.out);
  std::optional<ResultsDb> db;
  MergeReport r;
  try {
    db.emplace(a.out);
    r = db->merge(a.inputs, a.distinct, !a.quiet);  // one transaction: all or nothing
  } catch (...) {
    db.reset();
    std::error_code ec;
    if (!existed)  // a refused merge leaves no new OUT behind
      for (const char* suffix : {"", "-wal", "-shm", "-journal"}) std::filesystem::remove(a.out + suffix, ec);
    throw;
  }
  const ResultsDb& target = *db;
  DbStats s = target.stats();
  nlohmann::json j = {
      {"db", target.path()},
      {"inputs", a.inputs},
      {"added",
       {{"runs", r.runs}, {"solutions", r.solutions}, {"tilesets", r.tilesets}, {"conversions", r.conversions}}},
      {"solutions_read", r.solutions_seen},
      {"total", stats_json(s)}};
  emit(ctx, j, [&] {
    fmt::print(
        "merged {} input(s) into {}: {} new solutions (of {} read), {} new runs, {} new tile sets, {} new "
        "conversions; now {} solutions\n",
        a.inputs.size(), target.path(), r.solutions, r.solutions_seen, r.runs, r.tilesets, r.conversions, s.solutions);
  });
}

void add_merge(CLI::App& db, Context& ctx) {
  auto* cmd = db.add_subcommand("merge", "Merge databases or JSON exports IN... into OUT (one transaction, idempotent)");
  auto a = std::make_shared<MergeArgs>();
  cmd->add_option("OUT", a->out, "Target database (created if missing)")->required();
  cmd->add_option("IN", a->inputs, "Tilekit databases or `db export` JSON files")->required();
  cmd->add_flag("--distinct-orbits", a->distinct, "Keep one solution per canonical hash (orbit)");
  cmd->add_flag("--quiet", a->quiet, "No progress output on stderr (large merges report progress)");
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_merge(*a, ctx); });
}

struct AddArgs {
  DbArgs database;
  std::vector<std::string> files;
  std::string method = "import";
};

void run_add(const AddArgs& a, const Context& ctx) {
  std::vector<SolutionRecord> batch;
  for (const std::string& f : a.files) {  // every file checked before anything is written
    SolutionRecord s;
    s.tiling = read_tiling_file(f);
    ValidationReport rep = validate(s.tiling);
    if (!rep.valid)
      throw InputError(fmt::format("{}: not a valid tiling ({}); nothing stored", f,
                                   rep.errors.empty() ? "invalid" : rep.errors.front()));
    s.method = a.method;
    s.validated = true;
    batch.push_back(std::move(s));
  }
  ResultsDb db(a.database.path());
  RunRecord run;
  run.command = "db add";
  run.params = {{"files", a.files}, {"method", a.method}};
  run.status = "complete";
  const std::size_t added = db.add_run_with_solutions(run, batch);
  nlohmann::json hashes = nlohmann::json::array();
  for (const auto& s : batch) hashes.push_back(solution_hash(s.tiling));
  emit(ctx, {{"db", db.path()}, {"files", a.files.size()}, {"added", added}, {"solution_hashes", hashes}},
       [&] { fmt::print("{}: stored {} new solution(s) of {} file(s)\n", db.path(), added, a.files.size()); });
}

void add_add(CLI::App& db, Context& ctx) {
  auto* cmd = db.add_subcommand("add", "Validate tiling/packing files and store them as solutions");
  auto a = std::make_shared<AddArgs>();
  cmd->add_option("FILE", a->files, "Tiling/packing JSON files (the `tilekit check` format)")->required();
  cmd->add_option("--method", a->method, "Method recorded with each solution")->capture_default_str();
  add_db_option(cmd, a->database);
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_add(*a, ctx); });
}

}  // namespace

void add_db_commands(CLI::App& app, Context& ctx) {
  auto* db = app.add_subcommand("db", "Query and maintain the SQLite results database");
  db->require_subcommand(1);
  add_list(*db, ctx);
  add_stats(*db, ctx);
  add_db_show(*db, ctx);
  add_export(*db, ctx);
  add_merge(*db, ctx);
  add_add(*db, ctx);
  add_db_chain_commands(*db, ctx);
}

}  // namespace tilekit::cli
