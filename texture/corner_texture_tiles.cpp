// Corner texture tiles (thesis sec. 5.3, fig. 5.1, after Ng et al. 2005) that do not show their
// grid. Ng et al. give each corner colour one large patch centred on the lattice point; every
// tile then shows a quarter of the patch of each of its four corner colours, so on a surface a
// quarter of all texels repeat wherever the corner colour does (one lattice point in C): the
// lattice shows (grid repetition 0.13-0.16 at C = 4 in texture/README.md's measure).
//
// Here the texels a tile must share with its neighbours are only the bands along its borders
// (tile_synthesis.hpp, TileGeometry), and a border's band depends on both of its corner colours:
//   - one small square sample per corner colour around the lattice point, 2 * extent wide,
//     which covers the texels near two borders at once (they depend on that colour only);
//   - one sample per ordered pair (a, b) of corner colours and direction (a border from a lattice
//     point of colour a to one of colour b, east or south), covering the border's band: C^2
//     variants per direction instead of C, so a band repeats at a lattice lag once in C^2;
//   - a tile-unique centre patch over the rest, merged by a graph cut between `margin` and
//     `strip` pixels from the borders (merge_centre_patches).
// A band sample meets the corner squares at its two ends in minimum-error boundary cuts (Efros &
// Freeman 2001) that run between `margin` and `corner_reach` along the border, one per band sample and
// end, so both tiles that share a border use the same cut. The shared samples are searched
// (search_samples): seam goal first, then cut error plus overlap with the other samples.
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

class CornerSynthesis {
 public:
  CornerSynthesis(const Exemplar& e, const SynthesisOptions& o)
      : x_(e, o), e_(x_.exemplar()), o_(o), g_(o.tile_px, thin_bands(o, x_)), c_(o.colours) {
    check_synthesis_options(e_, o);
    const int n = g_.n, m = g_.margin, E = g_.extent, side = 2 * E + 2, band = n - 2 * m + 2;
    draws_.emplace_back(e_, side, side);
    draws_.emplace_back(e_, band, 2 * E);
    draws_.emplace_back(e_, 2 * E, band);
    for (std::uint32_t c = 0; c < c_; ++c)
      slots_.push_back({side, side, -E - 1, -E - 1, 1, E + 1, side - 2, true, 0, c, c_});
    for (std::uint32_t k = 0; k < c_ * c_; ++k)
      slots_.push_back({band, 2 * E, m - 1, -E, 1, E, n - 2 * m, true, 1, k, c_ * c_});
    for (std::uint32_t k = 0; k < c_ * c_; ++k)
      slots_.push_back({2 * E, band, -E, m - 1, E, 1, n - 2 * m, false, 2, k, c_ * c_});
    own_strata(slots_, g_);
  }

  TextureTileSet run() {
    const auto t0 = std::chrono::steady_clock::now();
    TextureTileSet s;
    s.kind = TileKind::Corner;
    s.colours = c_;
    s.tile_px = g_.n;
    s.seed = o_.seed;
    s.method = "corner-strips";
    s.shared_sources = c_ + 2 * c_ * c_;
    s.period = x_.period();
    s.perspective = x_.perspective();
    if (s.perspective.applied || x_.scale() != std::array<double, 2>{1, 1}) s.sampled = x_.exemplar().image;
    s.thin_bands = g_.thin;
    s.exemplar_scale = x_.scale();
    s.phase = x_.phase();
    choose_samples(s);
    compose_tiles(s);
    s.centre_cost = merge_centre_patches(s, x_, o_, fmt::format("corner tiles C={} {}px", c_, g_.n));
    s.samples = pos_;
    s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return s;
  }

 private:
  std::size_t hedge(Colour a, Colour b) const { return c_ + std::size_t(a) * c_ + b; }
  std::size_t vedge(Colour a, Colour b) const { return c_ + c_ * c_ + std::size_t(a) * c_ + b; }

  // Pixel (dx, dy) of a sample, in lattice coordinates relative to the lattice point it hangs
  // from (a corner: its own point; an edge: its west or north end).
  const std::uint8_t* pix(const std::vector<Pos>& pos, std::size_t j, int dx, int dy) const {
    const SampleSlot& s = slots_[j];
    const int x = pos[j][0] + dx - s.u, y = pos[j][1] + dy - s.v;
    assert(dx >= s.u && dx < s.u + s.w && dy >= s.v && dy < s.v + s.h);
    return e_.at(x, y);
  }

