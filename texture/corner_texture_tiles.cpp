// Corner texture tiles by the method of Ng et al. 2005 (thesis sec. 5.3, fig. 5.1): one square
// patch of the exemplar per corner colour, centred on the lattice point; each tile combines the
// quadrants of its four corner patches, and the cross-shaped seam they leave is covered by a
// tile-unique centre patch, merged by a graph cut (Kwatra et al. 2003) restricted to the circle
// inscribed in the tile.
//
// Two refinements keep the tile borders seamless: neighbouring corner patches overlap by 2w
// pixels and are joined by a minimum-error boundary cut (Efros & Freeman 2001) that depends only
// on the two corner colours, so both tiles that share a border use the same cut; and the
// centre circle stays `margin` pixels inside the border, so the texels near a border depend
// only on the border's two corner colours (what makes the atlas of a packing filter exactly
// like the tiling, texture_atlas.hpp). The patch positions are searched: coordinate descent
// over random candidates minimises the summed cut error of all C^2 ordered pairs (each pair
// meets both side by side and one above the other), and each tile's centre patch is the best
// of several candidates by graph-cut cost.
#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <numeric>

#include "base/parallel.hpp"
#include "base/progress.hpp"
#include "base/random.hpp"
#include "texture/graph_cut.hpp"
#include "texture/seam_cut.hpp"
#include "texture/tile_synthesis.hpp"

namespace tilekit {

namespace {

using Pos = std::array<int, 2>;

class CornerSynthesis {
 public:
  CornerSynthesis(const Exemplar& e, const SynthesisOptions& o)
      : e_(e), o_(o), g_(o.tile_px), c_(o.colours), draw_patch_(e, g_.patch), draw_centre_(e, g_.n) {}

  TextureTileSet run() {
    const auto t0 = std::chrono::steady_clock::now();
    TextureTileSet s;
    s.kind = TileKind::Corner;
    s.colours = c_;
    s.tile_px = g_.n;
    s.seed = o_.seed;
    s.method = "ng-corner";
    s.shared_sources = c_;
    choose_patches(s);
    compose_tiles(s);
    s.samples = patch_;
    s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return s;
  }

 private:
  // Pixel at offset (dx, dy) from the lattice point a patch at `p` is centred on.
  const std::uint8_t* pix(const Pos& p, int dx, int dy) const {
    const int x = p[0] + g_.half + g_.overlap + dx, y = p[1] + g_.half + g_.overlap + dy;
    assert(x >= p[0] && x < p[0] + g_.patch && y >= p[1] && y < p[1] + g_.patch);
    return e_.at(x, y);
  }

  // The cut between the patch `a` of one lattice point and the patch `b` of the next one to the
  // east (vertical = false) or to the south (vertical = true): for each of the 2*arm rows (or
  // columns) t = -arm..arm-1 around the shared tile border, the boundary position q measured
  // from a's lattice point: pixels before q come from a, the rest from b.
  CutPath pair_cut(const Pos& a, const Pos& b, bool vertical) const {
    CutBand band;
    band.rows = 2 * g_.arm;
    band.width = 2 * g_.overlap - 1;
    band.lo.assign(std::size_t(band.rows), 0);
    band.hi.assign(std::size_t(band.rows), band.width - 1);
    band.cost.resize(std::size_t(band.rows) * std::size_t(band.width));
    const float unit = float(e_.neighbour_difference);
    for (int r = 0; r < band.rows; ++r) {
      const int t = r - g_.arm;
      for (int p = 0; p < band.width; ++p) {
        const int q = first_boundary() + p;
        // the two pixels on either side of the boundary, each seen in both patches
        auto d = [&](int along) {
          return vertical ? colour_distance(pix(a, t, along), pix(b, t, along - g_.n))
                          : colour_distance(pix(a, along, t), pix(b, along - g_.n, t));
        };
        band.at(r, p) = (d(q - 1) + d(q)) / unit;
      }
    }
    return min_error_cut(band);
  }
  int first_boundary() const { return g_.half - g_.overlap + 1; }

  double pair_error(const std::vector<Pos>& pos, std::uint32_t a, std::uint32_t b) const {
    return pair_cut(pos[a], pos[b], false).cost + pair_cut(pos[a], pos[b], true).cost;
  }
  // The error of every pair that involves colour c (both orders, and c with itself).
  double colour_error(const std::vector<Pos>& pos, std::uint32_t c) const {
    double sum = 0;
    for (std::uint32_t k = 0; k < c_; ++k) sum += pair_error(pos, c, k) + (k == c ? 0 : pair_error(pos, k, c));
    return sum;
  }
  double total_error(const std::vector<Pos>& pos) const {
    double sum = 0;
    for (std::uint32_t a = 0; a < c_; ++a)
      for (std::uint32_t b = 0; b < c_; ++b) sum += pair_error(pos, a, b);
    return sum;
  }

  // The seam goal: the tile borders through the patch's lattice point step like the texture.
  double goal_miss(const Pos& p) const {
    const Pos centre{p[0] + g_.half + g_.overlap, p[1] + g_.half + g_.overlap};
    return seam_goal_miss(border_activity(e_, centre, g_.half, true, true) / draw_patch_.activity(p[0], p[1]));
  }

  // Corner patches: a random draw, then the search (search_samples): on the seam goal first,
  // then the least error of the cuts the patch takes part in.
  void choose_patches(TextureTileSet& s) {
    for (std::uint32_t c = 0; c < c_; ++c) patch_.push_back(draw_patch_(derive_seed(o_.seed, c)));
    s.cut_error_initial = total_error(patch_);
    search_samples(patch_, draw_patch_, o_, [&](std::size_t c, const std::vector<Pos>& pos) {
      return SampleScore{goal_miss(pos[c]), colour_error(pos, std::uint32_t(c))};
    });
    for (std::uint32_t a = 0; a < c_; ++a)
      for (std::uint32_t b = 0; b < c_; ++b) {
        hcut_.push_back(pair_cut(patch_[a], patch_[b], false).pos);
        vcut_.push_back(pair_cut(patch_[a], patch_[b], true).pos);
      }
    s.cut_error = total_error(patch_);
  }

