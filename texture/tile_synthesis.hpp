#pragma once
// Texture tiles synthesised from an exemplar (thesis sec. 5.3) for the complete corner set
// (corner_texture_tiles.cpp, after Ng et al.) and the complete Wang set (wang_texture_tiles.cpp,
// after Cohen et al. 2003) over C colours, made so that a surface does not show the tile grid:
// the samples that tiles share cover only narrow bands along the borders, and a tile-unique
// centre patch, from a region of the exemplar no other tile uses, covers the rest. The shared
// samples are searched for low cut error and for diversity (no two cover the same exemplar
// pixels), and periodic textures stay in phase. Seeded and deterministic: the same seed gives
// the same bytes on any thread count.
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "texture/exemplar.hpp"
#include "texture/perspective.hpp"
#include "tilesets/tile.hpp"

namespace tilekit {

// A further map of a material (texture/material.hpp) that the seam costs weigh beside the colour:
// the map at the exemplar's size (one copy of a torus), any depth. Its term is `weight` times its
// step between the two texels (normals as vectors, n = 2v - 1; a grey map as one channel) in
// units of its own mean 4-neighbour step, times the colour's mean step, so that a map's typical
// step costs what the colour's typical step does (SynthesisExemplar::distance).
struct SeamCostMap {
  Image image;
  bool normal = false;  // tangent-space normals, RGB = (n + 1) / 2
  double weight = 1;
};

struct SynthesisOptions {
  TileKind kind = TileKind::Corner;
  std::uint32_t colours = 2;
  int tile_px = 128;
  std::uint64_t seed = 1;
  int threads = 1;
  // Candidate exemplar positions tried per corner/edge sample and round of the search; 0 keeps
  // the first random draw (no search: the "plain minimum-error cut" baseline).
  int search = 96;  // at most kMaxSynthesisSearch
  int rounds = 3;
  int centre_candidates = 32;  // centre patches scored per tile on the band where the cut runs
  int centre_cuts = 2;         // of those, the best this many get the full graph cut
  // Structured textures: resample the exemplar so that the tile holds whole periods of it and
  // keep every sample in phase with the lattice (exemplar.hpp's dominant_period); off: never.
  bool keep_period = true;
  // With keep_period, this period (px, x and y; 0: none along that axis) instead of the one
  // dominant_period finds; both 0: find it.
  std::array<double, 2> period_override{0, 0};
  // With keep_period, a photographed wall whose lines converge is first rectified
  // (perspective.hpp); off: never.
  bool rectify = true;
  // Thin shared bands (TileGeometry): a margin of 3n/64, a cut zone of 3n/16 and the centre's
  // pull; fewer texels repeat on the lattice, but mip level 2 is no longer exact next to a border.
  // Periodic exemplars (keep_period and a period found) keep the default bands.
  bool thin_bands = false;
  bool progress = false;
  // Record where every tile texel was copied from (TextureTileSet::coords): what material sets
  // and `texture transfer` carry further maps by.
  bool record_coords = false;
  // Material sets: seam cost = colour_weight * the colour's term + the maps' terms (SeamCostMap);
  // the colour's term is exactly the albedo-only cost. With maps, coordinates are recorded.
  std::vector<SeamCostMap> cost_maps;
  double colour_weight = 1;
};

// Where the samples of a tile lie, relative to the tile (n x n pixels). Every border has a band
// of `strip` pixels on either side covered by the border's own samples (corner tiles: one sample
// per ordered pair of corner colours and a small one per corner colour at the lattice points;
// Wang tiles: one per edge colour); the rest of the tile is a tile-unique centre patch, merged
// by a graph cut that runs between `margin` and `strip` pixels from the borders. So the texels
// within `margin` of a border depend only on that border's colours, which is what makes the atlas
// of a packing filter like the tiling (texture_atlas.hpp): exactly at mip levels 0 and 1 (whose
// [1 3 3 1] tent reads 3 texels across a border) and, for 64-pixel tiles (margin 5), at level 2
// up to the 4/64 weight of its 6th and 7th texel (as Ng et al.'s centre circle came within 5
// texels of the border too). The shared samples cover only the bands: the centre, different in
// every tile, covers the middle (n - 2 strip)^2 or more.
//
// Everything shared repeats on the lattice (a Wang band once in C), so a surface's grid
// repetition is about the shared fraction of the texels over C. Thin bands (`thin`) share fewer:
// the least margin that keeps levels 0 and 1 exact (3), a zone 3n/16 wide where the cut may run
// (room to go round a pebble) and a pull towards the centre (kCentrePull): 0.22-0.30 of the texels
// of 64-pixel tiles instead of 0.40-0.48. Their price: a level-2 texel next to a border takes 5/16
// of its weight from texels 3-6 deep, which the atlas' neighbour and the rendered one need not
// share (renders up to 4/255 off the stitched tiling there; texture/README.md). With margin 5 the
// same zone and pull gained little (grid repetition 0.035-0.047) and crossed cut visibility 1.5.
struct TileGeometry {
  int n = 0;
  int margin = 0;        // m: 5n/64 (thin: 3n/64), at least 3; no centre texel nearer a border than this
  int strip = 0;         // h: m + 3n/32 (thin: m + 3n/16); the band each border's samples cover
  int corner_reach = 0;  // m + 3n/32: how far along a border a corner square (or a Wang corner cut) reaches
  int extent = 0;        // the bands as sampled: h + 2 (the graph cut compares a pixel's neighbours beyond h)
  bool thin = false;
  explicit TileGeometry(int tile_px, bool thin = false);
};

// The centre patch's graph cut pays this many exemplar neighbour differences for every texel of
// the cut zone it leaves to the shared samples (graph_cut_merge's keep_cost), with thin bands.
// With 0.5 cut visibility stays at or below 1.5 on the irregular textures; 0.75 to 1 pushed it
// to 1.6-1.85.
inline constexpr double kCentrePull = 0.5;

inline constexpr int kMaxSynthesisSearch = 1 << 16;

struct TextureTileSet {
  TileKind kind = TileKind::Corner;
  std::uint32_t colours = 0;
  int tile_px = 0;
  std::uint64_t seed = 0;
  std::vector<Image> tiles;  // by tile index (thesis eq. 2.2 / 2.5)
  // Per tile and pixel, the sample it was copied from: ids below shared_sources are samples that
  // several tiles share (see corner_texture_tiles.cpp / wang_texture_tiles.cpp), shared_sources +
  // t the centre patch of tile t (naive: the tile index).
  std::vector<std::vector<std::uint32_t>> sources;
  std::uint32_t shared_sources = 0;
  std::vector<std::array<int, 2>> samples;  // exemplar positions of the shared samples, by id
  std::vector<std::array<int, 2>> centres;  // exemplar position of every tile's centre patch
  // With SynthesisOptions::record_coords, per tile and texel the exemplar texel it is a copy of,
  // x | y << 16, in the exemplar as the samples saw it (`sampled` when there is one, else the
  // exemplar itself; a tileable one's torus reduced to one copy): see exemplar_coord.
  std::vector<std::vector<std::uint32_t>> coords;
  double cut_error_initial = 0;  // summed boundary-cut error (in exemplar neighbour differences) of the first draw
  double cut_error = 0;          // the same after the search
  double centre_cost = 0;        // mean graph-cut cost of the centre patches
  double overlap = 0;            // shared samples: mean fraction of a sample's window another one also covers
  double shared_fraction = 0;    // the fraction of all tile texels copied from a shared sample
  bool thin_bands = false;       // made with TileGeometry's thin bands
  PerspectiveFit perspective;    // the rectification of a photographed wall (applied: the exemplar was resampled)
  ExemplarPeriod period;         // of the exemplar as rectified (0: none found, or keep_period off)
  std::array<double, 2> exemplar_scale{1, 1};  // the resampling that fits whole periods into a tile
  // Where the lattice's corners fall in the exemplar as sampled, modulo the period (SynthesisExemplar::phase).
  std::array<double, 2> phase{0, 0};
  Image sampled;  // the exemplar as the samples saw it, when rectified or resampled (else empty)
  double seconds = 0;
  std::string method;  // "corner-strips", "wang-strips" or "naive"
};

// The texel of `e` that `p` points into, x | y << 16, the torus reduced to one copy (tileable).
inline std::uint32_t exemplar_coord(const Exemplar& e, const std::uint8_t* p) {
  const std::size_t i = std::size_t(p - e.image.pixels.data()) / 4;
  int x = int(i % std::size_t(e.width())), y = int(i / std::size_t(e.width()));
  if (e.wrap_w) x %= e.wrap_w;
  if (e.wrap_h) y %= e.wrap_h;
  return std::uint32_t(x) | std::uint32_t(y) << 16;
}

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

// The mean step (per channel) across a line of `length` pixel pairs starting at (x, y) in the
// exemplar: between rows y - 1 and y (horizontal) or columns x - 1 and x. The seam goal of the
// search: a tile border, which runs through a sample, steps within kBorderTolerance of the
// sample's own mean step (SampleDraw::activity), so that it looks like the texture around it.
double line_activity(const Exemplar& e, int x, int y, int length, bool horizontal);
inline constexpr double kBorderTolerance = 0.04;
double seam_goal_miss(double border_to_own_activity);

// The exemplar as the samples see it: rectified when it is a photographed wall whose lines
// converge (perspective.hpp; keep_period and rectify), resampled to whole periods per tile when it
// has a dominant period (keep_period), and the phase every sample keeps. A sample shown with its top-left at
// (u, v) in lattice coordinates (tile corners at multiples of n) is taken from an exemplar
// position congruent to (u, v) + phase modulo the period, so that bricks continue across every
// cut and every tile border (exemplar.hpp, dominant_period). A photographed wall is periodic
// only roughly (perspective bends and spreads its mortar lines), so the position is then
// refined by up to a quarter of the lines' spacing: where the window's lines (the Fourier
// component of its gradient profile along the axis at the lines' spacing: the period, or the
// harmonic of it that is strongest in the middle of the exemplar, as a two-column period of
// single columns) are clear, they are put where the lines of a tile-sized window in the middle
// of the exemplar are, shown at a tile corner.
class SynthesisExemplar {
 public:
  SynthesisExemplar(const Exemplar& e, const SynthesisOptions& o);
  const Exemplar& exemplar() const { return e_; }
  const ExemplarPeriod& period() const { return found_; }  // as found in the (rectified) exemplar
  const PerspectiveFit& perspective() const { return perspective_; }
  std::array<double, 2> scale() const { return scale_; }
  // Where the lattice's corners fall in the exemplar, modulo the period (0 along an axis without).
  std::array<double, 2> phase() const { return phase_; }
  bool periodic() const { return step_[0] > 0 || step_[1] > 0; }
  // The position nearest p that keeps the phase for a w x h sample shown at lattice (u, v).
  std::array<int, 2> in_phase(std::array<int, 2> p, int u, int v, int w, int h) const;