  // The cut between band sample `edge` (horizontal: from a west lattice point to an east one) and
  // the corner square at one of its ends: for each of the 2 * extent rows t across the border,
  // the boundary q in margin..corner_reach measured from that end's lattice point: the q nearest pixels
  // come from the corner, the rest from the band. The search scores a pair of samples by how
  // well they agree on the pixels either side of the boundary (Efros & Freeman's error,
  // `shown` false); the cut the tiles get (`shown`) pays the steps it shows instead: across the
  // boundary in every row, and along it where it moves between rows (there one pixel of the band
  // and one of the corner are vertical neighbours). With the error alone, skimage's brick showed
  // its corner-to-band cuts at 3-3.6 times the steps inside a sample, wherever they moved.
  CutPath end_cut(const std::vector<Pos>& pos, std::size_t edge, std::size_t corner, bool horizontal, bool far_end,
                  bool shown = false) const {
    const int n = g_.n, m = g_.margin, E = g_.extent;
    CutBand band;
    band.rows = 2 * E;
    band.width = g_.corner_reach - m + 1;
    band.lo.assign(std::size_t(band.rows), 0);
    band.hi.assign(std::size_t(band.rows), band.width - 1);
    band.cost.resize(std::size_t(band.rows) * std::size_t(band.width));
    if (shown) {
      band.rise.resize(band.cost.size());
      band.fall.resize(band.cost.size());
    }
    const float unit = float(e_.neighbour_difference);
    // the band's and the corner's pixel at distance `along` from the end's lattice point, inward,
    // and t across the border
    auto band_px = [&](int along, int t) {
      const int a = far_end ? n - 1 - along : along;
      return horizontal ? pix(pos, edge, a, t) : pix(pos, edge, t, a);
    };
    auto corner_px = [&](int along, int t) {
      const int a = far_end ? -1 - along : along;
      return horizontal ? pix(pos, corner, a, t) : pix(pos, corner, t, a);
    };
    for (int r = 0; r < band.rows; ++r) {
      const int t = r - E;
      for (int p = 0; p < band.width; ++p) {
        const int q = m + p;
        if (!shown) {
          band.at(r, p) =
              (x_.distance(band_px(q - 1, t), corner_px(q - 1, t)) + x_.distance(band_px(q, t), corner_px(q, t))) /
              unit;
          continue;
        }
        band.at(r, p) = x_.step(corner_px(q - 1, t), band_px(q, t)) / unit;
        if (r == 0) continue;
        // boundary q - 1 in row r - 1, q in row r: pixel q - 1 is the band's above, the corner's here
        const std::size_t i = std::size_t(r) * std::size_t(band.width) + std::size_t(p);
        band.rise[i] = x_.step(band_px(q - 1, t - 1), corner_px(q - 1, t)) / unit;
        // q + 1 in row r - 1, q in row r: pixel q is the corner's above, the band's here
        band.fall[i] = x_.step(corner_px(q, t - 1), band_px(q, t)) / unit;
      }
    }
    return min_error_cut(band);
  }

