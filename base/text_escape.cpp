#include "base/text_escape.hpp"

namespace tilekit {

std::string html_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) switch (c) {
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
        out += "&#39;";
        break;
      default:
        out += c;
    }
  return out;
}

std::string comment_text(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    const auto u = static_cast<unsigned char>(c);
    const char safe = u < 0x20 || u >= 0x7f ? '?' : c == '\\' ? '/' : c;
    // "*/" would end a block comment, "/*" open one inside it.
    if (!out.empty() && ((out.back() == '*' && safe == '/') || (out.back() == '/' && safe == '*'))) out += ' ';
    out += safe;
  }
  return out;
}

}  // namespace tilekit
