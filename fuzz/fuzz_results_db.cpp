// The results database (results/results_db.hpp) under structural damage made through SQLite, not
// bytes alone: each input is a program of edits applied to a small valid database (a run, two
// solutions, two tile sets, a conversion) — columns dropped or renamed, tables renamed, triggers,
// views and indices added, values of every SQLite type written into any column, rows inserted or
// deleted, the schema version and application id changed. Then every reader and writer runs on
// it: open (read-only and for writing), stats, listings with cells, a full export, a run and a
// solution added, a merge into a fresh database. Each must succeed or refuse with InputError or
// NotFound (exit 2 or 1); a refused open must leave the file's bytes as they were.
#include <sqlite3.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "base/error.hpp"
#include "results/results_db.hpp"

namespace {

using namespace tilekit;

const char* const kTables[] = {"runs", "solutions", "tilesets", "conversions", "tilekit_meta"};
const char* const kColumns[] = {"id", "uid", "command", "params", "status", "solutions", "orbits", "nodes",
                                "seconds", "threads", "host", "version", "started_at", "finished_at", "pid",
                                "pid_start", "run_id", "kind", "colors", "vertical_colors", "rows", "cols",
                                "torus", "cells", "method", "solution_hash", "canonical_hash", "orbit_size",
                                "validated", "group_json", "created_at", "name", "tiles", "content_hash", "source",
                                "text", "source_set", "result_set", "tiles_before", "tiles_after", "soundness",
                                "details", "key", "value"};

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream b;
  b << in.rdbuf();
  return b.str();
}

// The input as a stream of choices.
struct Choices {
  const std::uint8_t* p;
  std::size_t n;
  std::uint8_t byte() { return n ? (--n, *p++) : 0; }
  template <class T, std::size_t N>
  const T& pick(const T (&a)[N]) { return a[byte() % N]; }
  std::string text() {
    std::string s;
    for (std::size_t len = byte() % 24; len > 0 && n > 0; --len) s.push_back(char(byte()));
    return s;
  }
};

// A value of a random SQLite type, as SQL.
std::string value(Choices& c) {
  switch (c.byte() % 9) {
    case 0: return "NULL";
    case 1: return std::to_string(std::int64_t(c.byte()) - 128);
    case 2: return "9223372036854775807";
    case 3: return "-9223372036854775808";
    case 4: return "1e308";
    case 5: return "x'00ff10'";
    case 6: return "'[1,2,3,4]'";
    case 7: return "'wang'";
    default: {
      std::string s = "'";
      for (char ch : c.text()) s += ch == '\'' ? "''" : std::string(1, ch == 0 ? ' ' : ch);
      return s + "'";
    }
  }
}

std::string edit(Choices& c) {
  const std::string table = c.pick(kTables), column = c.pick(kColumns);
  switch (c.byte() % 12) {
    case 0: return "ALTER TABLE " + table + " DROP COLUMN " + column;
    case 1: return "ALTER TABLE " + table + " RENAME COLUMN " + column + " TO renamed";
    case 2: return "ALTER TABLE " + table + " RENAME TO " + table + "_old";
    case 3: return "ALTER TABLE " + table + " ADD COLUMN extra TEXT";
    case 4:
      return "CREATE TRIGGER t" + std::to_string(c.byte()) + " BEFORE INSERT ON " + table +
             " BEGIN SELECT RAISE(ABORT, 'trigger says no'); END";
    case 5: return "CREATE VIEW v" + std::to_string(c.byte()) + " AS SELECT * FROM " + table;
    case 6: return "CREATE INDEX i" + std::to_string(c.byte()) + " ON " + table + "(" + column + ")";
    case 7: return "UPDATE " + table + " SET " + column + " = " + value(c) + " WHERE rowid = " + std::to_string(c.byte() % 4);
    case 8: return "DELETE FROM " + table + " WHERE rowid = " + std::to_string(c.byte() % 4);
    case 9: return "DROP INDEX IF EXISTS " + std::string(c.pick({"runs_by_command", "solutions_by_shape", "solutions_by_run"}));
    case 10: return "PRAGMA user_version = " + std::to_string(int(c.byte() % 4));
    default:
      return "INSERT INTO " + table + "(" + column + ") VALUES (" + value(c) + ")";
  }
}

