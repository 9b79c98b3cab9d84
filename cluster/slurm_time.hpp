#pragma once
// Slurm wall times (sbatch --time) and the lead of the wall-time warning signal.
#include <string_view>

namespace tilekit::cluster {

// Seconds in a Slurm time string: M, M:S, H:M:S, D-H, D-H:M, D-H:M:S (sbatch --time), each
// number at most 9 digits. Throws InputError naming `field` (the request field the text came
// from, "time" or "merge_time") for anything else (including UNLIMITED: a signal needs a finite
// limit).
long parse_slurm_time(std::string_view text, std::string_view field = "time");

// The default signal lead for a wall time of `seconds`: 120 s, at most half the limit.
int default_signal_seconds(long seconds);

}  // namespace tilekit::cluster
