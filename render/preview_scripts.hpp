#pragma once
// The preview page's scripts, render/preview_tables.js and render/preview.js, embedded at build
// time (cmake/embed_files.cmake, render/CMakeLists.txt): the JavaScript lives in its own files,
// where node can load and test it (tests/render/preview_golden.test.js). Defined in the build's
// generated preview_scripts.cpp.
#include <vector>

#include "tilesets/reference_data.hpp"  // EmbeddedFile

namespace tilekit {

// By file name: "preview.js", "preview_tables.js".
const std::vector<EmbeddedFile>& preview_scripts();

}  // namespace tilekit
