#pragma once
// The example texture that texture tiles are synthesised from (thesis sec. 5.3), and where the
// real textures live: CC0 brick, grass and gravel from the Debian package python3-skimage,
// fetched by scripts/fetch-textures.sh (never committed).
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "atlas/atlas_image.hpp"

namespace tilekit {

struct Exemplar {
  Image image;
  std::string name;                 // the file it came from
  double neighbour_difference = 0;  // mean colour distance of 4-adjacent pixels: the unit of seam costs
  double mean_step = 0;             // mean absolute step per channel of 4-adjacent pixels (seam_metrics.hpp)
  int width() const { return image.width; }
  int height() const { return image.height; }
  const std::uint8_t* at(int x, int y) const { return image.at(x, y); }
};

// Smallest exemplar side accepted at all; synthesis asks for more (see tile_synthesis.hpp).
inline constexpr int kMinExemplarSide = 16;

// Reads a PNG or JPEG; a name without a file ("grass") is looked up among the fetched real
// textures. InputError (exit 2) naming the file when it is missing, cannot be decoded or is
// smaller than kMinExemplarSide.
Exemplar load_exemplar(const std::string& path_or_name);
Exemplar exemplar_from_image(Image image, std::string name);

// Euclidean RGB distance between two pixels (0 .. 441.7).
inline float colour_distance(const std::uint8_t* a, const std::uint8_t* b) {
  const int dr = int(a[0]) - int(b[0]), dg = int(a[1]) - int(b[1]), db = int(a[2]) - int(b[2]);
  return std::sqrt(float(dr * dr + dg * dg + db * db));
}
// Mean absolute difference over R, G and B (what the seam ratio averages).
inline float channel_step(const std::uint8_t* a, const std::uint8_t* b) {
  return float(std::abs(int(a[0]) - int(b[0])) + std::abs(int(a[1]) - int(b[1])) + std::abs(int(a[2]) - int(b[2]))) /
         3.0f;
}

// The folder of fetched real textures: $TILEKIT_TEXTURES, else $XDG_CACHE_HOME/tilekit/textures,
// else ~/.cache/tilekit/textures.
std::string texture_cache_dir();
// The fetched real textures the tests, benchmarks and the main job use.
const std::vector<std::string>& real_texture_names();  // brick, grass, gravel
// The file of a fetched real texture, or "" when it has not been fetched.
std::string real_texture_path(const std::string& name);

}  // namespace tilekit
