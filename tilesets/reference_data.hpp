#pragma once
// The files of tilesets/data/, embedded at build time (cmake/embed_files.cmake).
#include <string_view>
#include <vector>

namespace tilekit {

struct EmbeddedFile {
  std::string_view name;  // file name, e.g. "culik-13.tiles"
  std::string_view text;
};

const std::vector<EmbeddedFile>& reference_data();

}  // namespace tilekit