  // The seam costs between two texels of exemplar() (pointers into its image): colour_distance
  // (distance) or channel_step (step) times the colour weight, plus the maps' terms
  // (map_distance) times the colour's mean step in the same units (neighbour_difference,
  // mean_step). Without cost maps exactly colour_distance and channel_step.
  float distance(const std::uint8_t* a, const std::uint8_t* b) const {
    if (map_channels_ == 0) return colour_distance(a, b);
    return colour_weight_ * colour_distance(a, b) + float(e_.neighbour_difference) * map_distance(texel(a), texel(b));
  }
  float step(const std::uint8_t* a, const std::uint8_t* b) const {
    if (map_channels_ == 0) return channel_step(a, b);
    return colour_weight_ * channel_step(a, b) + float(e_.mean_step) * map_distance(texel(a), texel(b));
  }
  bool has_cost_maps() const { return map_channels_ > 0; }
  // The maps' terms between texels a and b of exemplar() (index y * width + x) in the units of
  // colour_distance; 0 without cost maps.
  float map_cost(std::size_t a, std::size_t b) const { return float(e_.neighbour_difference) * map_distance(a, b); }
  // The sum over the maps of weight x the map's step from a to b / its mean neighbour step.
  float map_distance(std::size_t a, std::size_t b) const {
    float sum = 0;
    const float* pa = planes_.data() + a * std::size_t(map_channels_);
    const float* pb = planes_.data() + b * std::size_t(map_channels_);
    for (int k : map_widths_) {
      float d2 = 0;
      for (int c = 0; c < k; ++c) d2 += (pa[c] - pb[c]) * (pa[c] - pb[c]);
      sum += std::sqrt(d2);
      pa += k, pb += k;
    }
    return sum;
  }
  std::size_t texel(const std::uint8_t* p) const { return std::size_t(p - e_.image.pixels.data()) / 4; }
  // A texel recorded as x | y << 16 (exemplar_coord) as an index of exemplar().
  std::size_t texel(std::uint32_t coord) const {
    return std::size_t(coord >> 16) * std::size_t(e_.width()) + std::size_t(coord & 0xffff);
  }

