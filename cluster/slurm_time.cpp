#include "cluster/slurm_time.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <regex>
#include <string>

#include "base/error.hpp"

namespace tilekit::cluster {

long parse_slurm_time(std::string_view text, std::string_view field) {
  // sbatch --time formats: M, M:S, H:M:S, D-H, D-H:M, D-H:M:S. Nine digits at most per number,
  // so that the sum below cannot overflow (std::stol of 20 digits would throw out_of_range).
  static const std::regex re(
      R"(^(?:(\d{1,9})-(\d{1,9})(?::(\d{1,9})(?::(\d{1,9}))?)?|(\d{1,9})(?::(\d{1,9})(?::(\d{1,9}))?)?)$)");
  std::cmatch m;
  const std::string s(text);
  if (!std::regex_match(s.c_str(), m, re))
    throw InputError(fmt::format("`{}` '{}': expected minutes, M:S, H:M:S, D-H, D-H:M or D-H:M:S", field, text));
  auto num = [&](int i) { return m[i].matched ? std::stol(m[i].str()) : 0L; };
  long secs = 0;
  if (m[1].matched) {
    secs = num(1) * 86400 + num(2) * 3600 + num(3) * 60 + num(4);
  } else if (m[7].matched) {
    secs = num(5) * 3600 + num(6) * 60 + num(7);
  } else if (m[6].matched) {
    secs = num(5) * 60 + num(6);
  } else {
    secs = num(5) * 60;
  }
  if (secs <= 0) throw InputError(fmt::format("`{}` '{}': the wall time must be positive", field, text));
  return secs;
}

int default_signal_seconds(long seconds) {
  return static_cast<int>(std::max(1L, std::min(120L, seconds / 2)));
}

}  // namespace tilekit::cluster
