#pragma once
// The example texture that texture tiles are synthesised from (thesis sec. 5.3), its dominant
// period, and where the real textures live: scikit-image's brick, grass and gravel, GIMP's
// patterns and OpenArena's textures, fetched from Debian packages by scripts/fetch-textures.sh
// (never committed).
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "image/image.hpp"

namespace tilekit {

struct Exemplar {
  Image image;
  std::string name;  // the file it came from
  // A tileable exemplar (a pattern made to repeat, like GIMP's and games' textures) is held as
  // copies side by side, so any sample of the torus is a plain window; wrap_w x wrap_h is the
  // torus (0: not tileable).
  int wrap_w = 0, wrap_h = 0;
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
Exemplar load_exemplar(const std::string& path_or_name, bool tileable = false);
Exemplar exemplar_from_image(Image image, std::string name, bool tileable = false);

// The exemplar resampled (bilinear) by sx horizontally and sy vertically (the torus with it).
Exemplar resample_exemplar(const Exemplar& e, double sx, double sy);
// The same for any image (any depth and channels): its w0 x h0 top-left part resampled to
// round(w0 sx) x round(h0 sy) (at least kMinExemplarSide), a torus when `torus`.
Image resample_image(const Image& src, int w0, int h0, double sx, double sy, bool torus);

// The dominant period of the exemplar along x and along y (0: none), from the autocorrelation
// of its gradient magnitude (so that mortar lines and joints count, not slow shading): among the
// local maxima in 6 .. side/3 whose rise above the lowest value at shorter lags is at least
// kPeriodProminence of the way to 1, the shortest lag that rises within 3 % as high as the
// highest (multiples of the period rise as high); between lags by a parabola through the peak,
// and on a torus the nearest whole fraction of it. Staggered bricks give the full bond (two rows),
// since only there do both the joints and the mortar lines align. An axis without a period at the
// exemplar's own resolution is looked at again with the luminance smoothed (a Gaussian of each
// of kPeriodScales pixels in turn): on rough bricks and grainy planks the grain's gradient hides
// the joints' until it is smoothed away. Such a look keeps only periods of at least kPeriodSpan
// times its smoothing (32 px): structure that the smoothing leaves standing, not a regular fine
// pattern that it uncovers. The weak repeats are the first look's. Beyond 512 rows (columns) an
// autocorrelation along x (y) sums evenly spaced rows (columns), 512 of them or a few more, here
// and in choose_tile_size: a 2048² exemplar's defaults took 44-48 s, now 14-16 s.
struct ExemplarPeriod {
  double x = 0, y = 0;
  double strength_x = 0, strength_y = 0;  // that rise, as a fraction of the way to 1
  // The largest rise of a local maximum below kPeriodProminence, per axis (0: none): a repeat too
  // weak to keep, which still says the texture is structured.
  double weak_x = 0, weak_y = 0;
};
inline constexpr double kPeriodProminence = 0.2;
inline constexpr double kPeriodScales[] = {2.0};
inline constexpr double kPeriodSpan = 16;
// Structure likely but not all found: a period along one axis only (courses without head
// joints, planks without ends), or a repeat of at least kStructureHint along an axis without one.
inline constexpr double kStructureHint = 0.1;
inline bool structure_likely(const ExemplarPeriod& p) {
  const bool x = p.x > 0, y = p.y > 0;
  if (x && y) return false;
  return x != y || p.weak_x >= kStructureHint || p.weak_y >= kStructureHint;
}
ExemplarPeriod dominant_period(const Exemplar& e);
// The same at one scale alone: the luminance smoothed by a Gaussian of `sigma` pixels first (none at 0).
ExemplarPeriod period_at_scale(const Exemplar& e, double sigma);

// `texture tiles --tile-px auto`: a tile size from the exemplar's feature scale. With a period
// (dominant_period, or the user's): the least multiple of the larger period of at least
// kPeriodicTilePx, so a tile holds whole periods, as few as make 64 px (one where the period is
// that or more; not the nearest multiple, which the 64-px floor could stretch by more than the
// synthesis' 25 %). Against the multiple nearest 128 px this brought the tuning walls' seam ratio
// under 1.10 and oa-brick's line continuity from 1.19 to 1.02 times the exemplar's (BENCHMARKS.md,
// "Texture structure and tile size"). Otherwise the size D of the largest features: the least
// lag at which the autocorrelation of its luminance (along x and y, averaged) falls to
// kFeatureCorrelation (a texture of blobs of diameter D decorrelates at about D; where it never
// falls that low, slow shading, the lag where it is lowest), and tiles of the least multiple of
// 32 px that holds two features across. Both clamped to 64 .. 512 px and to what the exemplar
// allows (tile_px + 16 <= its smaller side, tile_synthesis.cpp).
inline constexpr double kFeatureCorrelation = 0.1;
inline constexpr double kPeriodicTilePx = 64;
struct TileSizeChoice {
  int tile_px = 128;
  double feature_px = 0;  // D (0 with a period)
  double period = 0;      // the larger period used (0: none)
  std::string reason;     // one line for the user
};
TileSizeChoice choose_tile_size(const Exemplar& e, const ExemplarPeriod& period);

// Euclidean RGB distance between two pixels (0 .. 441.7).
inline float colour_distance(const std::uint8_t* a, const std::uint8_t* b) {
  const int dr = int(a[0]) - int(b[0]), dg = int(a[1]) - int(b[1]), db = int(a[2]) - int(b[2]);
  return std::sqrt(float(dr * dr + dg * dg + db * db));
}
// Luminance with Rec. 601 weights (texture_analysis.hpp measures the same).
inline float luma(const std::uint8_t* p) {
  return 0.299f * p[0] + 0.587f * p[1] + 0.114f * p[2];
}
// Mean absolute difference over R, G and B (what the seam ratio averages).
inline float channel_step(const std::uint8_t* a, const std::uint8_t* b) {
  return float(std::abs(int(a[0]) - int(b[0])) + std::abs(int(a[1]) - int(b[1])) + std::abs(int(a[2]) - int(b[2]))) /
         3.0f;
}

// The folder of fetched real textures: $TILEKIT_TEXTURES, else $XDG_CACHE_HOME/tilekit/textures,
// else ~/.cache/tilekit/textures.
std::string texture_cache_dir();
// The fetched real textures the benchmarks and the main job compare on: scikit-image's brick,
// grass and gravel, GIMP's patterns (gimp-*) and OpenArena's textures (oa-*); the last two are
// tileable.
struct RealTexture {
  std::string name;
  bool tileable = false;
};
const std::vector<RealTexture>& real_textures();
bool is_tileable_real_texture(const std::string& name);
// The file of a fetched real texture (NAME.png, .jpg, .tga or .ppm in the cache), or "".
std::string real_texture_path(const std::string& name);

}  // namespace tilekit
