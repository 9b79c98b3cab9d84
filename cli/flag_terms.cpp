#include "cli/flag_terms.hpp"

#include <utility>

namespace tilekit::cli {
namespace {

// The fields whose flags are not "--" plus the field's name: the library spells the thesis'
// words (colours), the CLI keeps the flags users type (--colors).
constexpr std::pair<std::string_view, std::string_view> kFlagSpelledOtherwise[] = {
    {"colours", "--colors"},
    {"edge_colours", "--edge-colors"},
    {"candidates", "--candidate"},
    {"sources", "--source"},
    {"max_aniso", "--aniso"},
    {"probes", "--estimate"},
    {"probe_seconds", "--estimate-seconds"},
    {"shard_args", "--pack-arg"},
    {"sbatch_args", "--sbatch-arg"},
};

bool is_field_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
}

}  // namespace

std::string flag_of_field(std::string_view field) {
  for (const auto& [name, flag] : kFlagSpelledOtherwise)
    if (name == field) return std::string(flag);
  std::string flag = "--";
  for (char c : field) flag += c == '_' ? '-' : c;
  return flag;
}

std::string in_flag_terms(std::string_view message) {
  std::string out;
  std::size_t i = 0;
  while (i < message.size()) {
    // "`name`" with a field's name in it (lower-case letters, digits, '_'): the flag.
    if (message[i] == '`') {
      std::size_t j = i + 1;
      while (j < message.size() && is_field_char(message[j])) ++j;
      if (j > i + 1 && j < message.size() && message[j] == '`') {
        out += flag_of_field(message.substr(i + 1, j - i - 1));
        i = j + 1;
        continue;
      }
    }
    out += message[i++];
  }
  return out;
}

}  // namespace tilekit::cli
