// Wang texture tiles by the method of Cohen et al. 2003 (sec. 3.2; thesis sec. 5.3, fig. 5.4a):
// one diamond-shaped sample of the exemplar per edge colour (horizontal and vertical edges have
// their own samples), centred on the edge's midpoint, so that a tile with north colour c holds
// the lower half of c's diamond and the tile above it the upper half. A tile joins its four
// half-diamonds along its diagonals by minimum-error boundary cuts (Efros & Freeman 2001), one
// per corner and pair of colours, that end exactly in the tile corner, so every tile border
// shows a single diamond. The samples are re-drawn to lower the total cut error (the sum over
// all 4 C^2 cuts, Cohen et al.'s "overall quilting error"): coordinate descent over random
// candidates, searched rather than accepted at the first draw.
#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <chrono>

#include "base/parallel.hpp"
#include "base/progress.hpp"
#include "base/random.hpp"
#include "texture/seam_cut.hpp"
#include "texture/tile_synthesis.hpp"

namespace tilekit {

namespace {

using Pos = std::array<int, 2>;

// The tile's quadrants, each with the diagonal from the tile centre to one corner; sx, sy point
// to the corner (y grows to the south).
struct Corner {
  int sx, sy;
};
constexpr Corner kCorners[4] = {{1, -1}, {1, 1}, {-1, 1}, {-1, -1}};  // NE, SE, SW, NW
int corner_of(int sx, int sy) {
  return sy < 0 ? (sx > 0 ? 0 : 3) : (sx > 0 ? 1 : 2);
}

class WangSynthesis {
 public:
  WangSynthesis(const Exemplar& e, const SynthesisOptions& o)
      : e_(e), o_(o), g_(o.tile_px), c_(o.colours), draw_(e, g_.patch) {}

  TextureTileSet run() {
    const auto t0 = std::chrono::steady_clock::now();
    TextureTileSet s;
    s.kind = TileKind::Wang;
    s.colours = c_;
    s.tile_px = g_.n;
    s.seed = o_.seed;
    s.method = "cohen-wang";
    s.shared_sources = 2 * c_;
    choose_samples(s);
    compose_tiles(s);
    s.samples = sample_;
    s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return s;
  }

 private:
  // Tile pixel (x, y) from the sample at `p` centred on the midpoint of the edge at (mx2/2, my2/2).
  const std::uint8_t* pix(const Pos& p, int x, int y, int mx2, int my2) const {
    const int dx = x - mx2 / 2, dy = y - my2 / 2;
    const int ex = p[0] + g_.half + g_.overlap + dx, ey = p[1] + g_.half + g_.overlap + dy;
    assert(ex >= p[0] && ex < p[0] + g_.patch && ey >= p[1] && ey < p[1] + g_.patch);
    return e_.at(ex, ey);
  }
  // Pixel of the horizontal-edge (north or south) and vertical-edge (east or west) sample.
  const std::uint8_t* hpix(const Pos& p, int sy, int x, int y) const {
    return pix(p, x, y, g_.n, sy < 0 ? 0 : 2 * g_.n);
  }
  const std::uint8_t* vpix(const Pos& p, int sx, int x, int y) const {
    return pix(p, x, y, sx < 0 ? 0 : 2 * g_.n, g_.n);
  }

  // Pixel (x, y) of diagonal coordinates (a, d) in corner k: a = sx X + sy Y (0 at the centre,
  // n at the corner), d = sx X - sy Y (negative on the horizontal edge's side), where (X, Y) is
  // the pixel centre relative to the tile centre.
  std::array<int, 2> pixel_of(int k, int a, int d) const {
    const int x2 = kCorners[k].sx * (a + d), y2 = kCorners[k].sy * (a - d);  // 2X, 2Y
    return {(x2 + g_.n - 1) / 2, (y2 + g_.n - 1) / 2};
  }

  // The cut in corner k between horizontal sample h and vertical sample v: d_a for a = 1..n-1.
  // It starts at the centre (d = 0), stays within w of the diagonal and inside the quadrant, and
  // ends in the corner: every border pixel lies on its own edge's side.
  CutPath cut(int k, const Pos& h, const Pos& v) const {
    const int n = g_.n, w = g_.overlap;
    CutBand band;
    band.rows = n - 1;
    band.width = 2 * w + 1;
    band.diagonal = true;
    band.cost.assign(std::size_t(band.rows) * std::size_t(band.width), 0.0f);
    const float unit = float(e_.neighbour_difference);
    for (int a = 1; a < n; ++a) {
      const int below = std::min({w, a - 1, n - 1 - a}), above = a == n - 1 ? 0 : std::min({w, a - 1, n - 2 - a});
      band.lo.push_back(w - below);
      band.hi.push_back(w + above);
      for (int d = -below; d <= above; ++d) {
        if ((a + d) % 2 == 0) continue;  // not a pixel centre
        const auto [x, y] = pixel_of(k, a, d);
        band.at(a - 1, d + w) = colour_distance(hpix(h, kCorners[k].sy, x, y), vpix(v, kCorners[k].sx, x, y)) / unit;
      }
    }
    return min_error_cut(band);
  }

