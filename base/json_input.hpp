#pragma once
// Every JSON document Tilekit reads (tile sets, tilings, checkpoints, database exports and
// stored rows, portfolio statistics, probability maps, cluster run files) goes through here:
//
//  - parse_json_input(): bounds the nesting depth *before* parsing (an iterative scan, so a
//    document of 100,000 '[' is an error, not a stack overflow in a recursive dump or
//    destructor), and turns every parser exception (syntax, invalid UTF-8, numbers such as
//    1e999 that overflow a double) into InputError "ORIGIN: invalid JSON: ...".
//  - JsonIn: one checked accessor. Each value knows its path in the document, and every
//    type or range problem is InputError "ORIGIN: PATH: problem", e.g.
//    "t.json: cells[2][3]: expected an integer between 0 and 4294967295, got 1e+100".
//    Nothing reaches the user as "internal error: [json.exception...]".
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "base/error.hpp"

namespace tilekit {

// The deepest nesting any Tilekit document has is 6 (a database export's group inside a
// solution inside "solutions"); 64 leaves room for users' own wrappers and stays far below
// what a recursive walk of the parsed value can take on any stack.
inline constexpr int kMaxJsonDepth = 64;

// Depth of the deepest nesting of arrays/objects in `text` (strings skipped), stopping early
// once `limit` is exceeded; the byte offset where it was exceeded in *at.
int json_nesting_depth(std::string_view text, int limit, std::size_t* at = nullptr);

// Parses one JSON document. Throws InputError "ORIGIN: ..." for anything that is not
// well-formed JSON within the depth limit.
nlohmann::json parse_json_input(std::string_view text, const std::string& origin, int max_depth = kMaxJsonDepth);
// read_input_file() + parse_json_input(); `what` names the kind of file in messages.
nlohmann::json read_json_file(const std::string& path, std::string_view what);

class JsonIn {
 public:
  // The root of a document; `origin` (a file name) prefixes every message.
  JsonIn(const nlohmann::json& root, std::string origin) : j_(&root), origin_(std::move(origin)) {}

  const nlohmann::json& raw() const { return *j_; }
  const std::string& path() const { return path_; }  // "" at the root, else e.g. "cells[2][3]"

  // Members of an object. at(): required (InputError when absent); find(): absent or null ->
  // nullopt. Both first require this value to be an object.
  JsonIn at(std::string_view key) const;
  std::optional<JsonIn> find(std::string_view key) const;
  bool has(std::string_view key) const { return find(key).has_value(); }
  // Elements of an array (requires array(); i < its size).
  JsonIn operator[](std::size_t i) const;

  // Type checks with bounds; each returns the value or throws InputError naming the path.
  void object() const;
  std::size_t array(std::size_t min_size = 0, std::size_t max_size = std::numeric_limits<std::size_t>::max()) const;
  std::int64_t integer(std::int64_t lo = std::numeric_limits<std::int64_t>::min(),
                       std::int64_t hi = std::numeric_limits<std::int64_t>::max()) const;
  std::uint64_t unsigned_integer(std::uint64_t hi = std::numeric_limits<std::uint64_t>::max()) const;
  double number(double lo = -std::numeric_limits<double>::max(), double hi = std::numeric_limits<double>::max()) const;
  bool boolean() const;
  std::string string(std::size_t max_size = std::size_t(1) << 20) const;
  // Optional members with a default (absent or null -> fallback).
  std::int64_t integer_or(std::string_view key, std::int64_t fallback, std::int64_t lo, std::int64_t hi) const;
  std::uint64_t unsigned_or(std::string_view key, std::uint64_t fallback,
                            std::uint64_t hi = std::numeric_limits<std::uint64_t>::max()) const;
  double number_or(std::string_view key, double fallback, double lo, double hi) const;
  bool boolean_or(std::string_view key, bool fallback) const;
  std::string string_or(std::string_view key, std::string fallback) const;

  // InputError "ORIGIN: PATH: problem" (or "ORIGIN: problem" at the root).
  InputError error(std::string_view problem) const;

 private:
  JsonIn(const nlohmann::json& j, const JsonIn& parent, std::string path)
      : j_(&j), origin_(parent.origin_), path_(std::move(path)) {}
  std::string got() const;  // the value, shortened, for messages
  const nlohmann::json* j_;
  std::string origin_, path_;
};

}  // namespace tilekit
