#pragma once
// The JSON files of aperiodic/data/ (search records such as smallest-chain.json), embedded at
// build time (cmake/embed_files.cmake), so that an installed `tilekit` needs no data directory.
#include <vector>

#include "tilesets/reference_data.hpp"

namespace tilekit {

const std::vector<EmbeddedFile>& recorded_data();

}  // namespace tilekit
