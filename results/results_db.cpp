// Opening, checking, migrating and writing the results database. The order of checks on
// open is the point of this file: a file that is not Tilekit's, or is damaged, is inspected
// through a read-only connection first, so that it is never modified (not even its journal
// mode) before we know it is ours and sound. Over 400 lines because the open sequence
// (inspect, connect, migrate) and the writers that share its connection read best in one place;
// queries, rows, merges and exports have their own files (db_query, db_rows, db_merge, db_export).
#include "results/results_db.hpp"

#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "results/db_rows.hpp"
#include "results/db_schema.hpp"
#include "results/db_sqlite.hpp"
#include "base/error.hpp"
#include "base/hash.hpp"
#include "base/version.hpp"

namespace tilekit {

using sqlitedb::Statement;
using sqlitedb::Transaction;

namespace {

enum class FileState { Missing, Fresh, Current, Older };

// The one error for a file we refuse to use (foreign, corrupt, newer, damaged).
struct NotOurs : InputError {
  using InputError::InputError;
};
NotOurs not_ours(const std::string& path, const std::string& why) {
  return NotOurs(fmt::format("{}: not a usable Tilekit results database: {}; the file was left untouched", path, why));
}

// "file:PATH?immutable=1" with the URI's reserved characters escaped (sqlite.org/uri.html).
std::string immutable_uri(const std::string& path) {
  std::string uri = "file:";
  for (char c : path) {
    if (c == '%' || c == '?' || c == '#') uri += fmt::format("%{:02X}", static_cast<unsigned char>(c));
    else uri += c;
  }
  return uri + "?immutable=1";
}

// The -wal and -shm files beside a database: which existed before we looked, and, when the
// file is refused, removal of those the inspection created (the connection is closed first:
// this object outlives it).
struct SideFiles {
  std::string wal, shm;
  bool wal_existed, shm_existed, refused = false, ours = true;
  explicit SideFiles(const std::string& path)
      : wal(path + "-wal"), shm(path + "-shm"), wal_existed(exists(wal)), shm_existed(exists(shm)) {}
  ~SideFiles() {
    if (!refused || !ours) return;
    std::error_code ec;
    if (!wal_existed) std::filesystem::remove(wal, ec);
    if (!shm_existed) std::filesystem::remove(shm, ec);
  }
  static bool exists(const std::string& p) {
    std::error_code ec;
    return std::filesystem::exists(p, ec);
  }
};

// What an immutable read of a file relies on staying unchanged while it reads: the main file
// (inode, size, modification time) and whether a -wal file is beside it.
struct FileStamp {
  bool present = false, wal = false;
  ino_t inode = 0;
  off_t size = 0;
  std::int64_t mtime_ns = 0;
  explicit FileStamp(const std::string& path) : wal(SideFiles::exists(path + "-wal")) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return;
    present = true;
    inode = st.st_ino;
    size = st.st_size;
    mtime_ns = std::int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
  }
  bool operator==(const FileStamp&) const = default;
};

// Read-only inspection of an existing file. Returns Fresh for an empty file (0 bytes, or an
// SQLite file without tables and without an application id: e.g. one a concurrent process
// is creating right now), Current/Older for a Tilekit database; throws InputError otherwise.
// `locked`: never read it as immutable; `lock_free` tells whether it did (see inspect below).
FileState inspect_file(const std::string& path, const DbOpenOptions& opt, bool locked, bool& lock_free) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) return FileState::Missing;
  if (!fs::is_regular_file(path, ec)) throw not_ours(path, "not a regular file");
  const auto size = fs::file_size(path, ec);
  if (ec) throw not_ours(path, "cannot read its size");
  if (size == 0) return FileState::Fresh;
  // The 100-byte database header (sqlite.org/fileformat.html, sec. 1.3).
  std::array<unsigned char, 100> header{};
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw not_ours(path, "cannot open it for reading");
    in.read(reinterpret_cast<char*>(header.data()), header.size());
    if (in.gcount() < 16 || std::memcmp(header.data(), "SQLite format 3\0", 16) != 0)
      throw not_ours(path, "not an SQLite file (corrupt or foreign)");
    if (in.gcount() != std::streamsize(header.size())) throw not_ours(path, "its SQLite header is truncated (damaged)");
  }
  // Bytes 18 and 19: file format write/read versions, 1 (rollback journal) or 2 (WAL). SQLite
  // opens a file with other values read-only or not at all; here it is damage.
  for (int b : {18, 19})
    if (header[std::size_t(b)] != 1 && header[std::size_t(b)] != 2)
      throw not_ours(path, fmt::format("its SQLite header is damaged (byte {} is {}; SQLite writes 1 or 2)", b,
                                       int(header[std::size_t(b)])));
  // A WAL database (bytes 18, 19 = 2) without a -wal file is complete in the main file: inspect
  // it as immutable, which creates no -wal/-shm files beside a file we may refuse. Otherwise (a
  // rollback-journal file, which a reader never adds files to; or a writer is active, or one
  // crashed) open it normally, and remove on refusal the side files this created.
  SideFiles side(path);
  const bool immutable = !locked && header[18] == 2 && header[19] == 2 && !side.wal_existed;
  side.ours = !immutable;  // an immutable read creates no side file: one that appears is a writer's
  lock_free = immutable;
  sqlite3* db = nullptr;
  int rc = immutable ? sqlite3_open_v2(immutable_uri(path).c_str(), &db, SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, nullptr)
                     : sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
  struct Closer {
    sqlite3* d;
    ~Closer() { sqlite3_close(d); }
  } closer{db};
  if (rc != SQLITE_OK) throw not_ours(path, fmt::format("SQLite cannot open it ({})", sqlite3_errstr(rc)));
  sqlite3_busy_timeout(db, opt.busy_timeout_ms);
  try {
    // One read transaction: the header fields and the tables from one snapshot, even while a
    // concurrent process commits its new schema (read apart, they once gave application_id 0
    // with 5 tables, and the file was refused as another application's).
    sqlitedb::exec(db, "BEGIN");
    const auto app = sqlitedb::pragma_int(db, "application_id");
    const auto version = sqlitedb::pragma_int(db, "user_version");
    Statement tables(db, "SELECT name FROM sqlite_master WHERE type = 'table'");
    std::vector<std::string> names;
    while (tables.step()) names.push_back(tables.text(0));
    if (app == 0 && names.empty() && version == 0) return FileState::Fresh;
    if (app != ResultsDb::kApplicationId)
      throw not_ours(path, fmt::format("an SQLite database of another application (application_id {:#x}, {} tables)",
                                       std::uint32_t(app), names.size()));
    if (version > ResultsDb::kSchemaVersion)
      throw not_ours(path, fmt::format("written by a newer Tilekit (schema version {}; this build knows up to {})",
                                       version, ResultsDb::kSchemaVersion));
    if (version < 1) throw not_ours(path, "marked as Tilekit's but without a schema version (damaged)");
    // The schema must be exactly the one this build makes: a dropped or renamed column would
    // fail a query half-way, a trigger could refuse or rewrite any write.
    if (std::string diff = dbschema::schema_difference(db, version); !diff.empty())
      throw not_ours(path, fmt::format("its schema differs from Tilekit's: {}", diff));
    if (opt.integrity_check) {
      Statement check(db, "PRAGMA integrity_check(5)");
      std::vector<std::string> problems;
      while (check.step())
        if (check.text(0) != "ok") problems.push_back(check.text(0));
      if (!problems.empty()) throw not_ours(path, fmt::format("corrupt (integrity_check: {})", problems.front()));
      if (std::string bad = dbschema::type_difference(db, version); !bad.empty()) throw not_ours(path, "damaged: " + bad);
    }
    return version == ResultsDb::kSchemaVersion ? FileState::Current : FileState::Older;
  } catch (const NotOurs&) {
    side.refused = true;
    throw;
  } catch (const InputError& e) {  // SQLITE_CORRUPT / SQLITE_NOTADB while reading
    side.refused = true;
    throw not_ours(path, fmt::format("corrupt ({})", e.what()));
  } catch (const std::runtime_error& e) {
    side.refused = true;
    throw not_ours(path, fmt::format("unreadable ({})", e.what()));
  }
}

