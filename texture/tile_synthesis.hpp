#pragma once
// Texture tiles synthesised from an exemplar (thesis sec. 5.3): the complete corner set over C
// colours by the method of Ng et al. (corner_texture_tiles.cpp) and the complete Wang set by the method
// of Cohen et al. 2003 (wang_texture_tiles.cpp), with the patch choice searched, not drawn at random.
// Seeded and deterministic: the same seed gives the same bytes on any thread count.
#include <array>
#include <cstdint>
#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "atlas/atlas_image.hpp"
#include "texture/exemplar.hpp"
#include "tilesets/tile.hpp"

namespace tilekit {

struct SynthesisOptions {
  TileKind kind = TileKind::Corner;
  std::uint32_t colours = 2;
  int tile_px = 128;
  std::uint64_t seed = 1;
  int threads = 1;
  // Candidate exemplar positions tried per corner patch (or diamond) and round of the search;
  // 0 keeps the first random draw (no search: the "plain minimum-error cut" baseline).
  int search = 96;  // at most kMaxSynthesisSearch
  int rounds = 3;
  int centre_candidates = 32;  // corner tiles: centre patches scored per tile on the ring where the cut runs
  int centre_cuts = 2;         // of those, the best this many get the full graph cut
  bool progress = false;
};

// What one sample covers, relative to the tile: how far samples overlap (w), and for corner
// tiles the margin between the centre patch's circle and the tile border.
struct TileGeometry {
  int n = 0, half = 0;
  int overlap = 0;  // w: half-width of the band in which two samples overlap and a cut runs
  int patch = 0;    // side of a corner patch / Wang diamond sample: n + 2w
  int margin = 0;   // corner tiles: the centre patch stays inside the circle of radius n/2 - margin
  int radius = 0;   // n/2 - margin
  int inner = 0;    // the cross is forced under the centre patch up to radius - inner
  int arm = 0;      // rows of a corner pair cut on each side of the tile border
  explicit TileGeometry(int tile_px);
};

inline constexpr int kMaxSynthesisSearch = 1 << 16;

struct TextureTileSet {
  TileKind kind = TileKind::Corner;
  std::uint32_t colours = 0;
  int tile_px = 0;
  std::uint64_t seed = 0;
  std::vector<Image> tiles;  // by tile index (thesis eq. 2.2 / 2.5)
  // Per tile and pixel, the sample it was copied from (corner patch c: c; centre patch of tile t:
  // C + t; Wang horizontal diamond h: h, vertical diamond v: C + v; naive: the tile index).
  std::vector<std::vector<std::uint32_t>> sources;
  std::uint32_t shared_sources = 0;  // ids below this are samples shared by several tiles, the rest belong to one tile
  std::vector<std::array<int, 2>> samples;  // exemplar positions of the corner patches / diamonds
  double cut_error_initial = 0;  // summed boundary-cut error (in exemplar neighbour differences) of the first draw
  double cut_error = 0;          // the same after the search
  double centre_cost = 0;        // corner tiles: mean graph-cut cost of the centre patches
  double seconds = 0;
  std::string method;  // "ng-corner", "cohen-wang" or "naive"
};

// InputError (exit 2) for options the exemplar cannot serve: tile size odd, out of 16..1024 or
// larger than the exemplar allows, C out of 1..16, or a set too large to hold.
void check_synthesis_options(const Exemplar& e, const SynthesisOptions& o);
TextureTileSet synthesize_tiles(const Exemplar& e, const SynthesisOptions& o);
TextureTileSet synthesize_corner_tiles(const Exemplar& e, const SynthesisOptions& o);
TextureTileSet synthesize_wang_tiles(const Exemplar& e, const SynthesisOptions& o);
// Baseline: every tile an independent random square of the exemplar (naive abutment).
TextureTileSet naive_tiles(const Exemplar& e, const SynthesisOptions& o);

// A uniformly random exemplar position for a side x side sample.
std::array<int, 2> random_sample_position(const Exemplar& e, int side, std::uint64_t seed);

// Draws positions of side x side samples uniformly among the typical ones: those whose activity
// (mean step per channel between neighbouring pixels inside the sample) lies within [0.85, 1.25] times
// the median over all positions. Without it, a search for low cut error drifts to bland samples
// (a flat brick face) whose seams are invisible only because there is nothing to see.
// The mean step (per channel) across the tile border lines a sample supplies: they run through
// the sample's centre (pixel boundary `centre`, exemplar coordinates), `half` pixels to either
// side, along the row boundary (a horizontal border) and/or the column boundary (a vertical
// border). The seam goal of the search: within kBorderTolerance of the sample's own mean step
// (SampleDraw::activity), so that tile borders look like the texture on either side of them.
double border_activity(const Exemplar& e, std::array<int, 2> centre, int half, bool row, bool column);
inline constexpr double kBorderTolerance = 0.04;

class SampleDraw {
 public:
  SampleDraw(const Exemplar& e, int side);
  std::array<int, 2> operator()(std::uint64_t seed) const;
  double activity(int x, int y) const;  // of the sample with top-left (x, y)
  double median_activity() const { return median_; }

 private:
  const Exemplar* e_;
  int side_;
  std::vector<double> integral_;  // (width + 1) x (height + 1) summed-area table of pixel activity
  double median_ = 0;
};

// The score of a sample in the search: first how far its border lines miss the seam goal (0 within
// kBorderTolerance of its own activity, see border_activity), then the cut error it takes part in.
using SampleScore = std::pair<double, double>;
double seam_goal_miss(double border_to_own_activity);

// The search over sample positions (corner patches, Wang diamonds): coordinate descent, `o.rounds`
// rounds over the samples; each round draws `o.search` candidates for sample j (from `draw`,
// seeded by o.seed, the round and j), scores them in parallel with score(j, samples with j
// replaced), and keeps the best if it beats the current one (ties by candidate order, so the
// result does not depend on the thread count).
void search_samples(std::vector<std::array<int, 2>>& samples, const SampleDraw& draw, const SynthesisOptions& o,
                    const std::function<SampleScore(std::size_t, const std::vector<std::array<int, 2>>&)>& score);

// The tiles in index order, about square, `gap` pixels apart on white (the README picture).
Image tile_set_sheet(const TextureTileSet& s, int gap = 4);
nlohmann::json tile_set_json(const TextureTileSet& s);
// DIR/tile-NNNN.png per tile (named by index, as `tilekit atlas build --tiles` reads them),
// DIR/tiles.json (the report) and DIR/tileset.png (the sheet); files written atomically.
void write_tile_set(const TextureTileSet& s, const std::string& dir, const std::string& exemplar);

}  // namespace tilekit