 private:
  // The cost maps as the samples see them (rectified and resampled like the exemplar, laid out
  // like its image, the torus' copies too), each scaled by weight / its mean neighbour step.
  void build_planes(const SynthesisOptions& o);

  // Where the lines of a w x h window at p lie along an axis, in lattice coordinates modulo the
  // lines' spacing (the window shown at lattice u); NaN when unclear (that component at most
  // `clear` of the summed gradient).
  static constexpr double kLinesClear = 0.1;
  double line_phase(std::array<int, 2> p, int u, int w, int h, std::size_t axis, double clear = kLinesClear) const;
  // Per column (axis 0) or row (1) c of the whole exemplar, the gradient along the axis between
  // c and c + 1 summed across it.
  std::vector<double> gradient_profile(std::size_t axis) const;
  // |that Fourier component| / the summed gradient, at a given spacing of the lines.
  double line_clarity(std::array<int, 2> p, int w, int h, std::size_t axis, double spacing) const;

  Exemplar e_;
  PerspectiveFit perspective_;
  ExemplarPeriod found_;
  std::array<double, 2> scale_{1, 1}, step_{0, 0}, phase_{0, 0};  // step: the period after resampling
  std::array<int, 2> harmonic_{1, 1};                             // the lines' spacing is step / harmonic
  std::array<double, 2> lines_{std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  std::vector<float> planes_;    // per texel of e_.image, map_channels_ floats
  std::vector<int> map_widths_;  // channels per map (3, or 1 for a grey map)
  int map_channels_ = 0;
  float colour_weight_ = 1;
};

// Whether a synthesis uses thin bands: asked for, and the exemplar has no period kept.
bool thin_bands(const SynthesisOptions& o, const SynthesisExemplar& x);

// Draws positions of w x h samples uniformly among the typical ones: those whose activity (mean
// step per channel between neighbouring pixels inside the sample) lies within [0.85, 1.25] times
// the median over all positions. Without it, a search for low cut error drifts to bland samples
// (a flat brick face) whose seams are invisible only because there is nothing to see.
// `stratum` k of `strata` restricts the draw to the k-th cell of a grid of about that many
// cells over the positions (distinct tiles draw from distinct exemplar regions).
class SampleDraw {
 public:
  SampleDraw(const Exemplar& e, int w, int h);
  std::array<int, 2> operator()(std::uint64_t seed, std::size_t stratum = 0, std::size_t strata = 1) const;
  double activity(int x, int y) const;  // of the sample with top-left (x, y)
  double median_activity() const { return median_; }
  int width() const { return w_; }
  int height() const { return h_; }