// An immutable read takes no lock, so it is exact only if no process wrote the file meanwhile:
// one that creates the database, or checkpoints its -wal into it, makes the read see a mixture.
// The raw read of the header takes none either. When the file changed during a lock-free read,
// or before a refusal, it is read again through SQLite's locks; a locked read that accepted the
// file stands (a concurrent writer changes the file without making that read inexact).
FileState inspect(const std::string& path, const DbOpenOptions& opt) {
  const FileStamp before(path);
  bool lock_free = false;
  try {
    FileState state = inspect_file(path, opt, false, lock_free);
    if (!lock_free || FileStamp(path) == before) return state;
  } catch (const NotOurs&) {
    if (FileStamp(path) == before) throw;
  }
  return inspect_file(path, opt, true, lock_free);
}

// Field 22 of /proc/PID/stat: the process's start time in clock ticks after boot (0 when the
// process does not exist). With the pid it names one process, whatever reuses the pid later.
std::int64_t process_start(long pid) {
  std::ifstream in(fmt::format("/proc/{}/stat", pid));
  std::string stat;
  if (!std::getline(in, stat)) return 0;
  const auto close = stat.rfind(')');  // the command name may hold spaces and parentheses
  if (close == std::string::npos) return 0;
  std::istringstream rest(stat.substr(close + 1));
  std::string field;
  for (int i = 3; i <= 22 && rest >> field; ++i)
    if (i == 22) return std::strtoll(field.c_str(), nullptr, 10);
  return 0;
}

