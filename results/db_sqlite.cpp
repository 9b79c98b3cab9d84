#include "results/db_sqlite.hpp"

#include <fmt/format.h>

#include <charconv>
#include <stdexcept>

#include "base/error.hpp"

namespace tilekit::sqlitedb {

void fail(sqlite3* db, int rc, std::string_view what) {
  const char* file = db ? sqlite3_db_filename(db, "main") : nullptr;
  std::string msg = fmt::format("{}{}{}: {}", file ? file : "", file ? ": " : "", what,
                                db ? sqlite3_errmsg(db) : sqlite3_errstr(rc));
  const int primary = rc & 0xff;
  // Problems of the file or its surroundings are the user's to fix (exit 2), not bugs.
  if (primary == SQLITE_CORRUPT || primary == SQLITE_NOTADB)
    throw InputError(msg + " (the results database is corrupt)");
  if (primary == SQLITE_BUSY || primary == SQLITE_LOCKED)
    throw InputError(msg + " (another process held the database longer than the busy timeout)");
  if (primary == SQLITE_READONLY || primary == SQLITE_PERM || primary == SQLITE_CANTOPEN)
    throw InputError(msg + " (the database or its directory cannot be written; nothing was changed)");
  if (primary == SQLITE_FULL) throw InputError(msg + " (the disk is full; the transaction was rolled back)");
  if (primary == SQLITE_IOERR) throw InputError(msg + " (an I/O error; the transaction was rolled back)");
  // Misuse of the API or SQLite's own failures are bugs; anything else the file made happen (a
  // constraint its rows break, a value too big) is exit 2 like the rest, and every write runs in
  // a transaction, so nothing of it was kept.
  if (primary == SQLITE_MISUSE || primary == SQLITE_INTERNAL || primary == SQLITE_NOMEM) throw std::runtime_error(msg);
  throw InputError(msg + " (nothing of this write was kept)");
}

void exec(sqlite3* db, const char* sql) {
  char* err = nullptr;
  int rc = sqlite3_exec(db, sql, nullptr, nullptr, &err);
  if (rc != SQLITE_OK) {
    std::string e = err ? err : sqlite3_errstr(rc);
    sqlite3_free(err);
    fail(db, rc, fmt::format("SQL failed ({})", e));
  }
}

Statement::Statement(sqlite3* db, std::string_view sql) : db_(db) {
  int rc = sqlite3_prepare_v2(db, sql.data(), int(sql.size()), &stmt_, nullptr);
  if (rc != SQLITE_OK) fail(db, rc, "cannot prepare a query");
}

Statement::~Statement() { sqlite3_finalize(stmt_); }

Statement& Statement::bind(int i, std::int64_t v) {
  sqlite3_bind_int64(stmt_, i, v);
  return *this;
}
Statement& Statement::bind(int i, double v) {
  sqlite3_bind_double(stmt_, i, v);
  return *this;
}
Statement& Statement::bind(int i, std::string_view v) {
  sqlite3_bind_text(stmt_, i, v.data(), int(v.size()), SQLITE_TRANSIENT);
  return *this;
}
Statement& Statement::bind_null(int i) {
  sqlite3_bind_null(stmt_, i);
  return *this;
}

bool Statement::step() {
  int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  fail(db_, rc, "query failed");
}

void Statement::run() {
  while (step()) {
  }
  reset();
}

void Statement::reset() {
  sqlite3_reset(stmt_);
  sqlite3_clear_bindings(stmt_);
}

std::int64_t Statement::int64(int col) const { return sqlite3_column_int64(stmt_, col); }
double Statement::real(int col) const { return sqlite3_column_double(stmt_, col); }
std::string Statement::text(int col) const {
  const unsigned char* p = sqlite3_column_text(stmt_, col);
  return p ? std::string(reinterpret_cast<const char*>(p), std::size_t(sqlite3_column_bytes(stmt_, col)))
           : std::string();
}
bool Statement::is_null(int col) const { return sqlite3_column_type(stmt_, col) == SQLITE_NULL; }

Transaction::Transaction(sqlite3* db) : db_(db) { exec(db, "BEGIN IMMEDIATE"); }

Transaction::~Transaction() {
  if (open_) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
}

void Transaction::commit() {
  exec(db_, "COMMIT");
  open_ = false;
}

std::int64_t pragma_int(sqlite3* db, const char* pragma) {
  Statement s(db, fmt::format("PRAGMA {}", pragma));
  return s.step() ? s.int64(0) : 0;
}

std::string cells_to_text(const std::vector<std::uint32_t>& cells) {
  std::string out;
  out.reserve(cells.size() * 6 + 2);
  out.push_back('[');
  char buf[16];
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i) out.push_back(',');
    auto [end, ec] = std::to_chars(buf, buf + sizeof buf, cells[i]);
    out.append(buf, end);
  }
  out.push_back(']');
  return out;
}

std::vector<std::uint32_t> cells_from_text(std::string_view text) {
  std::vector<std::uint32_t> out;
  const char* p = text.data();
  const char* end = p + text.size();
  auto skip = [&] {
    while (p < end && (*p == ' ' || *p == '\n' || *p == '\t' || *p == '\r')) ++p;
  };
  skip();
  if (p == end || *p != '[') throw InputError("stored cells are not a JSON array");
  ++p;
  skip();
  if (p < end && *p == ']') return out;
  while (p < end) {
    skip();
    std::uint32_t v = 0;
    auto [q, ec] = std::from_chars(p, end, v);
    if (ec != std::errc()) throw InputError("stored cells hold a value that is not a tile index");
    out.push_back(v);
    p = q;
    skip();
    if (p < end && *p == ',') {
      ++p;
      continue;
    }
    if (p < end && *p == ']') return out;
    break;
  }
  throw InputError("stored cells are not a JSON array of tile indices");
}

}  // namespace tilekit::sqlitedb
