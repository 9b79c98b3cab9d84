#pragma once
// The libraries name the fields of their requests, never flags (base/error.hpp's RequestError,
// checked by scripts/check-layers.sh): here the CLI maps each field to the flag that sets it, so
// that every error reads in flag terms ("`shard` must be I/N" -> "--shard must be I/N").
#include <string>
#include <string_view>

#include "base/error.hpp"

namespace tilekit::cli {

// The flag that sets a request field: "--" and the field's name with '-' for '_' ("max_depth":
// "--max-depth"), or the flag of a field whose flag is spelled otherwise ("colours": "--colors").
std::string flag_of_field(std::string_view field);

// `message` with every "`field`" in it replaced by the field's flag.
std::string in_flag_terms(std::string_view message);

// A RequestError's message in flag terms: what the CLI prints.
inline std::string in_flag_terms(const RequestError& e) {
  return in_flag_terms(std::string_view(e.what()));
}

}  // namespace tilekit::cli