  // Every cut that sample j takes part in, with its error.
  double cut_error(std::size_t j, const std::vector<Pos>& pos) const {
    double sum = 0;
    if (j < c_) {
      const Colour c = Colour(j);
      for (Colour k = 0; k < c_; ++k) {
        sum += end_cut(pos, hedge(c, k), c, true, false).cost + end_cut(pos, hedge(k, c), c, true, true).cost;
        sum += end_cut(pos, vedge(c, k), c, false, false).cost + end_cut(pos, vedge(k, c), c, false, true).cost;
      }
      return sum;
    }
    const std::size_t k = (j - c_) % (c_ * c_);
    const Colour a = Colour(k / c_), b = Colour(k % c_);
    const bool horizontal = j < c_ + c_ * c_;
    return end_cut(pos, j, a, horizontal, false).cost + end_cut(pos, j, b, horizontal, true).cost;
  }
  double total_error(const std::vector<Pos>& pos) const {
    double sum = 0;
    for (std::size_t j = c_; j < slots_.size(); ++j) sum += cut_error(j, pos);
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
                               [&](std::size_t j, const std::vector<Pos>& pos) { return cut_error(j, pos); });
    cuts_.resize(slots_.size());
    for (std::size_t j = c_; j < slots_.size(); ++j) {
      const std::size_t k = (j - c_) % (c_ * c_);
      const bool horizontal = j < c_ + c_ * c_;
      cuts_[j] = {end_cut(pos_, j, Colour(k / c_), horizontal, false, true).pos,
                  end_cut(pos_, j, Colour(k % c_), horizontal, true, true).pos};
    }
    s.cut_error = total_error(pos_);
  }

  // The bands and corner squares of tile t, with the source of every pixel; the middle, which
  // no band reaches, is left for the centre patch.
  void compose_tiles(TextureTileSet& s) {
    const int n = g_.n, m = g_.margin, E = g_.extent;
    const std::size_t count = std::size_t(c_) * c_ * c_ * c_, px = std::size_t(n) * std::size_t(n);
    s.tiles.assign(count, Image{n, n, std::vector<std::uint8_t>(px * 4)});
    s.sources.assign(count, std::vector<std::uint32_t>(px, 0));
    if (o_.record_coords) s.coords.assign(count, std::vector<std::uint32_t>(px, 0));
    parallel_for(std::int64_t(count), o_.threads, [&](std::int64_t ti) {
      const CornerTile c = corner_tile(TileIndex(ti), c_);
      // the four bands: sample, distance of the pixel to its border, along-position from its
      // first end, its corners, the lattice point offsets of that first end
      struct Band {
        std::size_t sample;
        Colour first, second;
        bool horizontal;
        int origin_x, origin_y;  // the band's first lattice point, in tile coordinates
      };
      const Band bands[4] = {{hedge(c.nw, c.ne), c.nw, c.ne, true, 0, 0},
                             {hedge(c.sw, c.se), c.sw, c.se, true, 0, n},
                             {vedge(c.nw, c.sw), c.nw, c.sw, false, 0, 0},
                             {vedge(c.ne, c.se), c.ne, c.se, false, n, 0}};
      const int corner_x[4] = {0, n, 0, n}, corner_y[4] = {0, 0, n, n};
      const Colour corner_c[4] = {c.nw, c.ne, c.sw, c.se};
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          int edge = -1, edge_distance = n;
          std::size_t corner = c_;  // none
          for (int k = 0; k < 4; ++k) {
            const Band& b = bands[k];
            const int across = b.horizontal ? y - b.origin_y : x - b.origin_x;  // t: from the border
            const int along = b.horizontal ? x : y;
            if (across < -E || across >= E) continue;
            const std::vector<int>* cut = cuts_[b.sample].data();
            const int first = m + cut[0][std::size_t(across + E)], second = m + cut[1][std::size_t(across + E)];
            if (along < first)
              corner = b.first;
            else if (along >= n - second)
              corner = b.second;
            else if (const int d = across >= 0 ? across : -across - 1; d < edge_distance)
              edge = k, edge_distance = d;
          }
          const std::size_t i = std::size_t(y) * std::size_t(n) + std::size_t(x);
          std::uint8_t* out = s.tiles[std::size_t(ti)].pixels.data() + 4 * i;
          if (edge >= 0) {
            const Band& b = bands[edge];
            const int dx = x - b.origin_x, dy = y - b.origin_y;
            const std::uint8_t* from = pix(pos_, b.sample, dx, dy);
            std::copy_n(from, 4, out);
            if (!s.coords.empty()) s.coords[std::size_t(ti)][i] = exemplar_coord(e_, from);
            s.sources[std::size_t(ti)][i] = std::uint32_t(b.sample);
          } else if (corner < c_) {
            for (int k = 0; k < 4; ++k)
              if (corner_c[k] == corner && std::abs(x - corner_x[k]) <= E + 1 && std::abs(y - corner_y[k]) <= E + 1) {
                const std::uint8_t* from = pix(pos_, corner, x - corner_x[k], y - corner_y[k]);
                std::copy_n(from, 4, out);
                if (!s.coords.empty()) s.coords[std::size_t(ti)][i] = exemplar_coord(e_, from);
                break;
              }
            s.sources[std::size_t(ti)][i] = std::uint32_t(corner);
          }
        }
    });
  }

  SynthesisExemplar x_;
  const Exemplar& e_;
  const SynthesisOptions& o_;
  const TileGeometry g_;
  const std::uint32_t c_;
  std::vector<SampleDraw> draws_;  // corner squares, horizontal bands, vertical bands
  std::vector<SampleSlot> slots_;  // corners 0..C-1, horizontal bands C + a*C + b, vertical bands C + C^2 + a*C + b
  std::vector<Pos> pos_;
  std::vector<std::array<std::vector<int>, 2>> cuts_;  // per band sample: the cut at its first and second end
};

}  // namespace

TextureTileSet synthesize_corner_tiles(const Exemplar& e, const SynthesisOptions& o) {
  check_synthesis_options(e, o);
  SynthesisOptions with = o;
  with.record_coords = o.record_coords || !o.cost_maps.empty();  // the maps' costs look texels up by them
  return CornerSynthesis(e, with).run();
}

}  // namespace tilekit
