// Texture tiles: the options, the shared geometry, the naive baseline and the tile-set files.
#include "texture/tile_synthesis.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/parallel.hpp"
#include "base/random.hpp"

namespace tilekit {

TileGeometry::TileGeometry(int tile_px) : n(tile_px), half(tile_px / 2) {
  overlap = std::max(2, n / 16);
  patch = n + 2 * overlap;
  margin = std::max(5, n / 16);
  radius = half - margin;
  inner = std::max(2, n / 32);
  arm = margin + inner + 2;
}

void check_synthesis_options(const Exemplar& e, const SynthesisOptions& o) {
  if (o.tile_px < 16 || o.tile_px > 1024 || o.tile_px % 2)
    throw InputError(fmt::format("--tile-px must be an even number of pixels in 16..1024, got {}", o.tile_px));
  if (o.colours < 1 || o.colours > 16) throw InputError(fmt::format("--colors must be 1..16, got {}", o.colours));
  if (o.search < 0 || o.rounds < 0 || o.centre_candidates < 1 || o.centre_cuts < 1)
    throw InputError("--search and the centre candidates must not be negative");
  // Each round holds the candidates of one sample at once; beyond 2^16 a search costs hours per
  // round and the memory grows with it, while the exemplars have at most a few million positions.
  if (o.search > kMaxSynthesisSearch)
    throw InputError(fmt::format("--search {} is more than the {} candidates a round may try", o.search,
                                 kMaxSynthesisSearch));
  const TileGeometry g(o.tile_px);
  const int need = g.patch + 8;  // a sample of n + 2w pixels, with room to choose where
  if (e.width() < need || e.height() < need)
    throw InputError(
        fmt::format("{}: a {}x{} exemplar is too small for {}-pixel tiles: the samples need at least "
                    "{}x{} pixels (use a smaller --tile-px)",
                    e.name, e.width(), e.height(), o.tile_px, need, need));
  const double bytes = std::pow(double(o.colours), 4) * o.tile_px * o.tile_px * 6.0;
  if (bytes > double(1ull << 31))
    throw InputError(fmt::format("{} tiles of {} pixels need {:.1f} GB; use fewer colours or a smaller --tile-px",
                                 std::pow(double(o.colours), 4), o.tile_px, bytes / 1e9));
}

std::array<int, 2> random_sample_position(const Exemplar& e, int side, std::uint64_t seed) {
  SplitMix64 rng(seed);
  const int x = int(rng.below(std::uint64_t(e.width() - side + 1)));
  const int y = int(rng.below(std::uint64_t(e.height() - side + 1)));
  return {x, y};
}

double border_activity(const Exemplar& e, std::array<int, 2> c, int half, bool row, bool column) {
  double sum = 0;
  int pairs = 0;
  for (int i = -half; i < half; ++i) {
    if (row) sum += channel_step(e.at(c[0] + i, c[1] - 1), e.at(c[0] + i, c[1])), ++pairs;
    if (column) sum += channel_step(e.at(c[0] - 1, c[1] + i), e.at(c[0], c[1] + i)), ++pairs;
  }
  return pairs ? sum / pairs : 0.0;
}

SampleDraw::SampleDraw(const Exemplar& e, int side) : e_(&e), side_(side) {
  const int w = e.width(), h = e.height();
  integral_.assign(std::size_t(w + 1) * std::size_t(h + 1), 0.0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double a = 0;  // the steps to the east and south neighbours, averaged
      if (x + 1 < w && y + 1 < h)
        a = (channel_step(e.at(x, y), e.at(x + 1, y)) + channel_step(e.at(x, y), e.at(x, y + 1))) / 2;
      const std::size_t i = std::size_t(y + 1) * std::size_t(w + 1) + std::size_t(x + 1);
      integral_[i] = a + integral_[i - 1] + integral_[i - std::size_t(w + 1)] - integral_[i - std::size_t(w + 1) - 1];
    }
  std::vector<double> all;
  const int step = std::max(1, std::max(w, h) / 64);
  for (int y = 0; y + side <= h; y += step)
    for (int x = 0; x + side <= w; x += step) all.push_back(activity(x, y));
  std::nth_element(all.begin(), all.begin() + std::ptrdiff_t(all.size() / 2), all.end());
  median_ = all[all.size() / 2];
}

double SampleDraw::activity(int x, int y) const {
  const std::size_t W = std::size_t(e_->width() + 1), s = std::size_t(side_ - 1);
  auto at = [&](std::size_t xx, std::size_t yy) { return integral_[yy * W + xx]; };
  const std::size_t x0 = std::size_t(x), y0 = std::size_t(y);
  return (at(x0 + s, y0 + s) - at(x0, y0 + s) - at(x0 + s, y0) + at(x0, y0)) / double(s * s);
}

std::array<int, 2> SampleDraw::operator()(std::uint64_t seed) const {
  SplitMix64 rng(seed);
  std::array<int, 2> p{0, 0};
  for (int attempt = 0; attempt < 256; ++attempt) {
    p = {int(rng.below(std::uint64_t(e_->width() - side_ + 1))),
         int(rng.below(std::uint64_t(e_->height() - side_ + 1)))};
    const double a = activity(p[0], p[1]);
    if (a >= 0.85 * median_ && a <= 1.25 * median_) break;
  }
  return p;
}

double seam_goal_miss(double ratio) { return std::max(0.0, std::abs(ratio - 1) - kBorderTolerance); }

void search_samples(std::vector<std::array<int, 2>>& samples, const SampleDraw& draw, const SynthesisOptions& o,
                    const std::function<SampleScore(std::size_t, const std::vector<std::array<int, 2>>&)>& score) {
  for (int round = 0; o.search > 0 && round < o.rounds; ++round)
    for (std::size_t j = 0; j < samples.size(); ++j) {
      std::vector<std::array<int, 2>> cand(std::size_t(o.search));
      std::vector<SampleScore> scores(cand.size());
      const std::uint64_t stream = derive_seed(o.seed, 1000 + std::uint64_t(round) * samples.size() + j);
      for (std::size_t k = 0; k < cand.size(); ++k) cand[k] = draw(derive_seed(stream, k));
      parallel_for(std::int64_t(cand.size()), o.threads, [&](std::int64_t k) {
        std::vector<std::array<int, 2>> pos = samples;
        pos[j] = cand[std::size_t(k)];
        scores[std::size_t(k)] = score(j, pos);
      });
      const std::size_t best = std::size_t(std::min_element(scores.begin(), scores.end()) - scores.begin());
      if (scores[best] < score(j, samples)) samples[j] = cand[best];
    }
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
    for (int y = 0; y < n; ++y) std::copy_n(s.tiles[std::size_t(t)].at(0, y), std::size_t(n) * 4, sheet.at(x0, y0 + y));
  }
  return sheet;
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
          {"seconds", s.seconds}};
}

void write_tile_set(const TextureTileSet& s, const std::string& dir, const std::string& exemplar) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir, ec)) throw InputError(fmt::format("{}: cannot create the folder", dir));
  for (std::size_t t = 0; t < s.tiles.size(); ++t)
    write_png((fs::path(dir) / fmt::format("tile-{:04d}.png", t)).string(), s.tiles[t]);
  write_png((fs::path(dir) / "tileset.png").string(), tile_set_sheet(s));
  nlohmann::json j = tile_set_json(s);
  j["exemplar"] = exemplar;
  j["files"] = "tile-NNNN.png, named by tile index (thesis eq. 2.2 / 2.5)";
  write_file_atomic((fs::path(dir) / "tiles.json").string(), j.dump(2) + "\n");
}

}  // namespace tilekit
