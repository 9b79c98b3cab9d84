// Wang texture tiles (thesis sec. 5.3, fig. 5.4a, after Cohen et al. 2003) that do not show
// their grid. Cohen et al. fill a tile with four half-diamonds, one per edge colour, so every
// texel is shared with every tile of the same edge colour: on a surface a texel repeats at a
// lattice lag once in C (grid repetition 0.38-0.47 at C = 2..3 in texture/README.md's measure).
//
// Here each edge colour's sample covers only the band along its border (tile_synthesis.hpp,
// TileGeometry: `extent` pixels on either side), and a tile-unique centre patch covers the rest,
// merged by a graph cut between `margin` and `strip` pixels from the borders
// (merge_centre_patches). Where two bands cross, in a tile corner, a minimum-error boundary cut
// (Efros & Freeman 2001) along the corner's diagonal separates them, one per corner and pair of
// colours; it ends exactly in the corner, so every border pixel comes from its own edge's sample
// (the Wang corner problem, thesis 5.4, stays confined to the corner). The samples are searched
// (search_samples): seam goal first, then the summed cut error (Cohen et al.'s "overall quilting
// error") plus overlap with the other samples.
#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <chrono>

#include "base/parallel.hpp"
#include "base/random.hpp"
#include "texture/seam_cut.hpp"
#include "texture/tile_synthesis.hpp"

namespace tilekit {

namespace {

using Pos = std::array<int, 2>;

// The tile's corners; sx, sy point to the corner (y grows to the south).
struct Corner {
  int sx, sy;
};
constexpr Corner kCorners[4] = {{1, -1}, {1, 1}, {-1, 1}, {-1, -1}};  // NE, SE, SW, NW

class WangSynthesis {
 public:
  WangSynthesis(const Exemplar& e, const SynthesisOptions& o)
      : x_(e, o), e_(x_.exemplar()), o_(o), g_(o.tile_px, thin_bands(o, x_)), c_(o.colours) {
    check_synthesis_options(e_, o);
    const int n = g_.n, E = g_.extent;
    draws_.emplace_back(e_, n, 2 * E);
    draws_.emplace_back(e_, 2 * E, n);
    for (std::uint32_t c = 0; c < c_; ++c) slots_.push_back({n, 2 * E, 0, -E, 0, E, n, true, 0, c, c_});
    for (std::uint32_t c = 0; c < c_; ++c) slots_.push_back({2 * E, n, -E, 0, E, 0, n, false, 1, c, c_});
    own_strata(slots_, g_);
  }

  TextureTileSet run() {
    const auto t0 = std::chrono::steady_clock::now();
    TextureTileSet s;
    s.kind = TileKind::Wang;
    s.colours = c_;
    s.tile_px = g_.n;
    s.seed = o_.seed;
    s.method = "wang-strips";
    s.shared_sources = 2 * c_;
    s.period = x_.period();
    s.perspective = x_.perspective();
    if (s.perspective.applied || x_.scale() != std::array<double, 2>{1, 1}) s.sampled = x_.exemplar().image;
    s.thin_bands = g_.thin;
    s.exemplar_scale = x_.scale();
    s.phase = x_.phase();
    choose_samples(s);
    compose_tiles(s);
    s.centre_cost = merge_centre_patches(s, x_, o_, fmt::format("Wang tiles C={} {}px", c_, g_.n));
    s.samples = pos_;
    s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return s;
  }

 private:
  // Tile pixel (x, y) from the sample of the horizontal border above (sy < 0) or below it, or of
  // the vertical border to the west (sx < 0) or east.
  const std::uint8_t* hpix(const std::vector<Pos>& pos, Colour c, int sy, int x, int y) const {
    const int t = sy < 0 ? y : y - g_.n;
    return e_.at(pos[c][0] + x, pos[c][1] + t + g_.extent);
  }
  const std::uint8_t* vpix(const std::vector<Pos>& pos, Colour c, int sx, int x, int y) const {
    const int s = sx < 0 ? x : x - g_.n;
    return e_.at(pos[c_ + c][0] + s + g_.extent, pos[c_ + c][1] + y);
  }

  // Pixel of corner k at distance dh from the horizontal border and dv from the vertical one.
  std::array<int, 2> pixel_of(int k, int dh, int dv) const {
    const int n = g_.n;
    return {kCorners[k].sx > 0 ? n - 1 - dv : dv, kCorners[k].sy < 0 ? dh : n - 1 - dh};
  }

  // The side of the square where two bands cross in a corner: the bands' extent, or with thin
  // bands (whose extent is wider) as far as a corner square reaches; beyond it a texel comes from
  // the nearer border's sample.
  int crossing() const { return g_.thin ? g_.corner_reach + 2 : g_.extent; }

  // The cut in corner k between horizontal-border sample h and vertical-border sample v, by
  // anti-diagonals a = dh + dv = 1 .. 2 crossing() - 3 of the square where the two bands cross: the
  // boundary P(a) between offsets d = dv - dh (pixels with d > P come from the horizontal
  // border's sample). |P| < a keeps every border pixel on its own side, and the boundary's
  // neighbours stay inside the square.
  CutPath cut(int k, const std::vector<Pos>& pos, Colour h, Colour v) const {
    const int E = crossing(), A = 2 * E - 3;
    CutBand band;
    band.rows = A;
    band.width = 2 * A + 1;
    band.diagonal = true;
    band.cost.assign(std::size_t(band.rows) * std::size_t(band.width), 0.0f);
    const float unit = float(e_.neighbour_difference);
    for (int a = 1; a <= A; ++a) {
      // thin bands: at most corner_reach - margin from the diagonal, so a texel within the margin
      // of one border comes from the other border's sample only within corner_reach of the corner
      const int reach = std::min({a - 1, 2 * E - 3 - a, g_.thin ? g_.corner_reach - g_.margin : E});
      band.lo.push_back(A - reach);
      band.hi.push_back(A + reach);
      for (int p = -reach; p <= reach; ++p) {
        if ((a + p) % 2 == 0) continue;  // a boundary lies between pixel centres
        float cost = 0;
        for (int d : {p - 1, p + 1}) {
          const auto [x, y] = pixel_of(k, (a - d) / 2, (a + d) / 2);
          cost += x_.distance(hpix(pos, h, kCorners[k].sy, x, y), vpix(pos, v, kCorners[k].sx, x, y));
        }
        band.at(a - 1, p + A) = cost / unit;
      }
    }
    return min_error_cut(band);
  }

