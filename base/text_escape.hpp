#pragma once
// User text (file names, set names, manifest fields) written into the languages of the outputs,
// escaped for each, so that a hostile name stays text: HTML and SVG (XML) text and attribute
// values, and comments of C headers and GLSL shaders. JSON is escaped by nlohmann-json; shell
// scripts quote with cluster/job_scripts.hpp's shell_quote.
#include <string>
#include <string_view>

namespace tilekit {

// `text` with & < > " ' as character references: safe as HTML or XML text and in a quoted
// attribute value.
std::string html_escape(std::string_view text);

// `text` as one line safe inside a C or GLSL comment, block (/* */) or line (//): control
// characters and bytes outside ASCII become '?', a backslash (a line continuation at the end of a
// line comment) becomes '/', and "*/" and "/*" are broken apart ("* /", "/ *").
std::string comment_text(std::string_view text);

}  // namespace tilekit