std::string host_name() {
  std::array<char, 256> buf{};
  if (gethostname(buf.data(), buf.size() - 1) != 0) return "";
  return buf.data();
}

// A run id unique across machines and processes: host, pid, wall and steady clock, hashed.
std::string make_run_uid(const RunRecord& run) {
  const auto wall = std::chrono::system_clock::now().time_since_epoch().count();
  const auto mono = std::chrono::steady_clock::now().time_since_epoch().count();
  const std::string seed = fmt::format("{}|{}|{}|{}|{}|{}", host_name(), getpid(), wall, mono, run.command,
                                       static_cast<const void*>(&run));
  return fmt::format("{:016x}{:08x}", stable_hash64(seed), std::uint32_t(wall ^ (mono >> 7)));
}

// Switching a new database to WAL needs a moment of exclusive access, and SQLite answers
// SQLITE_BUSY at once instead of calling the busy handler when another process holds it (two
// shards creating one database together). Retry until the busy timeout, then fail as usual.
void enable_wal(sqlite3* db, int busy_timeout_ms) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(busy_timeout_ms);
  for (;;) {
    const int rc = sqlite3_exec(db, "PRAGMA journal_mode = WAL", nullptr, nullptr, nullptr);
    const int primary = rc & 0xff;
    if (rc == SQLITE_OK) return;
    if ((primary != SQLITE_BUSY && primary != SQLITE_LOCKED) || std::chrono::steady_clock::now() > deadline) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  sqlitedb::exec(db, "PRAGMA journal_mode = WAL");  // reports the error with the usual message
}

}  // namespace

ResultsDb::ResultsDb(const std::string& path, bool create) : ResultsDb(path, DbOpenOptions{.create = create}) {}

ResultsDb::ResultsDb(const std::string& path, const DbOpenOptions& opt) : path_(path) {
  if (path.empty()) throw InputError("empty database path");
  FileState state = inspect(path, opt);
  if (state == FileState::Missing && !opt.create) throw NotFound(fmt::format("{}: no results database there", path));
  if (state == FileState::Missing) {
    std::filesystem::path parent = std::filesystem::path(path).parent_path();
    std::error_code ec;
    if (!parent.empty()) std::filesystem::create_directories(parent, ec);
    if (ec) throw InputError(fmt::format("{}: cannot create the directory ({})", parent.string(), ec.message()));
  }
  // A constructor that throws runs no destructor: close the connection on the way out.
  try {
    const bool needs_write = state == FileState::Missing || state == FileState::Fresh || state == FileState::Older;
    if (opt.read_only && !needs_write) {
      open_connection(true, opt.busy_timeout_ms);
      return;
    }
    // An older schema is migrated in place even by a reader (the queries know only the current
    // one); the migration keeps every row (db_schema.cpp) and runs in one transaction.
    if (opt.read_only && !opt.create && state != FileState::Older)
      throw NotFound(fmt::format("{}: no results database there", path));
    open_connection(false, opt.busy_timeout_ms);
    migrate();
    mark_killed_runs();
    if (opt.read_only) {
      sqlite3_close(db_);
      db_ = nullptr;
      open_connection(true, opt.busy_timeout_ms);
    }
  } catch (...) {
    sqlite3_close(db_);
    db_ = nullptr;
    throw;
  }
}

ResultsDb::~ResultsDb() { sqlite3_close(db_); }