  // Boundary of the pair cut (a west/north of b) at row t from the shared border, clamped to
  // the rows the cut was computed for (further in, the centre patch covers the seam).
  int boundary(const std::vector<std::vector<int>>& cuts, Colour a, Colour b, int t) const {
    t = std::clamp(t, -g_.arm, g_.arm - 1);
    return first_boundary() + cuts[std::size_t(a) * c_ + b][std::size_t(t + g_.arm)];
  }

  // The tile from its four corner patches, with the source of every pixel.
  void base_tile(const CornerTile& t, Image& img, std::vector<std::uint32_t>& src) const {
    const int n = g_.n;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const bool west = y < g_.half ? x < boundary(hcut_, t.nw, t.ne, y) : x < boundary(hcut_, t.sw, t.se, y - n);
        const bool north = x < g_.half ? y < boundary(vcut_, t.nw, t.sw, x) : y < boundary(vcut_, t.ne, t.se, x - n);
        const Colour c = north ? (west ? t.nw : t.ne) : (west ? t.sw : t.se);
        const int dx = west ? x : x - n, dy = north ? y : y - n;  // offset from that corner's lattice point
        std::copy_n(pix(patch_[c], dx, dy), 4, img.at(x, y));
        src[std::size_t(y) * std::size_t(n) + std::size_t(x)] = c;
      }
  }

  double centre_distance(int x, int y) const { return std::hypot(x + 0.5 - g_.half, y + 0.5 - g_.half); }

  void compose_tiles(TextureTileSet& s) {
    const int n = g_.n;
    const std::size_t count = std::size_t(c_) * c_ * c_ * c_, px = std::size_t(n) * std::size_t(n);
    // The circle the centre patch may cover, the cross under it, and the ring where its cut runs.
    std::vector<std::uint8_t> region(px, 0), forced(px, 0);
    std::vector<std::size_t> ring;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const std::size_t i = std::size_t(y) * std::size_t(n) + std::size_t(x);
        const double r = centre_distance(x, y);
        if (r >= g_.radius) continue;
        region[i] = 1;
        const bool cross = std::abs(x + 0.5 - g_.half) < g_.overlap + 2 || std::abs(y + 0.5 - g_.half) < g_.overlap + 2;
        forced[i] = cross && r < g_.radius - g_.inner;
        if (r >= g_.radius - g_.inner - 2) ring.push_back(i);
      }
    s.tiles.assign(count, Image{n, n, std::vector<std::uint8_t>(px * 4)});
    s.sources.assign(count, std::vector<std::uint32_t>(px));
    std::vector<double> cost(count);
    const int candidates = o_.search > 0 ? o_.centre_candidates : 1, cuts = o_.search > 0 ? o_.centre_cuts : 1;
    ProgressReporter progress(fmt::format("corner tiles C={} {}px", c_, n), double(count), o_.progress);
    parallel_for(std::int64_t(count), o_.threads, [&](std::int64_t ti) {
      const TileIndex t = TileIndex(ti);
      Image& img = s.tiles[t];
      base_tile(corner_tile(t, c_), img, s.sources[t]);
      // Centre patch candidates, scored by their difference to the tile on the ring.
      std::vector<std::pair<double, Pos>> scored;
      for (int k = 0; k < candidates; ++k) {
        const Pos q = draw_centre_(derive_seed(derive_seed(o_.seed, 7000 + t), std::uint64_t(k)));
        double d = 0;
        for (std::size_t i : ring)
          d += colour_distance(img.pixels.data() + 4 * i,
                               e_.at(q[0] + int(i % std::size_t(n)), q[1] + int(i / std::size_t(n))));
        scored.push_back({d, q});
      }
      std::stable_sort(scored.begin(), scored.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      Image patch{n, n, std::vector<std::uint8_t>(px * 4)}, best_patch;
      GraphCutResult best;
      for (int k = 0; k < std::min(cuts, candidates); ++k) {
        const Pos q = scored[std::size_t(k)].second;
        for (int y = 0; y < n; ++y) std::copy_n(e_.at(q[0], q[1] + y), std::size_t(n) * 4, patch.at(0, y));
        GraphCutResult r = graph_cut_merge(img, patch, region, forced);
        if (k == 0 || r.cost < best.cost) best = std::move(r), best_patch = patch;
      }
      for (std::size_t i = 0; i < px; ++i)
        if (best.take_new[i]) {
          std::copy_n(best_patch.pixels.data() + 4 * i, 4, img.pixels.data() + 4 * i);
          s.sources[t][i] = c_ + t;
        }
      cost[t] = best.cost;
      progress.add(1);
    });
    progress.finish();
    s.centre_cost = std::accumulate(cost.begin(), cost.end(), 0.0) / double(count);
  }

  const Exemplar& e_;
  const SynthesisOptions& o_;
  const TileGeometry g_;
  const std::uint32_t c_;
  const SampleDraw draw_patch_, draw_centre_;  // typical corner patches and centre patches
  std::vector<Pos> patch_;                     // corner patch per colour (exemplar top-left)
  std::vector<std::vector<int>> hcut_, vcut_;  // pair cuts, index a * C + b
};

}  // namespace

TextureTileSet synthesize_corner_tiles(const Exemplar& e, const SynthesisOptions& o) {
  check_synthesis_options(e, o);
  return CornerSynthesis(e, o).run();
}

}  // namespace tilekit