 private:
  const Exemplar* e_;
  int w_, h_;
  int range_x_, range_y_;         // positions 0..range-1 (the torus, for a tileable exemplar)
  std::vector<double> integral_;  // (width + 1) x (height + 1) summed-area table of pixel activity
  double median_ = 0;
};

// One shared sample of the search: its window size, where it is shown (lattice coordinates of the
// window's top-left) and the border line it carries (for the seam goal), in window coordinates.
struct SampleSlot {
  int w = 0, h = 0;
  int u = 0, v = 0;
  int line_x = 0, line_y = 0, line_length = 0;
  bool line_horizontal = true;
  int draw = 0;  // which SampleDraw (one per window size)
  // Drawn from stratum k of `strata` of the exemplar (SampleDraw): the samples of one kind
  // spread over the whole exemplar, so they are far apart and differ in appearance as the
  // exemplar's regions do.
  std::size_t stratum = 0, strata = 1;
};

// With thin bands, every shared sample from its own cell of the exemplar (slot j: stratum j of
// all), so that no two of their larger windows overlap; otherwise one grid per kind of sample
// (slot k of a kind: stratum k of that kind's count).
void own_strata(std::vector<SampleSlot>& slots, const TileGeometry& g);

// The score of a sample in the search: first how far its border line misses the seam goal (0
// within kBorderTolerance of its own activity, see line_activity), then the cut error it takes
// part in plus kOverlapWeight times the fraction of its window that other samples also cover.
using SampleScore = std::pair<double, double>;
inline constexpr double kOverlapWeight = 50;

// The fraction of a's window (w x h at pa) that b's window (at pb, wb x hb) covers, on the torus
// of a tileable exemplar.
double window_overlap(const Exemplar& e, std::array<int, 2> pa, int w, int h, std::array<int, 2> pb, int wb, int hb);

// The search over the shared samples: coordinate descent, `o.rounds` rounds over the samples;
// each round draws `o.search` candidates for sample j (from its SampleDraw, seeded by o.seed,
// the round and j, put in phase), scores them in parallel with
// (goal miss, cut_error(j, samples with j replaced) + overlap penalty), and keeps the best if it
// beats the current one (ties by candidate order, so the result does not depend on the thread
// count). Returns the mean overlap of the result.
double search_samples(std::vector<std::array<int, 2>>& samples, const std::vector<SampleSlot>& slots,
                      const std::vector<SampleDraw>& draws, const SynthesisExemplar& x, const SynthesisOptions& o,
                      const std::function<double(std::size_t, const std::vector<std::array<int, 2>>&)>& cut_error);

// The tile-unique centre patch of every tile, merged over the tile by a graph cut (Kwatra et al.
// 2003) inside the pixels at least `margin` from every border, forced beyond `strip`. Candidates
// come from the tile's own stratum of the exemplar (distinct tiles, distinct regions), in phase,
// scored by their difference to the tile on the band where the cut runs; the best
// o.centre_cuts get the full cut. Returns the mean cut cost.
double merge_centre_patches(TextureTileSet& s, const SynthesisExemplar& x, const SynthesisOptions& o,
                            const std::string& title);

// The tiles in index order, about square, `gap` pixels apart on white (the README picture).
Image tile_set_sheet(const TextureTileSet& s, int gap = 4);
nlohmann::json tile_set_json(const TextureTileSet& s);
// When a period was likely missed (structure_likely), what to tell the user (else ""); and the
// `structure` object of tiles.json: periods found, their strength, the strongest repeat below the
// prominence per axis, that message.
std::string structure_message(const ExemplarPeriod& p);
nlohmann::json structure_json(const ExemplarPeriod& p);
// Tile t's sources as colours, one per sample (texture_analysis.hpp's labels): a bijection of the
// ids, so two samples never share a colour.
Image source_labels(const TextureTileSet& s, TileIndex t);
// DIR/tile-NNNN.png per tile (named by index, as `tilekit atlas build --tiles` reads them),
// DIR/tiles.json (the report), DIR/tileset.png (the sheet), DIR/exemplar.png (`sampled`, when
// there is one) and DIR/labels/ (the same files for
// the source labels: `texture atlas DIR/labels` and `texture render` of that atlas give the
// labels of a render); files written atomically.
// `more`, when given, writes further files into the folder before it replaces `dir` (material
// maps, coordinates: texture/material.hpp) and may add to the manifest.
void write_tile_set(const TextureTileSet& s, const std::string& dir, const std::string& exemplar,
                    const std::function<void(const std::string&, nlohmann::json&)>& more = {});

}  // namespace tilekit