void ResultsDb::open_connection(bool read_only, int busy_timeout_ms) {
  const int flags = read_only ? SQLITE_OPEN_READONLY : (SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE);
  int rc = sqlite3_open_v2(path_.c_str(), &db_, flags, nullptr);
  if (rc != SQLITE_OK) {
    std::string msg = db_ ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
    sqlite3_close(db_);
    db_ = nullptr;
    throw InputError(fmt::format("{}: cannot open the results database ({})", path_, msg));
  }
  read_only_ = read_only;
  sqlite3_busy_timeout(db_, busy_timeout_ms);
  sqlite3_extended_result_codes(db_, 1);
  const auto probe_fails = [&] {
    if (sqlite3_exec(db_, "SELECT count(*) FROM sqlite_master", nullptr, nullptr, nullptr) == SQLITE_OK) return false;
    const int code = sqlite3_extended_errcode(db_) & 0xff;
    return code == SQLITE_CANTOPEN || code == SQLITE_READONLY;
  };
  if (read_only && probe_fails()) {
    // A WAL database on read-only media (or in a read-only directory) cannot get its -shm file
    // (SQLite says it cannot open it, or that it cannot write it). Then no process can be
    // writing to it either, so reading it as immutable is exact.
    sqlite3_close(db_);
    db_ = nullptr;
    if (sqlite3_open_v2(immutable_uri(path_).c_str(), &db_, SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, nullptr) !=
        SQLITE_OK) {
      std::string msg = db_ ? sqlite3_errmsg(db_) : "out of memory";
      sqlite3_close(db_);
      db_ = nullptr;
      throw InputError(fmt::format("{}: cannot open the results database ({})", path_, msg));
    }
    sqlite3_extended_result_codes(db_, 1);
  }
  if (!read_only) {
    // WAL: readers keep working while a writer runs (only now, after the checks above).
    enable_wal(db_, busy_timeout_ms);
    sqlitedb::exec(db_, "PRAGMA synchronous = NORMAL");
  }
  sqlitedb::exec(db_, "PRAGMA foreign_keys = ON");
}

bool dbrows::process_gone(const std::string& host, std::int64_t pid, std::int64_t start) {
  return pid > 0 && host == host_name() && process_start(long(pid)) != start;
}

void ResultsDb::mark_killed_runs() {
  // Runs of this host still "running" whose process is gone (or is another process now).
  std::vector<std::int64_t> dead;
  {
    Statement s(db_, "SELECT id, host, pid, pid_start FROM runs WHERE status = 'running' AND pid IS NOT NULL");
    while (s.step())
      if (dbrows::process_gone(s.text(1), s.int64(2), s.int64(3))) dead.push_back(s.int64(0));
  }
  if (dead.empty()) return;
  Transaction tx(db_);
  Statement mark(db_, "UPDATE runs SET status = 'killed' WHERE id = ?1 AND status = 'running'");
  for (std::int64_t id : dead) mark.bind(1, id).run();
  tx.commit();
}

void ResultsDb::migrate() {
  if (sqlitedb::pragma_int(db_, "user_version") == kSchemaVersion &&
      sqlitedb::pragma_int(db_, "application_id") == kApplicationId)
    return;
  Transaction tx(db_);
  // Re-read under the write lock: a concurrent process may have created the schema meanwhile.
  const auto app = sqlitedb::pragma_int(db_, "application_id");
  auto version = sqlitedb::pragma_int(db_, "user_version");
  if (app != 0 && app != kApplicationId) throw not_ours(path_, "another application wrote to it meanwhile");
  const auto& steps = dbschema::migrations();
  for (; version < kSchemaVersion; ++version) sqlitedb::exec(db_, std::string(steps[std::size_t(version)]).c_str());
  sqlitedb::exec(db_, fmt::format("PRAGMA application_id = {}", kApplicationId).c_str());
  sqlitedb::exec(db_, fmt::format("PRAGMA user_version = {}", kSchemaVersion).c_str());
  Statement meta(db_, "INSERT OR REPLACE INTO tilekit_meta(key, value) VALUES ('schema_version', ?1)");
  meta.bind(1, std::int64_t(kSchemaVersion)).run();
  tx.commit();
}

