#include "cli/numeric_flags.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <cstdint>

namespace tilekit::cli {

namespace {

// The value as shown in a message: long values shortened.
std::string shown(const std::string& text) {
  return text.size() > 40 ? text.substr(0, 37) + "..." : text;
}

// The CLI11 type name of an option's value ("INT", "UINT", "FLOAT"), "" for anything else. The
// name may carry the descriptions of the option's validators after a ':' or a space.
std::string number_type(const CLI::Option* opt) {
  if (opt->get_expected_min() == 0) return "";  // a flag without a value
  const std::string name = opt->get_type_name();
  for (const char* t : {"UINT", "INT", "FLOAT"}) {
    const std::string type = t;
    if (name.compare(0, type.size(), type) == 0 &&
        (name.size() == type.size() || name[type.size()] == ':' || name[type.size()] == ' '))
      return type;
  }
  return "";
}

void add_checks(CLI::App& app) {
  for (CLI::Option* opt : app.get_options()) {
    const std::string type = number_type(opt);
    if (type.empty()) continue;
    opt->transform(CLI::Validator([type](std::string& text) { return strict_number(text, type); }, ""));
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) add_checks(*sub);
}

}  // namespace

std::string strict_number(std::string& text, const std::string& type) {
  const char* first = text.data();
  const char* last = first + text.size();
  if (type == "FLOAT") {
    double v = 0;
    auto [p, ec] = std::from_chars(first, last, v);
    if (text.empty() || ec == std::errc::invalid_argument || p != last || !std::isfinite(v) ||
        (ec == std::errc() && std::isnan(v)))
      return fmt::format("expected a finite decimal number, got '{}'", shown(text));
    if (ec == std::errc::result_out_of_range)
      return fmt::format("'{}' is out of the range of a double-precision number", shown(text));
    return "";
  }
  const bool is_unsigned = type == "UINT";
  if (text.empty() || (*first != '-' && (*first < '0' || *first > '9')) || (is_unsigned && *first == '-'))
    return fmt::format("expected {} decimal integer, got '{}'", is_unsigned ? "a non-negative" : "a",
                       shown(text));
  if (is_unsigned) {
    std::uint64_t v = 0;
    auto [p, ec] = std::from_chars(first, last, v);
    if (ec == std::errc::result_out_of_range && p == last)
      return fmt::format("'{}' is larger than the largest value, {}", shown(text), UINT64_MAX);
    if (ec != std::errc() || p != last) return fmt::format("expected a non-negative decimal integer, got '{}'", shown(text));
    text = std::to_string(v);
    return "";
  }
  std::int64_t v = 0;
  auto [p, ec] = std::from_chars(first, last, v);
  if (ec == std::errc::result_out_of_range && p == last)
    return fmt::format("'{}' is out of the range of a 64-bit integer", shown(text));
  if (ec != std::errc() || p != last) return fmt::format("expected a decimal integer, got '{}'", shown(text));
  text = std::to_string(v);
  return "";
}

void check_numeric_flags(CLI::App& app) { add_checks(app); }

const CLI::Validator& non_empty_text() {
  static const CLI::Validator v(
      [](std::string& text) { return text.empty() ? std::string("may not be empty") : std::string(); }, "");
  return v;
}

const CLI::Validator& positive_number() {
  static const CLI::Validator v(
      [](std::string& text) {
        double x = 0;
        auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), x);
        return ec == std::errc() && p == text.data() + text.size() && x > 0
                   ? std::string()
                   : fmt::format("expected a number > 0, got '{}'", shown(text));
      },
      "");
  return v;
}

const CLI::Validator& non_negative_seconds() {
  static const CLI::Validator v(
      [](std::string& text) {
        double s = 0;
        auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), s);
        return ec == std::errc() && p == text.data() + text.size() && s >= 0
                   ? std::string()
                   : fmt::format("expected a number of seconds >= 0, got '{}'", shown(text));
      },
      "");
  return v;
}

}  // namespace tilekit::cli
