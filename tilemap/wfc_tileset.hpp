#pragma once
// The tile sets of Wave Function Collapse's "simple tiled model" (mxgmn/WaveFunctionCollapse,
// MIT): an XML file listing tiles with a symmetry class (X, I, L, T, \, F; X when omitted), an
// optional weight (1 when omitted) and the allowed left/right neighbour pairs ("name" or
// "name k", k a rotation or reflection), with named subsets; one PNG per tile in a folder named
// after the file. Read as the reference reads it (SimpleTiledModel.cs): each tile expands to its
// 1, 2, 4 or 8 orientations ("name k", k counting rotations by 90 degrees, then reflections), each
// with the tile's weight, its image rotated or reflected as the reference does, and every pair
// expands to the four pairs its symmetries imply, horizontally and vertically.
// Refused (InputError, exit 2): not such XML, an unknown symmetry, a neighbour naming an unknown
// tile or orientation, a missing or non-square image, images of different sizes, an unknown subset.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "image/image.hpp"

namespace tilekit::tilemap {

inline constexpr std::uint64_t kMaxWfcXmlBytes = std::uint64_t(16) << 20;

struct WfcTileset {
  std::string name;    // the file's stem ("Knots")
  std::string subset;  // "" = every tile
  int tile_px = 0;
  std::vector<std::string> names;  // orientation t: "corner 1" (the reference's tilenames)
  std::vector<double> weights;
  std::vector<Image> images;  // RGBA, tile_px x tile_px; empty when read without images
  // (d, a, b): b may be a's neighbour in direction d (0 north, 1 east, 2 south, 3 west); each
  // allowed pair once, listed from both sides.
  std::vector<std::array<int, 3>> pairs;
};

// `images`: also read the tile images (from the folder named after the XML file beside it).
WfcTileset read_wfc_tileset(const std::string& xml_path, const std::string& subset, bool images = true);

// The orientation named "name" or "name k" ("name:k" too), or -1.
int wfc_tile_number(const WfcTileset& set, const std::string& name);

}  // namespace tilekit::tilemap
