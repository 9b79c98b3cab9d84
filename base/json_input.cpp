#include "base/json_input.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "base/input.hpp"

namespace tilekit {

int json_nesting_depth(std::string_view text, int limit, std::size_t* at) {
  int depth = 0, deepest = 0;
  bool in_string = false, escaped = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
      continue;
    }
    if (c == '"') in_string = true;
    else if (c == '[' || c == '{') {
      if (++depth > deepest) deepest = depth;
      if (deepest > limit) {
        if (at) *at = i;
        return deepest;
      }
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

namespace {

// nlohmann's messages start with "[json.exception.parse_error.101] "; users need the rest.
std::string without_tag(const char* what) {
  std::string_view s(what);
  if (s.starts_with("[json.exception.")) {
    auto close = s.find("] ");
    if (close != std::string_view::npos) s.remove_prefix(close + 2);
  }
  return std::string(s);
}

std::string child_key(const std::string& parent, std::string_view key) {
  bool plain = !key.empty();
  for (char c : key)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) plain = false;
  if (plain) return parent.empty() ? std::string(key) : fmt::format("{}.{}", parent, key);
  return fmt::format("{}[{}]", parent, nlohmann::json(std::string(key)).dump(-1, ' ', false,
                                                                                nlohmann::json::error_handler_t::replace));
}

}  // namespace

nlohmann::json parse_json_input(std::string_view text, const std::string& origin, int max_depth) {
  std::size_t at = 0;
  if (json_nesting_depth(text, max_depth, &at) > max_depth) {
    const std::string_view before = text.substr(0, at);
    const auto line = 1 + std::count(before.begin(), before.end(), '\n');
    throw InputError(fmt::format("{}:{}: invalid JSON: nested deeper than {} levels", origin, line, max_depth));
  }
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: invalid JSON: {}", origin, without_tag(e.what())));
  }
}

nlohmann::json read_json_file(const std::string& path, std::string_view what) {
  return parse_json_input(read_input_file(path, what), path);
}

InputError JsonIn::error(std::string_view problem) const {
  if (path_.empty()) return InputError(fmt::format("{}: {}", origin_, problem));
  return InputError(fmt::format("{}: {}: {}", origin_, path_, problem));
}

std::string JsonIn::got() const {
  std::string s = j_->dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (s.size() > 40) s = s.substr(0, 37) + "...";
  return s;
}

void JsonIn::object() const {
  if (!j_->is_object()) throw error(fmt::format("expected a JSON object, got {}", got()));
}

JsonIn JsonIn::at(std::string_view key) const {
  object();
  auto it = j_->find(key);
  if (it == j_->end()) throw error(fmt::format("missing \"{}\"", key));
  return JsonIn(*it, *this, child_key(path_, key));
}

std::optional<JsonIn> JsonIn::find(std::string_view key) const {
  object();
  auto it = j_->find(key);
  if (it == j_->end() || it->is_null()) return std::nullopt;
  return JsonIn(*it, *this, child_key(path_, key));
}

JsonIn JsonIn::operator[](std::size_t i) const {
  if (!j_->is_array() || i >= j_->size()) throw error(fmt::format("no element {}", i));
  return JsonIn((*j_)[i], *this, fmt::format("{}[{}]", path_, i));
}

std::size_t JsonIn::array(std::size_t min_size, std::size_t max_size) const {
  if (!j_->is_array()) throw error(fmt::format("expected an array, got {}", got()));
  const std::size_t n = j_->size();
  if (n < min_size || n > max_size) {
    if (min_size == max_size) throw error(fmt::format("expected an array of {} elements, got {}", min_size, n));
    throw error(fmt::format("expected an array of {} to {} elements, got {}", min_size, max_size, n));
  }
  return n;
}

std::int64_t JsonIn::integer(std::int64_t lo, std::int64_t hi) const {
  bool ok = false;
  std::int64_t v = 0;
  if (j_->is_number_unsigned()) {
    const auto u = j_->get<std::uint64_t>();
    ok = u <= std::uint64_t(std::numeric_limits<std::int64_t>::max());
    v = std::int64_t(u);
  } else if (j_->is_number_integer()) {
    ok = true;
    v = j_->get<std::int64_t>();
  }
  if (!ok || v < lo || v > hi) throw error(fmt::format("expected an integer between {} and {}, got {}", lo, hi, got()));
  return v;
}

std::uint64_t JsonIn::unsigned_integer(std::uint64_t hi) const {
  bool ok = false;
  std::uint64_t v = 0;
  if (j_->is_number_unsigned()) {
    ok = true;
    v = j_->get<std::uint64_t>();
  } else if (j_->is_number_integer() && j_->get<std::int64_t>() >= 0) {
    ok = true;
    v = std::uint64_t(j_->get<std::int64_t>());
  }
  if (!ok || v > hi) throw error(fmt::format("expected an integer between 0 and {}, got {}", hi, got()));
  return v;
}

double JsonIn::number(double lo, double hi) const {
  if (!j_->is_number()) throw error(fmt::format("expected a number, got {}", got()));
  const double v = j_->get<double>();
  if (!std::isfinite(v) || v < lo || v > hi) throw error(fmt::format("expected a number between {} and {}, got {}", lo, hi, got()));
  return v;
}

bool JsonIn::boolean() const {
  if (!j_->is_boolean()) throw error(fmt::format("expected true or false, got {}", got()));
  return j_->get<bool>();
}

std::string JsonIn::string(std::size_t max_size) const {
  if (!j_->is_string()) throw error(fmt::format("expected a string, got {}", got()));
  const auto& s = j_->get_ref<const std::string&>();
  if (s.size() > max_size) throw error(fmt::format("string of {} bytes, more than {}", s.size(), max_size));
  return s;
}

std::int64_t JsonIn::integer_or(std::string_view key, std::int64_t fallback, std::int64_t lo, std::int64_t hi) const {
  auto v = find(key);
  return v ? v->integer(lo, hi) : fallback;
}

std::uint64_t JsonIn::unsigned_or(std::string_view key, std::uint64_t fallback, std::uint64_t hi) const {
  auto v = find(key);
  return v ? v->unsigned_integer(hi) : fallback;
}

double JsonIn::number_or(std::string_view key, double fallback, double lo, double hi) const {
  auto v = find(key);
  return v ? v->number(lo, hi) : fallback;
}

bool JsonIn::boolean_or(std::string_view key, bool fallback) const {
  auto v = find(key);
  return v ? v->boolean() : fallback;
}

std::string JsonIn::string_or(std::string_view key, std::string fallback) const {
  auto v = find(key);
  return v ? v->string() : std::move(fallback);
}

}  // namespace tilekit
