// Whether rendered surfaces of texture tiles show their grid (texture/README.md's measures), per
// real texture, tile kind and C, one JSON line per case. Usage:
//   build/bench_texture_quality [--textures a,b,...] [--kinds corner,wang] [--colors 2,3,4]
//                               [--tile-px 64|auto] [--size 1024] [--threads 2] [--out DIR] [--speed REPS]
//                               [--bands default|thin]   (thin: SynthesisOptions::thin_bands)
//                               [--seed S]   (the synthesis' seed, SynthesisOptions::seed; 1 unless given)
//   quality/...  synthesis (seconds on --threads), the atlas of the packing, a flat size^2 CPU render
//                (at least 4 tiles across: a 480-px tile takes 1920^2)
//                at scale 1 and the labels of the same view; grid repetition, seam ratio, cut
//                visibility, histogram distance, lattice peak, line continuity beside the exemplar's
//                own on the same lattice at the synthesis' phase (line_continuity_vs_exemplar;
//                held-out ufo-* textures, scripts/fetch-textures.sh --held-out, as tori). --tile-px
//                auto: per texture the size `texture tiles --tile-px auto` picks (tile-px-auto/...).
//                Goals (corner, C = 4, 64 px): grid repetition <= 0.05 with seam ratio <= 1.10, cut
//                visibility <= 1.5; line continuity within 20 % of the exemplar's.
//   naive/...    the baseline of the same run: random crops of the exemplar abutted (no cuts, no
//                lattice repetition, visible seams)
//   speed/...    with --speed R: corner C = 4 synthesis on one thread, median of R runs (goal < 10 s)
// --out DIR writes every render as DIR/TEXTURE-KIND-cC.png (the README's pictures) and the naive
// mosaic as DIR/TEXTURE-naive.png.
#include <fmt/format.h>

#include <cstring>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "atlas/lookup.hpp"
#include "base/random.hpp"
#include "bench/bench_common.hpp"
#include "render/cpu_renderer.hpp"
#include "texture/texture_analysis.hpp"
#include "texture/texture_atlas.hpp"
#include "texture/tile_synthesis.hpp"

using namespace tilekit;
using tilekit::bench::median_midpoint;
using tilekit::bench::seconds_of;