std::string ResultsDb::default_path() {
  namespace fs = std::filesystem;
  if (const char* p = std::getenv("TILEKIT_DB"); p && *p) return p;
  if (const char* x = std::getenv("XDG_DATA_HOME"); x && *x) return (fs::path(x) / "tilekit" / "results.sqlite").string();
  const char* home = std::getenv("HOME");
  fs::path base = home && *home ? fs::path(home) : fs::temp_directory_path();
  return (base / ".local" / "share" / "tilekit" / "results.sqlite").string();
}

std::int64_t ResultsDb::begin_run(const RunRecord& run) {
  Statement s(db_,
              "INSERT INTO runs(uid, command, params, status, solutions, orbits, nodes, seconds, threads, host, "
              "version, started_at, finished_at, pid, pid_start) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, "
              "COALESCE(NULLIF(?12, ''), strftime('%Y-%m-%dT%H:%M:%fZ', 'now')), NULLIF(?13, ''), ?14, ?15)");
  s.bind(1, run.uid.empty() ? make_run_uid(run) : run.uid)
      .bind(2, run.command)
      .bind(3, run.params.is_null() ? std::string("{}") : run.params.dump())
      .bind(4, run.status.empty() ? std::string("running") : run.status)
      .bind(5, std::int64_t(run.solutions));
  if (run.orbits) s.bind(6, std::int64_t(*run.orbits));
  s.bind(7, std::int64_t(run.nodes))
      .bind(8, run.seconds)
      .bind(9, std::int64_t(run.threads))
      .bind(10, run.host.empty() ? host_name() : run.host)
      .bind(11, run.version.empty() ? version_line() : run.version)
      .bind(12, run.started_at)
      .bind(13, run.finished_at)
      .bind(14, std::int64_t(getpid()))
      .bind(15, process_start(long(getpid())));
  s.run();
  return sqlite3_last_insert_rowid(db_);
}

void ResultsDb::finish_run(const RunRecord& run) {
  Statement s(db_,
              "UPDATE runs SET status = ?2, solutions = ?3, orbits = ?4, nodes = ?5, seconds = ?6, threads = ?7, "
              "finished_at = COALESCE(NULLIF(?8, ''), strftime('%Y-%m-%dT%H:%M:%fZ', 'now')) WHERE id = ?1");
  s.bind(1, run.id)
      .bind(2, run.status.empty() ? std::string("complete") : run.status)
      .bind(3, std::int64_t(run.solutions));
  if (run.orbits) s.bind(4, std::int64_t(*run.orbits));
  s.bind(5, std::int64_t(run.nodes)).bind(6, run.seconds).bind(7, std::int64_t(run.threads)).bind(8, run.finished_at);
  s.run();
  if (sqlite3_changes(db_) == 0) throw NotFound(fmt::format("{}: no run with id {}", path_, run.id));
}

bool ResultsDb::forget_run(std::int64_t id) {
  Statement s(db_, "DELETE FROM runs WHERE id = ?1 AND NOT EXISTS (SELECT 1 FROM solutions WHERE run_id = ?1)");
  s.bind(1, id).run();
  return sqlite3_changes(db_) > 0;
}

bool ResultsDb::add_solution(const SolutionRecord& s) { return add_solutions({s}) == 1; }

std::size_t ResultsDb::add_solutions(const std::vector<SolutionRecord>& batch) {
  if (batch.empty()) return 0;
  Transaction tx(db_);
  const std::size_t added = insert_solutions(batch);
  tx.commit();
  return added;
}

std::size_t ResultsDb::insert_solutions(const std::vector<SolutionRecord>& batch) {
  Statement ins(db_, dbrows::kInsertSolution);
  std::size_t added = 0;
  for (const SolutionRecord& s : batch) {
    dbrows::bind_solution(ins, s, solution_hash(s.tiling));
    ins.run();
    added += std::size_t(sqlite3_changes(db_));
  }
  return added;
}

std::size_t ResultsDb::add_run_with_solutions(RunRecord& run, std::vector<SolutionRecord>& batch) {
  Transaction tx(db_);
  run.id = begin_run(run);
  for (SolutionRecord& s : batch) s.run_id = run.id;
  const std::size_t added = insert_solutions(batch);
  run.solutions = added;
  finish_run(run);
  tx.commit();
  return added;
}