  const Pos& hsample(std::uint32_t c, const std::vector<Pos>& s) const { return s[c]; }
  const Pos& vsample(std::uint32_t c, const std::vector<Pos>& s) const { return s[c_ + c]; }

  // Summed error of every cut that involves sample j (0..C-1 horizontal, C..2C-1 vertical).
  double sample_error(const std::vector<Pos>& s, std::uint32_t j) const {
    double sum = 0;
    for (int k = 0; k < 4; ++k)
      for (std::uint32_t other = 0; other < c_; ++other)
        sum += j < c_ ? cut(k, s[j], vsample(other, s)).cost : cut(k, hsample(other, s), s[j]).cost;
    return sum;
  }
  double total_error(const std::vector<Pos>& s) const {
    double sum = 0;
    for (std::uint32_t h = 0; h < c_; ++h) sum += sample_error(s, h);
    return sum;
  }

  // The seam goal: the tile border through the diamond's centre (a row for a horizontal edge, a
  // column for a vertical one) steps like the texture.
  double goal_miss(const Pos& p, std::size_t j) const {
    const Pos centre{p[0] + g_.half + g_.overlap, p[1] + g_.half + g_.overlap};
    return seam_goal_miss(border_activity(e_, centre, g_.half, j < c_, j >= c_) / draw_.activity(p[0], p[1]));
  }

  // The diamonds: a random draw, then the search (search_samples): on the seam goal first, then
  // the least error of the cuts the diamond takes part in.
  void choose_samples(TextureTileSet& s) {
    for (std::uint32_t j = 0; j < 2 * c_; ++j) sample_.push_back(draw_(derive_seed(o_.seed, j)));
    s.cut_error_initial = total_error(sample_);
    search_samples(sample_, draw_, o_, [&](std::size_t j, const std::vector<Pos>& pos) {
      return SampleScore{goal_miss(pos[j], j), sample_error(pos, std::uint32_t(j))};
    });
    for (int k = 0; k < 4; ++k)
      for (std::uint32_t h = 0; h < c_; ++h)
        for (std::uint32_t v = 0; v < c_; ++v) cuts_.push_back(cut(k, hsample(h, sample_), vsample(v, sample_)).pos);
    s.cut_error = total_error(sample_);
  }

  void compose_tiles(TextureTileSet& s) {
    const int n = g_.n, w = g_.overlap;
    const std::size_t count = std::size_t(c_) * c_ * c_ * c_, px = std::size_t(n) * std::size_t(n);
    s.tiles.assign(count, Image{n, n, std::vector<std::uint8_t>(px * 4)});
    s.sources.assign(count, std::vector<std::uint32_t>(px));
    ProgressReporter progress(fmt::format("Wang tiles C={} {}px", c_, n), double(count), o_.progress);
    parallel_for(std::int64_t(count), o_.threads, [&](std::int64_t ti) {
      const WangTile t = wang_tile(TileIndex(ti), c_);  // thesis eq. (2.3)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const int x2 = 2 * x + 1 - n, y2 = 2 * y + 1 - n;
          const int sx = x2 > 0 ? 1 : -1, sy = y2 > 0 ? 1 : -1, k = corner_of(sx, sy);
          const int a = (sx * x2 + sy * y2) / 2, d = (sx * x2 - sy * y2) / 2;
          const Colour h = sy < 0 ? t.n : t.s, v = sx > 0 ? t.e : t.w;
          const std::vector<int>& path = cuts_[(std::size_t(k) * c_ + h) * c_ + v];
          const bool horizontal = d <= path[std::size_t(a - 1)] - w;
          const std::uint8_t* p =
              horizontal ? hpix(hsample(h, sample_), sy, x, y) : vpix(vsample(v, sample_), sx, x, y);
          const std::size_t i = std::size_t(y) * std::size_t(n) + std::size_t(x);
          std::copy_n(p, 4, s.tiles[std::size_t(ti)].pixels.data() + 4 * i);
          s.sources[std::size_t(ti)][i] = horizontal ? h : c_ + v;
        }
      progress.add(1);
    });
    progress.finish();
  }

  const Exemplar& e_;
  const SynthesisOptions& o_;
  const TileGeometry g_;
  const std::uint32_t c_;
  const SampleDraw draw_;               // typical diamond samples
  std::vector<Pos> sample_;             // diamonds: C horizontal-edge colours, then C vertical-edge colours
  std::vector<std::vector<int>> cuts_;  // (corner * C + h) * C + v -> path position (d + w) per a - 1
};

}  // namespace

TextureTileSet synthesize_wang_tiles(const Exemplar& e, const SynthesisOptions& o) {
  check_synthesis_options(e, o);
  return WangSynthesis(e, o).run();
}

}  // namespace tilekit