  // Summed error of every cut that involves sample j (0..C-1 horizontal, C..2C-1 vertical).
  double sample_error(std::size_t j, const std::vector<Pos>& pos) const {
    double sum = 0;
    for (int k = 0; k < 4; ++k)
      for (Colour other = 0; other < c_; ++other)
        sum += j < c_ ? cut(k, pos, Colour(j), other).cost : cut(k, pos, other, Colour(j - c_)).cost;
    return sum;
  }
  double total_error(const std::vector<Pos>& pos) const {
    double sum = 0;
    for (std::size_t h = 0; h < c_; ++h) sum += sample_error(h, pos);
    return sum;
  }

  void choose_samples(TextureTileSet& s) {
    for (std::size_t j = 0; j < slots_.size(); ++j) {
      const SampleSlot& sl = slots_[j];
      const Pos p = draws_[std::size_t(sl.draw)](derive_seed(o_.seed, j), sl.stratum, sl.strata);
      pos_.push_back(x_.in_phase(p, sl.u, sl.v, sl.w, sl.h));
    }
    s.cut_error_initial = total_error(pos_);
    s.overlap = search_samples(pos_, slots_, draws_, x_, o_,
                               [&](std::size_t j, const std::vector<Pos>& pos) { return sample_error(j, pos); });
    for (int k = 0; k < 4; ++k)
      for (Colour h = 0; h < c_; ++h)
        for (Colour v = 0; v < c_; ++v) cuts_.push_back(cut(k, pos_, h, v).pos);
    s.cut_error = total_error(pos_);
  }

  // The bands of every tile, split in the corners by the diagonal cuts; the middle, which no band
  // reaches, is left for the centre patch.
  void compose_tiles(TextureTileSet& s) {
    const int n = g_.n, E = g_.extent, A = 2 * crossing() - 3;
    const std::size_t count = std::size_t(c_) * c_ * c_ * c_, px = std::size_t(n) * std::size_t(n);
    s.tiles.assign(count, Image{n, n, std::vector<std::uint8_t>(px * 4)});
    s.sources.assign(count, std::vector<std::uint32_t>(px, 0));
    if (o_.record_coords) s.coords.assign(count, std::vector<std::uint32_t>(px, 0));
    parallel_for(std::int64_t(count), o_.threads, [&](std::int64_t ti) {
      const WangTile t = wang_tile(TileIndex(ti), c_);  // thesis eq. (2.3)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const int sx = 2 * x + 1 > n ? 1 : -1, sy = 2 * y + 1 > n ? 1 : -1;
          const int dh = sy < 0 ? y : n - 1 - y, dv = sx > 0 ? n - 1 - x : x;
          const Colour h = sy < 0 ? t.n : t.s, v = sx > 0 ? t.e : t.w;
          bool horizontal;
          if (dh >= E && dv >= E) continue;  // the centre's
          if (dh >= E || dv >= E) {
            horizontal = dh < E;
          } else {
            const int k = sy < 0 ? (sx > 0 ? 0 : 3) : (sx > 0 ? 1 : 2), a = dh + dv, d = dv - dh;
            const std::vector<int>& path = cuts_[(std::size_t(k) * c_ + h) * c_ + v];
            horizontal = a == 0 || (a <= A ? d > path[std::size_t(a - 1)] - A : d >= 0);
          }
          const std::uint8_t* p = horizontal ? hpix(pos_, h, sy, x, y) : vpix(pos_, v, sx, x, y);
          const std::size_t i = std::size_t(y) * std::size_t(n) + std::size_t(x);
          std::copy_n(p, 4, s.tiles[std::size_t(ti)].pixels.data() + 4 * i);
          if (!s.coords.empty()) s.coords[std::size_t(ti)][i] = exemplar_coord(e_, p);
          s.sources[std::size_t(ti)][i] = horizontal ? h : c_ + v;
        }
    });
  }

  SynthesisExemplar x_;
  const Exemplar& e_;
  const SynthesisOptions& o_;
  const TileGeometry g_;
  const std::uint32_t c_;
  std::vector<SampleDraw> draws_;       // horizontal-border bands, vertical-border bands
  std::vector<SampleSlot> slots_;       // C horizontal-edge colours, then C vertical-edge colours
  std::vector<Pos> pos_;                // the samples' exemplar positions, by slot
  std::vector<std::vector<int>> cuts_;  // (corner * C + h) * C + v -> boundary position (P + A) per a - 1
};

}  // namespace

TextureTileSet synthesize_wang_tiles(const Exemplar& e, const SynthesisOptions& o) {
  check_synthesis_options(e, o);
  SynthesisOptions with = o;
  with.record_coords = o.record_coords || !o.cost_maps.empty();  // the maps' costs look texels up by them
  return WangSynthesis(e, with).run();
}

}  // namespace tilekit