std::optional<SolutionRecord> ResultsDb::find_solution(TileKind kind, std::uint32_t colours, int rows, int cols,
                                                      int window_rows, int window_cols) {
  Statement s(db_, std::string(dbrows::kSelectSolution) +
                       " WHERE kind = ?1 AND colors = ?2 AND rows = ?3 AND cols = ?4 AND validated = 1 "
                       "AND window_rows = ?5 AND window_cols = ?6 ORDER BY id LIMIT 1");
  s.bind(1, std::string(kind_name(kind)))
      .bind(2, std::int64_t(colours))
      .bind(3, std::int64_t(rows))
      .bind(4, std::int64_t(cols))
      .bind(5, std::int64_t(window_rows))
      .bind(6, std::int64_t(window_cols));
  if (!s.step()) return std::nullopt;
  return dbrows::read_solution(s, true);
}

std::int64_t ResultsDb::add_tileset(const std::string& name, TileKind kind, std::uint64_t tiles, std::uint32_t colours,
                                    const std::string& content_hash, const std::string& source,
                                    const std::string& text) {
  Transaction tx(db_);
  Statement ins(db_,
                "INSERT OR IGNORE INTO tilesets(name, kind, tiles, colors, content_hash, source, text, created_at) "
                "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))");
  ins.bind(1, name)
      .bind(2, std::string(kind_name(kind)))
      .bind(3, std::int64_t(tiles))
      .bind(4, std::int64_t(colours))
      .bind(5, content_hash)
      .bind(6, source)
      .bind(7, text)
      .run();
  Statement id(db_, "SELECT id FROM tilesets WHERE name = ?1 AND content_hash = ?2");
  id.bind(1, name).bind(2, content_hash);
  if (!id.step()) throw std::runtime_error("tile set row vanished after insert");
  const auto result = id.int64(0);
  tx.commit();
  return result;
}

std::int64_t ResultsDb::add_conversion(std::int64_t source_set, const std::string& method, std::int64_t result_set,
                                       std::uint64_t tiles_before, std::uint64_t tiles_after, std::uint32_t colours,
                                       const std::string& soundness, const nlohmann::json& details) {
  Transaction tx(db_);
  for (std::int64_t set : {source_set, result_set}) {
    Statement q(db_, "SELECT 1 FROM tilesets WHERE id = ?1");
    q.bind(1, set);
    if (!q.step()) throw InputError(fmt::format("{}: no tile set with id {} (add it with add_tileset first)", path_, set));
  }
  Statement ins(db_,
                "INSERT INTO conversions(source_set, method, result_set, tiles_before, tiles_after, colors, soundness, "
                "details, created_at) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, strftime('%Y-%m-%dT%H:%M:%fZ', 'now')) "
                "ON CONFLICT(source_set, method, result_set) DO UPDATE SET tiles_before = excluded.tiles_before, "
                "tiles_after = excluded.tiles_after, colors = excluded.colors, soundness = excluded.soundness, "
                "details = excluded.details");
  ins.bind(1, source_set)
      .bind(2, method)
      .bind(3, result_set)
      .bind(4, std::int64_t(tiles_before))
      .bind(5, std::int64_t(tiles_after))
      .bind(6, std::int64_t(colours))
      .bind(7, soundness.empty() ? std::string("unknown") : soundness)
      .bind(8, details.is_null() ? std::string("{}") : details.dump())
      .run();
  Statement id(db_, "SELECT id FROM conversions WHERE source_set = ?1 AND method = ?2 AND result_set = ?3");
  id.bind(1, source_set).bind(2, method).bind(3, result_set);
  if (!id.step()) throw std::runtime_error("conversion row vanished after insert");
  const auto result = id.int64(0);
  tx.commit();
  return result;
}

// StableHash over a fixed little-endian serialisation of the tiling.
std::string solution_hash(const Tiling& t) {
  StableHash h;
  h.add(t.kind == TileKind::Wang ? 1 : t.kind == TileKind::Corner ? 2 : 3, 1);
  h.add(t.colours, 4);
  if (t.kind == TileKind::Wang && t.cv() != t.ch()) h.add(t.cv(), 4);  // mixed radix only
  if (t.kind == TileKind::Window) h.add(std::uint64_t(t.window_rows), 4).add(std::uint64_t(t.window_cols), 4);
  h.add(std::uint64_t(t.rows), 4);
  h.add(std::uint64_t(t.cols), 4);
  h.add(t.torus ? 1 : 0, 1);
  for (TileIndex c : t.cells) h.add(c, 4);
  return fmt::format("{:016x}", h.mixed());
}

}  // namespace tilekit