namespace {

void print(nlohmann::json j) {
  j["bench"] = "texture_quality";
  j["cores"] = std::thread::hardware_concurrency();
  j["load"] = tilekit::bench::loadavg();
  fmt::print("{}\n", j.dump());
  std::fflush(stdout);
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

Exemplar texture(const std::string& name) {
  if (real_texture_path(name).empty()) {
    fmt::print(stderr, "bench_texture_quality: {} not fetched: run scripts/fetch-textures.sh\n", name);
    std::exit(1);
  }
  // the held-out game textures (scripts/fetch-textures.sh --held-out, ufo-* and re-*) are made to repeat
  return load_exemplar(real_texture_path(name),
                       is_tileable_real_texture(name) || name.rfind("ufo-", 0) == 0 || name.rfind("re-", 0) == 0);
}

nlohmann::json measures(const TextureAnalysis& a) {
  nlohmann::json j = {{"grid_repetition", a.grid_repetition},
                      {"lattice_correlation", a.lattice_correlation},
                      {"reference_correlation", a.reference_correlation},
                      {"lattice_peak_db", a.spectrum.lattice_peak_db}};
  if (a.seam_ratio) j["seam_ratio"] = *a.seam_ratio;
  if (a.cut_visibility) j["cut_visibility"] = *a.cut_visibility;
  if (a.histogram_distance) j["histogram_distance"] = *a.histogram_distance;
  if (a.line_continuity) j["line_continuity"] = *a.line_continuity;
  return j;
}

void quality(const std::string& name, const Exemplar& e, TileKind kind, std::uint32_t c, int px, int size, int threads,
             const std::string& out, bool thin, std::uint64_t seed) {
  SynthesisOptions o;
  o.seed = seed;
  o.thin_bands = thin;
  o.kind = kind;
  o.colours = c;
  o.tile_px = px;
  o.threads = threads;
  TextureTileSet s;
  const double seconds = seconds_of([&] { s = synthesize_tiles(e, o); });
  const AtlasLookup lookup = atlas_lookup(kind, c);
  std::vector<Image> labels;
  for (TileIndex t = 0; t < s.tiles.size(); ++t) labels.push_back(source_labels(s, t));
  const View view{size, size, 1, 0, 0, 0};
  const RenderOptions ro{HashKind::LongPeriod, 1, threads, false};
  const Image img = render_cpu(build_texture_atlas(lookup, s.tiles), view, ro);
  const Image lab = render_cpu(build_texture_atlas(lookup, labels), view, ro);
  const TextureAnalysis a = analyze_texture(img, Lattice::square(px), &e.image, &lab, threads);
  if (!out.empty()) write_png(fmt::format("{}/{}-{}-c{}.png", out, name, kind_name(kind), c), img);
  // The exemplar's own line continuity on the same lattice, as the samples saw it (rectified,
  // resampled), with a corner where the synthesis puts one (its phase; 0 along an axis without a
  // period): what the render's is compared with.
  const LineContinuity own = line_continuity(s.sampled.width ? s.sampled : e.image, px, int(std::lround(s.phase[0])),
                                             int(std::lround(s.phase[1])));
  nlohmann::json j = {{"case", fmt::format("quality/{}/{}/C={}", name, kind_name(kind), c)},
                      {"texture", name},
                      {"kind", std::string(kind_name(kind))},
                      {"colors", c},
                      {"tiles", s.tiles.size()},
                      {"tile_px", px},
                      {"render", fmt::format("{}x{} flat, scale 1", size, size)},
                      {"threads", threads},
                      {"seed", seed},
                      {"synthesis_seconds", seconds},
                      {"exemplar_scale", s.exemplar_scale},
                      {"sample_overlap", s.overlap},
                      {"shared_fraction", s.shared_fraction},
                      {"bands", s.thin_bands ? "thin" : "default"}};
  j.update(measures(a));
  j["exemplar_line_continuity"] = own.ratio;
  if (a.line_continuity && own.ratio > 0) j["line_continuity_vs_exemplar"] = *a.line_continuity / own.ratio;
  j["period"] = {s.period.x, s.period.y};
  j["phase"] = s.phase;
  print(j);
}

// Random px-square crops of the exemplar abutted on the lattice (the naive mosaic).
void naive(const std::string& name, const Exemplar& e, int px, int size, int threads, const std::string& out) {
  Image img(size, size);
  for (int r = 0; r * px < size; ++r)
    for (int c = 0; c * px < size; ++c) {
      const auto p = random_sample_position(e, px, derive_seed(7, std::uint64_t(r * 1000 + c)));
      for (int y = 0; y < px && r * px + y < size; ++y)
        for (int x = 0; x < px && c * px + x < size; ++x) {
          const std::uint8_t* q = e.at(p[0] + x, p[1] + y);
          img.set(c * px + x, r * px + y, {q[0], q[1], q[2]});
        }
    }
  const TextureAnalysis a = analyze_texture(img, Lattice::square(px), &e.image, nullptr, threads);
  if (!out.empty()) write_png(fmt::format("{}/{}-naive.png", out, name), img);
  nlohmann::json j = {{"case", fmt::format("naive/{}", name)}, {"texture", name}, {"tile_px", px}};
  j.update(measures(a));
  print(j);
}

// The same mosaic for a periodic exemplar kept in phase (SynthesisExemplar, as the synthesis
// sees it): random px-square crops, each at the in-phase position nearest a random draw, abutted.
// Bricks continue across the lattice and no content repeats on it, so its grid repetition is
// what the exemplar's own period, in phase with the lattice, adds to the measure: the floor of any
// synthesis that keeps the bricks whole.
void naive_in_phase(const std::string& name, const Exemplar& given, int px, int size, int threads,
                    const std::string& out) {
  SynthesisOptions o;
  o.tile_px = px;
  const SynthesisExemplar x(given, o);
  if (!x.periodic()) return;
  const Exemplar& e = x.exemplar();
  Image img(size, size);
  for (int r = 0; r * px < size; ++r)
    for (int c = 0; c * px < size; ++c) {
      const auto p =
          x.in_phase(random_sample_position(e, px, derive_seed(7, std::uint64_t(r * 1000 + c))), 0, 0, px, px);
      for (int y = 0; y < px && r * px + y < size; ++y)
        for (int xx = 0; xx < px && c * px + xx < size; ++xx) {
          const std::uint8_t* q = e.at(p[0] + xx, p[1] + y);
          img.set(c * px + xx, r * px + y, {q[0], q[1], q[2]});
        }
    }
  // The exemplar itself as the samples see it (rectified, resampled), on the same lattice with a
  // corner where the synthesis puts one: the wall's own score, no tiles at all.
  const Image& own = e.image;
  if (own.width >= 4 * px && own.height >= 4 * px) {
    Lattice l = Lattice::square(px);
    l.offset = {std::round(x.phase()[0]), std::round(x.phase()[1])};
    const TextureAnalysis a = analyze_texture(own, l, &given.image, nullptr, threads);
    nlohmann::json j = {{"case", fmt::format("exemplar-in-phase/{}", name)},
                        {"texture", name},
                        {"tile_px", px},
                        {"size", {own.width, own.height}}};
    j.update(measures(a));
    print(j);
  }
  const TextureAnalysis a = analyze_texture(img, Lattice::square(px), &given.image, nullptr, threads);
  if (!out.empty()) write_png(fmt::format("{}/{}-naive-in-phase.png", out, name), img);
  nlohmann::json j = {{"case", fmt::format("naive-in-phase/{}", name)},
                      {"texture", name},
                      {"tile_px", px},
                      {"exemplar_scale", x.scale()},
                      {"period", {x.period().x, x.period().y}}};
  j.update(measures(a));
  print(j);
}

void speed(const std::string& name, const Exemplar& e, int px, int reps) {
  SynthesisOptions o;
  o.kind = TileKind::Corner;
  o.colours = 4;
  o.tile_px = px;
  o.threads = 1;
  std::vector<double> t;
  for (int r = 0; r < reps; ++r) t.push_back(seconds_of([&] { synthesize_tiles(e, o); }));
  print({{"case", fmt::format("speed/{}/corner/C=4", name)},
         {"tiles", 256},
         {"tile_px", px},
         {"threads", 1},
         {"reps", reps},
         {"median_seconds", median_midpoint(t)},
         {"seconds", t},
         {"goal", "< 10 s on one thread"}});
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> textures, kinds = {"corner", "wang"};
  for (const RealTexture& t : real_textures()) textures.push_back(t.name);
  std::vector<std::uint32_t> colours = {2, 3, 4};
  int px = 64, size = 1024, threads = 2, reps = 0;
  std::string out;
  bool thin = false, auto_px = false;
  std::uint64_t seed = 1;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i], value = argv[i + 1];
    if (flag == "--textures") textures = split(value);
    if (flag == "--kinds") kinds = split(value);
    if (flag == "--colors") {
      colours.clear();
      for (const std::string& c : split(value)) colours.push_back(std::uint32_t(std::stoul(c)));
    }
    if (flag == "--tile-px") auto_px = value == "auto", px = auto_px ? 0 : std::stoi(value);
    if (flag == "--size") size = std::stoi(value);
    if (flag == "--threads") threads = std::stoi(value);
    if (flag == "--out") out = value;
    if (flag == "--speed") reps = std::stoi(value);
    if (flag == "--bands") thin = value == "thin";
    if (flag == "--seed") seed = std::stoull(value);
  }
  for (const std::string& name : textures) {
    const Exemplar e = texture(name);
    if (auto_px) {  // texture tiles --tile-px auto (texture/exemplar.hpp)
      const TileSizeChoice choice = choose_tile_size(e, dominant_period(e));
      px = choice.tile_px;
      print({{"case", fmt::format("tile-px-auto/{}", name)}, {"tile_px", px}, {"reason", choice.reason}});
    }
    if (reps > 0) {
      speed(name, e, px, reps);
      continue;
    }
    const int view = std::max(size, 4 * px);  // the lattice's analysis takes lags up to twice the spacing
    naive(name, e, px, view, threads, out);
    naive_in_phase(name, e, px, view, threads, out);
    for (const std::string& k : kinds)
      for (std::uint32_t c : colours)
        quality(name, e, k == "wang" ? TileKind::Wang : TileKind::Corner, c, px, view, threads, out, thin, seed);
  }
  return 0;
}
