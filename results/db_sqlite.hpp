#pragma once
// Thin RAII helpers over the SQLite C API for the results store (internal to results/):
// prepared statements, immediate transactions, and one mapping of SQLite errors to the
// project's errors (a corrupt or foreign file is bad input, exit 2).
#include <sqlite3.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace tilekit::sqlitedb {

// Throws InputError (exit 2) for what the file or its surroundings caused (corrupt, busy, read-only,
// full, a constraint), std::runtime_error for misuse, SQLite's internal errors and out of memory.
[[noreturn]] void fail(sqlite3* db, int rc, std::string_view what);

void exec(sqlite3* db, const char* sql);

class Statement {
 public:
  Statement(sqlite3* db, std::string_view sql);
  ~Statement();
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  Statement& bind(int i, std::int64_t v);
  Statement& bind(int i, double v);
  Statement& bind(int i, std::string_view v);
  Statement& bind_null(int i);
  // true while a row is available; false when done. Throws on error.
  bool step();
  // Runs a statement that returns no rows; resets it for reuse.
  void run();
  void reset();

  std::int64_t int64(int col) const;
  double real(int col) const;
  std::string text(int col) const;
  bool is_null(int col) const;

 private:
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

// BEGIN IMMEDIATE (takes the write lock now, so a second writer waits on the busy timeout
// instead of failing on upgrade); rolls back unless commit() was called.
class Transaction {
 public:
  explicit Transaction(sqlite3* db);
  ~Transaction();
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  void commit();

 private:
  sqlite3* db_;
  bool open_ = true;
};

std::int64_t pragma_int(sqlite3* db, const char* pragma);

// Flat JSON array of tile indices "[1,2,3]" <-> vector, for the cells column.
std::string cells_to_text(const std::vector<std::uint32_t>& cells);
std::vector<std::uint32_t> cells_from_text(std::string_view text);

}  // namespace tilekit::sqlitedb