// A small valid database, made once (by the code under test) and copied for every input.
const std::string& template_bytes(const std::string& dir) {
  static const std::string bytes = [&] {
    const std::string path = dir + "/template.sqlite";
    {
      ResultsDb db(path);
      RunRecord run;
      run.command = "pack";
      run.params = {{"colors", 2}};
      run.id = db.begin_run(run);
      run.status = "complete";
      db.finish_run(run);
      for (std::uint32_t k = 0; k < 2; ++k) {
        SolutionRecord s;
        s.run_id = run.id;
        s.tiling = Tiling(TileKind::Corner, 2, 4, 4, true);
        for (std::size_t i = 0; i < 16; ++i) s.tiling.cells[i] = TileIndex((i + k) % 16);
        s.method = "fuzz";
        db.add_solution(s);
      }
      const auto a = db.add_tileset("a", TileKind::Wang, 1, 2, "h1", "fuzz", "0 0 0 0\n");
      const auto b = db.add_tileset("b", TileKind::Corner, 1, 2, "h2", "fuzz", "# kind: corner\n0 0 0 0\n");
      db.add_conversion(a, "diagonal", b, 1, 1, 2, "sound", {{"k", 1}});
      sqlite3_exec(db.handle(), "PRAGMA wal_checkpoint(TRUNCATE); PRAGMA journal_mode = DELETE", nullptr, nullptr,
                   nullptr);
    }
    return slurp(path);
  }();
  return bytes;
}

void exercise(const std::string& path, const std::string& other) {
  {
    ResultsDb db(path, DbOpenOptions{.create = false, .read_only = true});
    db.stats();
    db.list_runs(0);
    SolutionFilter f;
    f.limit = 0;
    db.list_solutions(f, true);
    db.list_tilesets(0);
    db.list_conversions(0);
    std::ostringstream sink;
    db.export_json(sink);
    for (const char* t : {"solutions", "runs", "tilesets", "conversions"}) db.export_csv(sink, t);
    db.solution(1);
    db.find_solution(TileKind::Corner, 2, 4, 4);
  }
  {
    ResultsDb db(path);
    RunRecord run;
    run.command = "fuzz";
    run.id = db.begin_run(run);
    SolutionRecord s;
    s.run_id = run.id;
    s.tiling = Tiling(TileKind::Wang, 2, 1, 1, true);
    db.add_solution(s);
    db.finish_run(run);
    db.add_tileset("c", TileKind::Wang, 1, 2, "h3", "fuzz", "1 1 1 1\n");
  }
  std::filesystem::remove(other);
  ResultsDb out(other);
  out.merge({path});
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string dir = [] {
    std::string t = (std::filesystem::exists("/dev/shm") ? std::string("/dev/shm") : std::string("/tmp")) +
                    "/tilekit-fuzz-db-XXXXXX";
    return std::string(::mkdtemp(t.data()));
  }();
  const std::string path = dir + "/db.sqlite", other = dir + "/merged.sqlite";
  for (const char* side : {"", "-wal", "-shm", "-journal"}) std::filesystem::remove(path + side);
  std::ofstream(path, std::ios::binary) << template_bytes(dir);
  Choices c{data, size};
  {
    sqlite3* raw = nullptr;
    if (sqlite3_open(path.c_str(), &raw) == SQLITE_OK)
      for (int k = 0; k < 6 && c.n > 0; ++k) sqlite3_exec(raw, edit(c).c_str(), nullptr, nullptr, nullptr);
    sqlite3_close(raw);
  }
  const std::string before = slurp(path);
  try {
    ResultsDb probe(path, DbOpenOptions{.create = false, .read_only = true});
  } catch (const InputError&) {
    if (slurp(path) != before) __builtin_trap();  // a refused file is never modified
    return 0;
  } catch (const NotFound&) {
    return 0;
  }
  try {
    exercise(path, other);
  } catch (const InputError&) {
  } catch (const NotFound&) {
  }
  return 0;
}
