#pragma once
// Text for Tiled's XML files: attribute values escaped, so that a user's name with <, &, " or '
// reads back as written.
#include <string>
#include <string_view>

namespace tilekit::tilemap {

// `text` with & < > " ' as entities. Throws InputError naming `what` unless `text` is UTF-8 of
// characters XML 1.0 allows (no control characters other than tab, line feed, carriage return).
std::string xml_escape(std::string_view text, std::string_view what);

}  // namespace tilekit::tilemap
