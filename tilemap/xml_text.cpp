#include "tilemap/xml_text.hpp"

#include <fmt/format.h>

#include "base/error.hpp"
#include "base/input.hpp"

namespace tilekit::tilemap {

std::string xml_escape(std::string_view text, std::string_view what) {
  if (invalid_utf8_offset(text) != std::string_view::npos) throw InputError(fmt::format("{} is not UTF-8 text", what));
  std::string out;
  out.reserve(text.size());
  for (const char ch : text) {
    const auto u = static_cast<unsigned char>(ch);
    if (u < 0x20 && ch != '\t' && ch != '\n' && ch != '\r')
      throw InputError(fmt::format("{} holds control character 0x{:02x}, which XML cannot carry", what, u));
    switch (ch) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      case '\t':
        out += "&#9;";
        break;
      case '\n':
        out += "&#10;";
        break;
      case '\r':
        out += "&#13;";
        break;
      default:
        out += ch;
    }
  }
  return out;
}

}  // namespace tilekit::tilemap
