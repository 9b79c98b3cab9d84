// Texture tiles: the options, the shared geometry, the naive baseline and the tile-set files.
#include "texture/tile_synthesis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <numbers>
#include <numeric>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/parallel.hpp"
#include "base/progress.hpp"
#include "base/random.hpp"
#include "base/signals.hpp"
#include "texture/graph_cut.hpp"
#include "texture/material.hpp"

namespace tilekit {

TileGeometry::TileGeometry(int tile_px, bool thin) : n(tile_px), thin(thin) {
  margin = std::max(3, (thin ? 3 : 5) * n / 64);
  corner_reach = margin + std::max(2, 3 * n / 32);
  strip = thin ? margin + std::max(2, 3 * n / 16) : corner_reach;
  extent = strip + 2;
}

bool thin_bands(const SynthesisOptions& o, const SynthesisExemplar& x) {
  return o.thin_bands && !x.periodic();
}

void check_synthesis_options(const Exemplar& e, const SynthesisOptions& o) {
  if (o.tile_px < 16 || o.tile_px > 1024 || o.tile_px % 2)
    throw RequestError("tile_px",
                       fmt::format("`tile_px` must be an even number of pixels in 16..1024, got {}", o.tile_px));
  if (o.colours < 1 || o.colours > 16)
    throw RequestError("colours", fmt::format("`colours` must be 1..16, got {}", o.colours));
  if (o.search < 0 || o.rounds < 0 || o.centre_candidates < 1 || o.centre_cuts < 1)
    throw RequestError("search", "`search` and the centre candidates must not be negative");
  // Each round holds the candidates of one sample at once; beyond 2^16 a search costs hours per
  // round and the memory grows with it, while the exemplars have at most a few million positions.
  if (o.search > kMaxSynthesisSearch)
    throw RequestError("search", fmt::format("`search` {} is more than the {} candidates a round may try", o.search,
                                             kMaxSynthesisSearch));
  const int need = o.tile_px + 16;  // a centre patch of n pixels, with room to choose where
  if (e.width() < need || e.height() < need)
    throw RequestError("tile_px",
                       fmt::format("{}: a {}x{} exemplar is too small for {}-pixel tiles: the samples need at least "
                                   "{}x{} pixels (use a smaller `tile_px`)",
                                   e.name, e.width(), e.height(), o.tile_px, need, need));
  const double bytes = std::pow(double(o.colours), 4) * o.tile_px * o.tile_px * 6.0;
  if (bytes > double(1ull << 31))
    throw RequestError("tile_px",
                       fmt::format("{} tiles of {} pixels need {:.1f} GB; use fewer colours or a smaller `tile_px`",
                                   std::pow(double(o.colours), 4), o.tile_px, bytes / 1e9));
}

std::array<int, 2> random_sample_position(const Exemplar& e, int side, std::uint64_t seed) {
  SplitMix64 rng(seed);
  const int x = int(rng.below(std::uint64_t(e.width() - side + 1)));
  const int y = int(rng.below(std::uint64_t(e.height() - side + 1)));
  return {x, y};
}

double line_activity(const Exemplar& e, int x, int y, int length, bool horizontal) {
  double sum = 0;
  for (int i = 0; i < length; ++i)
    sum += horizontal ? channel_step(e.at(x + i, y - 1), e.at(x + i, y))
                      : channel_step(e.at(x - 1, y + i), e.at(x, y + i));
  return length ? sum / length : 0.0;
}

double seam_goal_miss(double ratio) {
  return std::max(0.0, std::abs(ratio - 1) - kBorderTolerance);
}

void SynthesisExemplar::build_planes(const SynthesisOptions& o) {
  colour_weight_ = float(o.colour_weight);
  if (o.cost_maps.empty()) return;
  const int ew = e_.width(), eh = e_.height();
  struct Plane {
    Image map;  // as sampled
    int channels;
    bool normal;
    double weight;
  };
  std::vector<Plane> maps;
  for (const SeamCostMap& m : o.cost_maps) {
    Image img = map_as_sampled(m.image, e_.wrap_w > 0, perspective_, scale_);
    bool grey = !m.normal;
    for (int y = 0; grey && y < img.height; ++y)
      for (int x = 0; grey && x < img.width; ++x)
        grey = img.sample(x, y, 0) == img.sample(x, y, 1) && img.sample(x, y, 0) == img.sample(x, y, 2);
    maps.push_back({std::move(img), grey ? 1 : 3, m.normal, m.weight});
    map_widths_.push_back(grey ? 1 : 3);
    map_channels_ += grey ? 1 : 3;
  }
  planes_.assign(std::size_t(ew) * std::size_t(eh) * std::size_t(map_channels_), 0.0f);
  int offset = 0;
  for (const Plane& m : maps) {
    const int mw = m.map.width, mh = m.map.height;
    const double max = m.map.max_value();
    auto value = [&](int x, int y, int c) {
      const double v = m.map.sample(x, y, c) / max;
      return m.normal ? 2 * v - 1 : v;
    };
    // the map's unit: its mean step between 4-neighbours (what a cut through it shows)
    double sum = 0;
    std::size_t pairs = 0;
    for (int y = 0; y + 1 < mh; ++y)
      for (int x = 0; x + 1 < mw; ++x)
        for (auto [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
          double d2 = 0;
          for (int c = 0; c < m.channels; ++c) d2 += std::pow(value(x, y, c) - value(x + dx, y + dy, c), 2);
          sum += std::sqrt(d2), ++pairs;
        }
    const double unit = pairs ? sum / double(pairs) : 0.0;
    const double scale = unit > 0 ? m.weight / unit : 0.0;
    for (int y = 0; y < eh; ++y)
      for (int x = 0; x < ew; ++x) {
        // the torus' copies repeat the map; elsewhere the sizes agree (at most a rounding apart)
        const int mx = e_.wrap_w ? x % mw : std::min(x, mw - 1), my = e_.wrap_h ? y % mh : std::min(y, mh - 1);
        float* f = planes_.data() + (std::size_t(y) * std::size_t(ew) + std::size_t(x)) * std::size_t(map_channels_) +
                   std::size_t(offset);
        for (int c = 0; c < m.channels; ++c) f[c] = float(scale * value(mx, my, c));
      }
    offset += m.channels;
  }
}

SynthesisExemplar::SynthesisExemplar(const Exemplar& e, const SynthesisOptions& o) : e_(e) {
  if (!o.keep_period) {
    build_planes(o);
    return;
  }
  if (o.rectify) {
    perspective_ = fit_perspective(e);
    if (perspective_.applied) e_ = rectify_exemplar(e, perspective_);
  }
  found_ = dominant_period(e_);
  if (o.period_override[0] > 0 || o.period_override[1] > 0) {  // the user's period (0: none along that axis)
    found_.x = o.period_override[0], found_.y = o.period_override[1];
    found_.strength_x = found_.x > 0 ? 1 : 0, found_.strength_y = found_.y > 0 ? 1 : 0;
  }
  // the tile holds k whole periods, k the nearest whole number; at most 25 % of stretch
  for (int axis = 0; axis < 2; ++axis) {
    const double p = axis == 0 ? found_.x : found_.y;
    if (p <= 0) continue;
    const double k = std::max(1.0, std::round(o.tile_px / p)), s = o.tile_px / (k * p);
    if (std::abs(s - 1) > 0.25) continue;
    scale_[std::size_t(axis)] = s;
    step_[std::size_t(axis)] = o.tile_px / k;
  }
  if (scale_[0] != 1 || scale_[1] != 1) e_ = resample_exemplar(e_, scale_[0], scale_[1]);
  // The phase: where the lines (where they are clear) fall on the tile borders. A border then
  // runs along a mortar line, both tiles' bands hold its halves and a little of the faces beside
  // it, and the cuts to the centre patches run close to the line instead of across the middle of
  // the bricks (skimage's brick: cut visibility 1.78 -> 1.54, seam ratio 1.71 -> 1.05). A
  // rectified wall is periodic only roughly, so its phase is that of a tile-sized window in the
  // middle, and every sample is then moved to put its own lines there (in_phase). Any other
  // exemplar repeats exactly: its phase comes from the whole of it (lines too faint for one
  // window, like the ends of planks, still count), and samples are not moved (a window's own
  // estimate of its lines, off by a few pixels, broke a tile floor's grout at the corners).
  const int n = o.tile_px;
  const bool whole = !perspective_.applied;
  const std::array<int, 2> p =
      whole ? std::array<int, 2>{0, 0}
            : std::array<int, 2>{std::max(0, (e_.width() - n) / 2), std::max(0, (e_.height() - n) / 2)};
  const int rw = whole ? e_.width() - 1 : std::min(n, e_.width() - p[0] - 1);
  const int rh = whole ? e_.height() - 1 : std::min(n, e_.height() - p[1] - 1);
  for (std::size_t k = 0; k < 2; ++k)
    if (step_[k] > 0) {
      phase_[k] = std::fmod(p[k], step_[k]);
      // the lines' own spacing: the period's harmonic (step / j, at least 6 px) whose component
      // is strongest in that window (a two-row bond has its bed joints at half the period)
      double clearest = 0;
      for (int j = 1; j <= 4 && step_[k] / j >= 6; ++j) {
        const double c = line_clarity(p, rw, rh, k, step_[k] / j);
        if (c > clearest) clearest = c, harmonic_[k] = j;
      }
      lines_[k] = line_phase(p, 0, rw, rh, k, whole ? 0.0 : kLinesClear);
      if (std::isnan(lines_[k])) continue;
      // Lines at a spacing of the period / j lie at `lines` + i period / j; of these j the one
      // with the strongest lines over the whole exemplar, folded by the period, goes on the border
      // (planks: their edges, not a line of the grain a third of a plank away). A rectified wall's
      // lines are not where the whole exemplar folded puts them: there the window's stay.
      double at = lines_[k];
      if (whole && harmonic_[k] > 1) {
        const std::vector<double> g = gradient_profile(k);
        double best = -1;
        for (int i = 0; i < harmonic_[k]; ++i) {
          const double c = lines_[k] + i * step_[k] / harmonic_[k];
          double sum = 0;
          for (std::size_t q = 0; q < g.size(); ++q)
            if (std::abs(std::remainder(double(q) + 0.5 - (p[k] + c), step_[k])) <= 1.5) sum += g[q];
          if (sum > best) best = sum, at = c;
        }
      }
      phase_[k] = std::fmod(p[k] + at, step_[k]);
      lines_[k] = whole ? std::numeric_limits<double>::quiet_NaN() : 0.0;  // NaN: samples are not moved
    }
  build_planes(o);
}

std::vector<double> SynthesisExemplar::gradient_profile(std::size_t axis) const {
  const int along = axis == 0 ? e_.width() : e_.height(), across = axis == 0 ? e_.height() : e_.width();
  std::vector<double> g(std::size_t(std::max(0, along - 1)), 0.0);
  for (int c = 0; c + 1 < along; ++c)
    for (int r = 0; r < across; ++r) {
      const int x = axis == 0 ? c : r, y = axis == 0 ? r : c;
      g[std::size_t(c)] += std::abs(luma(e_.at(x + (axis == 0), y + (axis == 1))) - luma(e_.at(x, y)));
    }
  return g;
}

double SynthesisExemplar::line_clarity(std::array<int, 2> p, int w, int h, std::size_t axis, double spacing) const {
  std::complex<double> sum = 0;
  double total = 0;
  const int along = axis == 0 ? w : h, across = axis == 0 ? h : w;
  for (int c = 0; c + 1 < along; ++c) {
    double g = 0;
    for (int r = 0; r < across; ++r) {
      const int x = p[0] + (axis == 0 ? c : r), y = p[1] + (axis == 0 ? r : c);
      g += std::abs(luma(e_.at(x + (axis == 0), y + (axis == 1))) - luma(e_.at(x, y)));
    }
    sum += g * std::polar(1.0, -2 * std::numbers::pi * (c + 0.5) / spacing);
    total += g;
  }
  return total > 0 ? std::abs(sum) / total : 0.0;
}

double SynthesisExemplar::line_phase(std::array<int, 2> p, int u, int w, int h, std::size_t axis, double clear) const {
  const double step = step_[axis] / harmonic_[axis];
  std::complex<double> sum = 0;
  double total = 0;
  const int along = axis == 0 ? w : h, across = axis == 0 ? h : w;
  for (int c = 0; c + 1 < along; ++c) {
    double g = 0;  // the gradient along the axis, summed across the window
    for (int r = 0; r < across; ++r) {
      const int x = p[0] + (axis == 0 ? c : r), y = p[1] + (axis == 0 ? r : c);
      g += std::abs(luma(e_.at(x + (axis == 0), y + (axis == 1))) - luma(e_.at(x, y)));
    }
    sum += g * std::polar(1.0, -2 * std::numbers::pi * (u + c + 0.5) / step);
    total += g;
  }
  if (total <= 0 || std::abs(sum) <= clear * total) return std::nan("");
  return std::fmod(-std::arg(sum) / (2 * std::numbers::pi) * step + step, step);
}

std::array<int, 2> SynthesisExemplar::in_phase(std::array<int, 2> p, int u, int v, int w, int h) const {
  const int uv[2] = {u, v}, size[2] = {w, h}, extent[2] = {e_.width(), e_.height()};
  for (std::size_t k = 0; k < 2; ++k) {
    const double step = step_[k];
    if (step <= 0) continue;
    const double target = uv[k] + phase_[k];
    double q = target + step * std::round((p[k] - target) / step);
    while (q > extent[k] - size[k]) q -= step;
    while (q < 0) q += step;
    p[k] = std::clamp(int(std::lround(q)), 0, extent[k] - size[k]);
    if (std::isnan(lines_[k])) continue;  // not refined (an exemplar that repeats exactly)
    const double lines = line_phase(p, uv[k], w, h, k);
    if (std::isnan(lines)) continue;
    // moving the window by s moves its lines by -s in lattice coordinates
    const double spacing = step / harmonic_[k], s = std::remainder(lines - lines_[k], spacing);
    if (std::abs(s) <= spacing / 4) p[k] = std::clamp(p[k] + int(std::lround(s)), 0, extent[k] - size[k]);
  }
  return p;
}

SampleDraw::SampleDraw(const Exemplar& e, int w, int h) : e_(&e), w_(w), h_(h) {
  const int ew = e.width(), eh = e.height();
  range_x_ = e.wrap_w && ew - w + 1 >= e.wrap_w ? e.wrap_w : ew - w + 1;
  range_y_ = e.wrap_h && eh - h + 1 >= e.wrap_h ? e.wrap_h : eh - h + 1;
  integral_.assign(std::size_t(ew + 1) * std::size_t(eh + 1), 0.0);
  for (int y = 0; y < eh; ++y)
    for (int x = 0; x < ew; ++x) {
      double a = 0;  // the steps to the east and south neighbours, averaged
      if (x + 1 < ew && y + 1 < eh)
        a = (channel_step(e.at(x, y), e.at(x + 1, y)) + channel_step(e.at(x, y), e.at(x, y + 1))) / 2;
      const std::size_t i = std::size_t(y + 1) * std::size_t(ew + 1) + std::size_t(x + 1);
      integral_[i] = a + integral_[i - 1] + integral_[i - std::size_t(ew + 1)] - integral_[i - std::size_t(ew + 1) - 1];
    }
  std::vector<double> all;
  const int step = std::max(1, std::max(range_x_, range_y_) / 64);
  for (int y = 0; y < range_y_; y += step)
    for (int x = 0; x < range_x_; x += step) all.push_back(activity(x, y));
  std::nth_element(all.begin(), all.begin() + std::ptrdiff_t(all.size() / 2), all.end());
  median_ = all[all.size() / 2];
}

double SampleDraw::activity(int x, int y) const {
  const std::size_t W = std::size_t(e_->width() + 1), sx = std::size_t(w_ - 1), sy = std::size_t(h_ - 1);
  auto at = [&](std::size_t xx, std::size_t yy) { return integral_[yy * W + xx]; };
  const std::size_t x0 = std::size_t(x), y0 = std::size_t(y);
  return (at(x0 + sx, y0 + sy) - at(x0, y0 + sy) - at(x0 + sx, y0) + at(x0, y0)) /
         double(std::max<std::size_t>(1, sx * sy));
}

std::array<int, 2> SampleDraw::operator()(std::uint64_t seed, std::size_t stratum, std::size_t strata) const {
  // the stratum: cell k of a gx x gy grid over the positions, gx / gy about range_x / range_y
  const double aspect = double(range_x_) / double(range_y_);
  const std::size_t gx = std::clamp<std::size_t>(std::size_t(std::ceil(std::sqrt(double(strata) * aspect))), 1,
                                                 std::size_t(range_x_)),
                    gy = std::min<std::size_t>((strata + gx - 1) / gx, std::size_t(range_y_));
  const std::size_t cx = stratum % gx, cy = (stratum / gx) % gy;
  const int x0 = int(cx * std::size_t(range_x_) / gx), x1 = int((cx + 1) * std::size_t(range_x_) / gx);
  const int y0 = int(cy * std::size_t(range_y_) / gy), y1 = int((cy + 1) * std::size_t(range_y_) / gy);
  SplitMix64 rng(seed);
  std::array<int, 2> p{0, 0};
  for (int attempt = 0; attempt < 256; ++attempt) {
    p = {x0 + int(rng.below(std::uint64_t(std::max(1, x1 - x0)))),
         y0 + int(rng.below(std::uint64_t(std::max(1, y1 - y0))))};
    const double a = activity(p[0], p[1]);
    if (a >= 0.85 * median_ && a <= 1.25 * median_) break;
  }
  return p;
}

void own_strata(std::vector<SampleSlot>& slots, const TileGeometry& g) {
  if (!g.thin) return;
  for (std::size_t j = 0; j < slots.size(); ++j) slots[j].stratum = j, slots[j].strata = slots.size();
}

double window_overlap(const Exemplar& e, std::array<int, 2> pa, int w, int h, std::array<int, 2> pb, int wb, int hb) {
  auto along = [](int a, int la, int b, int lb, int wrap) {
    if (!wrap) return std::max(0, std::min(a + la, b + lb) - std::max(a, b));
    int best = 0;  // the torus: b's copies one wrap either way
    for (int k = -2; k <= 2; ++k)
      best = std::max(best, std::min(a + la, b + k * wrap + lb) - std::max(a, b + k * wrap));
    return std::max(0, std::min(best, la));
  };
  return double(along(pa[0], w, pb[0], wb, e.wrap_w)) * along(pa[1], h, pb[1], hb, e.wrap_h) / (double(w) * h);
}

double search_samples(std::vector<std::array<int, 2>>& samples, const std::vector<SampleSlot>& slots,
                      const std::vector<SampleDraw>& draws, const SynthesisExemplar& x, const SynthesisOptions& o,
                      const std::function<double(std::size_t, const std::vector<std::array<int, 2>>&)>& cut_error) {
  const Exemplar& e = x.exemplar();
  auto overlap = [&](std::size_t j, const std::vector<std::array<int, 2>>& pos) {
    double sum = 0;
    for (std::size_t k = 0; k < pos.size(); ++k)
      if (k != j) sum += window_overlap(e, pos[j], slots[j].w, slots[j].h, pos[k], slots[k].w, slots[k].h);
    return sum;
  };
  auto score = [&](std::size_t j, const std::vector<std::array<int, 2>>& pos) {
    const SampleSlot& s = slots[j];
    const double line = line_activity(e, pos[j][0] + s.line_x, pos[j][1] + s.line_y, s.line_length, s.line_horizontal);
    const double own = draws[std::size_t(s.draw)].activity(pos[j][0], pos[j][1]);
    return SampleScore{seam_goal_miss(own > 0 ? line / own : 1), cut_error(j, pos) + kOverlapWeight * overlap(j, pos)};
  };
  for (int round = 0; o.search > 0 && round < o.rounds; ++round)
    for (std::size_t j = 0; j < samples.size(); ++j) {
      throw_if_interrupted();  // the search of a large set takes seconds: a signal ends it too
      const SampleSlot& s = slots[j];
      std::vector<std::array<int, 2>> cand(std::size_t(o.search));
      std::vector<SampleScore> scores(cand.size());
      const std::uint64_t stream = derive_seed(o.seed, 1000 + std::uint64_t(round) * samples.size() + j);
      for (std::size_t k = 0; k < cand.size(); ++k)
        cand[k] =
            x.in_phase(draws[std::size_t(s.draw)](derive_seed(stream, k), s.stratum, s.strata), s.u, s.v, s.w, s.h);
      parallel_for(std::int64_t(cand.size()), o.threads, [&](std::int64_t k) {
        std::vector<std::array<int, 2>> pos = samples;
        pos[j] = cand[std::size_t(k)];
        scores[std::size_t(k)] = score(j, pos);
      });
      const std::size_t best = std::size_t(std::min_element(scores.begin(), scores.end()) - scores.begin());
      if (scores[best] < score(j, samples)) samples[j] = cand[best];
    }
  double sum = 0;
  for (std::size_t j = 0; j < samples.size(); ++j) sum += overlap(j, samples);
  return samples.empty() ? 0.0 : sum / double(samples.size());
}

double merge_centre_patches(TextureTileSet& s, const SynthesisExemplar& x, const SynthesisOptions& o,
                            const std::string& title) {
  const Exemplar& e = x.exemplar();
  const TileGeometry g(s.tile_px, thin_bands(o, x));
  const int n = g.n;
  const std::size_t count = s.tiles.size(), px = std::size_t(n) * std::size_t(n);
  // The pixels the centre may take (at least `margin` from every border), the ones it must take
  // (beyond `strip`, where no shared sample reaches), and the band between, where the cut runs.
  std::vector<std::uint8_t> region(px, 0), forced(px, 0);
  std::vector<std::size_t> band;
  for (int y = 0; y < n; ++y)
    for (int xx = 0; xx < n; ++xx) {
      const int d = std::min({xx, y, n - 1 - xx, n - 1 - y});
      const std::size_t i = std::size_t(y) * std::size_t(n) + std::size_t(xx);
      region[i] = d >= g.margin;
      forced[i] = d >= g.strip;
      if (region[i] && !forced[i]) band.push_back(i);
    }
  const SampleDraw draw(e, n, n);
  const double pull = g.thin ? kCentrePull * e.neighbour_difference : 0.0;
  const int candidates = o.search > 0 ? o.centre_candidates : 1, cuts = o.search > 0 ? o.centre_cuts : 1;
  ProgressReporter progress(title, 2.0 * double(count), o.progress);
  // 1. Candidates from the whole exemplar, in phase, ranked by their difference to the tile on
  //    the band where the cut runs.
  using Scored = std::pair<double, std::array<int, 2>>;
  std::vector<std::vector<Scored>> ranked(count);
  parallel_for(std::int64_t(count), o.threads, [&](std::int64_t ti) {
    throw_if_interrupted();  // a caught signal ends the synthesis: nothing is written (base/signals.hpp)
    const std::size_t t = std::size_t(ti);
    const Image& img = s.tiles[t];
    for (int k = 0; k < candidates; ++k) {
      const std::array<int, 2> q =
          x.in_phase(draw(derive_seed(derive_seed(o.seed, 7000 + t), std::uint64_t(k))), 0, 0, n, n);
      double d = 0;
      for (std::size_t i : band) {
        const std::uint8_t* c = e.at(q[0] + int(i % std::size_t(n)), q[1] + int(i / std::size_t(n)));
        d += x.has_cost_maps() ? o.colour_weight * colour_distance(img.pixels.data() + 4 * i, c) +
                                     x.map_cost(x.texel(s.coords[t][i]), x.texel(c))
                               : colour_distance(img.pixels.data() + 4 * i, c);
      }
      ranked[t].push_back({d, q});
    }
    std::stable_sort(ranked[t].begin(), ranked[t].end(),
                     [](const Scored& a, const Scored& b) { return a.first < b.first; });
    progress.add(1);
  });
  // 2. Distinct regions: in a seeded order, each tile keeps its best candidates that lie at least
  //    `apart` (in x or y, on the torus of a tileable exemplar) from every patch kept before, half
  //    the side of an equal share of the exemplar (the best one anyway when none does).
  const double area = double(e.wrap_w ? e.wrap_w : e.width() - n) * double(e.wrap_h ? e.wrap_h : e.height() - n);
  const int apart = std::max(1, int(0.5 * std::sqrt(area / double(count))));
  auto gap = [&](int a, int b, int wrap) {
    const int d = std::abs(a - b);
    return wrap ? std::min(d % wrap, wrap - d % wrap) : d;
  };
  std::vector<std::size_t> order(count);
  std::iota(order.begin(), order.end(), 0);
  SplitMix64 rng(derive_seed(o.seed, 6000));
  shuffle(order.begin(), order.end(), rng);
  std::vector<std::array<int, 2>> kept;
  std::vector<std::vector<std::array<int, 2>>> chosen(count);
  for (std::size_t t : order) {
    for (const Scored& c : ranked[t]) {
      if (int(chosen[t].size()) == cuts) break;
      const bool far = std::all_of(kept.begin(), kept.end(), [&](const std::array<int, 2>& p) {
        return gap(p[0], c.second[0], e.wrap_w) >= apart || gap(p[1], c.second[1], e.wrap_h) >= apart;
      });
      if (far) chosen[t].push_back(c.second);
    }
    if (chosen[t].empty()) chosen[t].push_back(ranked[t].front().second);
    kept.insert(kept.end(), chosen[t].begin(), chosen[t].end());
  }
  // 3. The full graph cut for each tile's kept candidates; the cheapest wins.
  std::vector<double> cost(count);
  s.centres.assign(count, {0, 0});
  parallel_for(std::int64_t(count), o.threads, [&](std::int64_t ti) {
    throw_if_interrupted();
    const std::size_t t = std::size_t(ti);
    Image& img = s.tiles[t];
    Image patch{n, n, std::vector<std::uint8_t>(px * 4)}, best_patch;
    GraphCutResult best;
    for (std::size_t k = 0; k < chosen[t].size(); ++k) {
      const std::array<int, 2> q = chosen[t][k];
      for (int y = 0; y < n; ++y) std::copy_n(e.at(q[0], q[1] + y), std::size_t(n) * 4, patch.at(0, y));
      // with cost maps, the maps' terms between the tile's texel at pixel i and the patch's at j
      const auto maps = [&](std::size_t i, std::size_t j) {
        return x.map_cost(x.texel(s.coords[t][i]),
                          x.texel(e.at(q[0] + int(j % std::size_t(n)), q[1] + int(j / std::size_t(n)))));
      };
      GraphCutResult r = x.has_cost_maps()
                             ? graph_cut_merge(img, patch, region, forced, pull, maps, float(o.colour_weight))
                             : graph_cut_merge(img, patch, region, forced, pull);
      if (k == 0 || r.cost < best.cost) best = std::move(r), best_patch = patch, s.centres[t] = q;
    }
    for (std::size_t i = 0; i < px; ++i)
      if (best.take_new[i]) {
        std::copy_n(best_patch.pixels.data() + 4 * i, 4, img.pixels.data() + 4 * i);
        s.sources[t][i] = s.shared_sources + std::uint32_t(t);
        if (!s.coords.empty())
          s.coords[t][i] = exemplar_coord(
              e, e.at(s.centres[t][0] + int(i % std::size_t(n)), s.centres[t][1] + int(i / std::size_t(n))));
      }
    cost[t] = best.cost;
    progress.add(1);
  });
  progress.finish();
  std::size_t shared = 0;
  for (const auto& src : s.sources)
    shared +=
        std::size_t(std::count_if(src.begin(), src.end(), [&](std::uint32_t id) { return id < s.shared_sources; }));
  s.shared_fraction = double(shared) / double(count * px);
  return std::accumulate(cost.begin(), cost.end(), 0.0) / double(count);
}

TextureTileSet synthesize_tiles(const Exemplar& e, const SynthesisOptions& o) {
  return o.kind == TileKind::Corner ? synthesize_corner_tiles(e, o) : synthesize_wang_tiles(e, o);
}

TextureTileSet naive_tiles(const Exemplar& e, const SynthesisOptions& o) {
  check_synthesis_options(e, o);
  TextureTileSet s;
  s.kind = o.kind;
  s.colours = o.colours;
  s.tile_px = o.tile_px;
  s.seed = o.seed;
  s.method = "naive";
  const std::size_t count = std::size_t(std::pow(o.colours, 4) + 0.5),
                    px = std::size_t(o.tile_px) * std::size_t(o.tile_px);
  for (std::size_t t = 0; t < count; ++t) {
    const auto [x0, y0] = random_sample_position(e, o.tile_px, derive_seed(o.seed, t));
    Image tile{o.tile_px, o.tile_px, std::vector<std::uint8_t>(px * 4)};
    for (int y = 0; y < o.tile_px; ++y) std::copy_n(e.at(x0, y0 + y), std::size_t(o.tile_px) * 4, tile.at(0, y));
    s.tiles.push_back(std::move(tile));
    if (o.record_coords) {
      s.coords.emplace_back(px);
      for (std::size_t i = 0; i < px; ++i)
        s.coords.back()[i] =
            exemplar_coord(e, e.at(x0 + int(i % std::size_t(o.tile_px)), y0 + int(i / std::size_t(o.tile_px))));
    }
    s.sources.emplace_back(px, std::uint32_t(t));
  }
  return s;
}

Image tile_set_sheet(const TextureTileSet& s, int gap) {
  const int count = int(s.tiles.size()), cols = std::max(1, int(std::ceil(std::sqrt(double(count))))),
            rows = (count + cols - 1) / cols, n = s.tile_px;
  Image sheet(cols * n + (cols + 1) * gap, rows * n + (rows + 1) * gap, Rgb{255, 255, 255});
  for (int t = 0; t < count; ++t) {
    const int x0 = gap + (t % cols) * (n + gap), y0 = gap + (t / cols) * (n + gap);
    const Image tile = s.tiles[std::size_t(t)].to_depth(8);
    for (int y = 0; y < n; ++y) std::copy_n(tile.at(0, y), std::size_t(n) * 4, sheet.at(x0, y0 + y));
  }
  return sheet;
}

std::string structure_message(const ExemplarPeriod& p) {
  if (!structure_likely(p)) return "";
  const bool x = p.x > 0, y = p.y > 0;
  if (x || y)
    return fmt::format(
        "a period was found along {} ({:g} px) but not along {} (strongest repeat {:.2f} of the {:.2f} "
        "needed): the {} keep their phase, the other axis does not; give both with the period option "
        "X,Y if it has one",
        x ? "x" : "y", x ? p.x : p.y, x ? "y" : "x", x ? p.weak_y : p.weak_x, kPeriodProminence,
        x ? "columns" : "courses");
  return fmt::format(
      "the exemplar looks structured (repeats of {:.2f} along x, {:.2f} along y, below the {:.2f} "
      "needed) but no period was found: bricks, tiles or planks may be cut; give the period option "
      "X,Y in pixels",
      p.weak_x, p.weak_y, kPeriodProminence);
}

nlohmann::json structure_json(const ExemplarPeriod& p) {
  return {{"period_found", {p.x > 0, p.y > 0}},
          {"strength", {p.strength_x, p.strength_y}},
          {"weak_repeat", {p.weak_x, p.weak_y}},
          {"likely_missed", structure_likely(p)},
          {"message", structure_message(p)}};
}

nlohmann::json tile_set_json(const TextureTileSet& s) {
  nlohmann::json samples = nlohmann::json::array();
  for (const auto& [x, y] : s.samples) samples.push_back({x, y});
  return {{"kind", std::string(kind_name(s.kind))},
          {"colors", s.colours},
          {"tile_px", s.tile_px},
          {"tiles", s.tiles.size()},
          {"seed", s.seed},
          {"method", s.method},
          {"samples", samples},
          {"cut_error_initial", s.cut_error_initial},
          {"cut_error", s.cut_error},
          {"centre_cost", s.centre_cost},
          {"sample_overlap", s.overlap},
          {"shared_fraction", s.shared_fraction},
          {"thin_bands", s.thin_bands},
          {"perspective",
           {{"applied", s.perspective.applied},
            {"axis", s.perspective.axis < 0    ? "none"
                     : s.perspective.axis == 0 ? "x"
                                               : "y"},
            {"lines", s.perspective.lines},
            {"rms_periods", s.perspective.rms},
            {"drift_periods", s.perspective.drift},
            {"spacing_spread", s.perspective.spread},
            {"homography", s.perspective.to_plane.m}}},
          {"period", {s.period.x, s.period.y}},
          {"structure", structure_json(s.period)},
          {"exemplar_scale", s.exemplar_scale},
          {"phase", s.phase},
          {"colour_space", "srgb"},
          {"seconds", s.seconds}};
}

Image source_labels(const TextureTileSet& s, TileIndex t) {
  const int n = s.tile_px;
  Image img(n, n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      // a bijection of 24-bit ids (an odd multiplier), so neighbouring ids get unlike colours
      const std::uint32_t v = (s.sources[t][std::size_t(y) * std::size_t(n) + std::size_t(x)] + 1) * 2654435761u;
      img.set(x, y, {std::uint8_t(v >> 16), std::uint8_t(v >> 8), std::uint8_t(v)});
    }
  return img;
}

// The set goes to a temp folder beside `out` that replaces the old folder whole (base/atomic_file.hpp
// AtomicFolder): a signal, a full disk or an error leaves the old set as it was, never a mix of old
// and new tiles, and a larger old set leaves no stale tile behind.
void write_tile_set(const TextureTileSet& s, const std::string& out, const std::string& exemplar,
                    const std::function<void(const std::string&, nlohmann::json&)>& more) {
  namespace fs = std::filesystem;
  std::error_code ec;
  AtomicFolder folder(out);
  const std::string& dir = folder.temp_path();
  for (std::size_t t = 0; t < s.tiles.size(); ++t) {
    throw_if_interrupted();
    write_png((fs::path(dir) / fmt::format("tile-{:04d}.png", t)).string(), s.tiles[t]);
  }
  write_png((fs::path(dir) / "tileset.png").string(), tile_set_sheet(s));
  if (s.sampled.width > 0) write_png((fs::path(dir) / "exemplar.png").string(), s.sampled);
  nlohmann::json j = tile_set_json(s);
  j["exemplar"] = exemplar;
  j["files"] = "tile-NNNN.png, named by tile index (thesis eq. 2.2 / 2.5); labels/: the sample of every pixel";
  const fs::path labels = fs::path(dir) / "labels";
  fs::create_directories(labels, ec);
  for (std::size_t t = 0; t < s.sources.size(); ++t)
    write_png((labels / fmt::format("tile-{:04d}.png", t)).string(), source_labels(s, TileIndex(t)));
  nlohmann::json jl = j;
  jl["files"] = "tile-NNNN.png: the sample each pixel was copied from, one colour per sample (texture_analysis.hpp)";
  jl["colour_space"] = "linear";  // ids, not colours: never averaged in linear light
  write_file_atomic((labels / "tiles.json").string(), jl.dump(2) + "\n");
  if (more) more(dir, j);
  write_file_atomic((fs::path(dir) / "tiles.json").string(), j.dump(2) + "\n");
  throw_if_interrupted();
  folder.commit();
}

}  // namespace tilekit
