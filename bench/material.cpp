// Material sets (texture/material.hpp) on the held-out textures, which no tuning decision looks
// at (scripts/fetch-textures.sh --held-out: colour, normal and specular maps of UFO: Alien
// Invasion, ufo-*, and of Red Eclipse's trak4 surfaces, re-*). One JSON line per case.
// Usage: build/bench_material [--reps R] [--seeds S] [--only PREFIX] [--textures NAME,...]
//   material-seams/NAME/{albedo,all}  corner tiles (C = 4, 64 px, one thread, seeds 1..S, default
//       3: the albedo-only and the all-map run of one seed are a pair) whose samples and cuts are
//       chosen on the albedo alone or on every map (--map-cost), the normal map carried by the
//       recorded texels either way; a 16x16-tile window of the tiling, lit through its normal map
//       (albedo in linear light x (0.15 + 0.85 max(0, n.l)), back to sRGB), light from the upper
//       left at 50 degrees: cut_ratio is the step across sample boundaries (cut_step) over the step
//       inside samples (same_source_step) in that render (texture/seam_metrics.hpp); ring_cut_ratio
//       the mean of the same over 8 lights all round at that elevation (no light favoured);
//       shading_cut_ratio the same for the shading alone (grey albedo), normal_cut_ratio and
//       albedo_cut_ratio on the maps themselves. The all-map run draws its samples with the
//       maps in the cost too, so a pair differs in samples as well as cuts: one seed's
//       difference mixes the two (seed to seed the lit ratio moves by up to 0.07), hence seeds.
//   material-seams-mean/NAME  the means over the seeds of both runs.
//   material-seams-tally/SET  per set (ufo, re): of its textures, on how many the all-map mean is
//       lower (lit, 8 lights, shading), and in how many of the seed pairs the lit ratio is lower.
//   material-speed/NAME  synthesis of the albedo alone against a four-map material (albedo,
//       normal, specular, height), C = 4, 64 px, one thread, interleaved; the median of R runs
//       each; goal: ratio <= 2.
#include "texture/material.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include "bench/bench_common.hpp"
#include "texture/seam_metrics.hpp"
#include "texture/tile_synthesis.hpp"
#include "tiling/direct_tiling.hpp"

using namespace tilekit;

namespace {

void print(nlohmann::json j) {
  j["bench"] = "material";
  j["cores"] = std::thread::hardware_concurrency();
  j["load"] = bench::loadavg();
  fmt::print("{}\n", j.dump());
  std::fflush(stdout);
}

struct HeldOut {
  std::string name;
  Image albedo;
  std::vector<MaterialMap> maps;  // normal, then spec and height where there are
};

HeldOut held_out(const std::string& name) {
  const std::string path = real_texture_path(name), normal = real_texture_path(name + ".normal");
  if (path.empty() || normal.empty()) {
    fmt::print(stderr, "bench_material: {} not fetched: run scripts/fetch-textures.sh --held-out\n", name);
    std::exit(1);
  }
  HeldOut h{name, read_image(path), {}};
  h.maps.push_back(parse_material_map("normal=" + normal + ":normal"));
  if (const std::string spec = real_texture_path(name + ".spec"); !spec.empty())
    h.maps.push_back(parse_material_map("spec=" + spec + ":linear"));
  resize_maps(h.maps, h.albedo.width, h.albedo.height, true);
  if (const char* w = std::getenv("TILEKIT_MAP_WEIGHT"))  // every map's WEIGHT
    for (MaterialMap& m : h.maps) m.weight = std::atof(w);
  return h;
}

constexpr double kAlbedoWeight = 1.0;

SynthesisOptions options(std::uint64_t seed = 1) {
  SynthesisOptions o;
  o.kind = TileKind::Corner;
  o.colours = 4;
  o.tile_px = 64;
  o.seed = seed;
  o.threads = 1;
  o.thin_bands = true;
  o.record_coords = true;
  return o;
}

TextureTileSet synthesize(const HeldOut& h, bool all_maps, const std::vector<MaterialMap>& maps,
                          std::uint64_t seed = 1) {
  const SynthesisOptions o = options(seed);
  if (!all_maps) return synthesize_tiles(exemplar_from_image(h.albedo, h.name, true), o);
  SynthesisOptions with = o;
  const char* w = std::getenv("TILEKIT_ALBEDO_WEIGHT");  // --albedo-weight
  with.colour_weight = w ? std::atof(w) : kAlbedoWeight;
  with.cost_maps = seam_cost_maps(maps);
  return synthesize_tiles(exemplar_from_image(h.albedo, h.name, true), with);
}

// The window lit through its normal map; by default the light from the upper left, 50 degrees up.
constexpr std::array<double, 3> kLight{0.45, -0.45, 0.77};
Image lit(const Image& albedo, const Image& normals, const std::array<double, 3>& l = kLight) {
  const double ll = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
  Image out(albedo.width, albedo.height);
  for (int y = 0; y < albedo.height; ++y)
    for (int x = 0; x < albedo.width; ++x) {
      double n[3], dot = 0;
      for (int c = 0; c < 3; ++c)
        n[c] = 2.0 * normals.sample(x, y, c) / normals.max_value() - 1, dot += n[c] * l[c] / ll;
      const double shade = 0.15 + 0.85 * std::max(0.0, dot);
      std::uint8_t* p = out.at(x, y);
      for (int c = 0; c < 3; ++c)
        p[c] = std::uint8_t(
            std::lround(linear_to_srgb(std::min(1.0, srgb_to_linear(albedo.at(x, y)[c] / 255.0) * shade)) * 255));
    }
  return out;
}

// How often the all-map run's cut ratio is lower than the albedo-only run's: per texture (the
// means over seeds) and per pair (one seed).
struct Tally {
  int textures = 0, lit_mean_lower = 0, ring_mean_lower = 0, shading_mean_lower = 0, pairs = 0, lit_pairs_lower = 0;
  Tally& operator+=(const Tally& o) {
    textures += o.textures, lit_mean_lower += o.lit_mean_lower, ring_mean_lower += o.ring_mean_lower;
    shading_mean_lower += o.shading_mean_lower, pairs += o.pairs, lit_pairs_lower += o.lit_pairs_lower;
    return *this;
  }
};

Tally seams(const std::string& name, int seeds) {
  Tally tally;
  tally.textures = 1;
  double albedo_lit = 0;
  const HeldOut h = held_out(name);
  const Tiling window = DirectCornerTiling(4, HashKind::LongPeriod, 1).generate(16, 16);
  std::map<std::string, std::array<double, 2>> sums;  // per figure: albedo-only, all-map
  for (int seed = 1; seed <= seeds; ++seed)
    for (const bool all : {false, true}) {
      TextureTileSet s = synthesize(h, all, h.maps, std::uint64_t(seed));
      const Image albedo = map_as_sampled(h.albedo, true, s.perspective, s.exemplar_scale);
      s.tiles = transfer_tiles(s.coords, s.tile_px, albedo);
      TextureTileSet normal_set = s;
      normal_set.tiles =
          transfer_tiles(s.coords, s.tile_px, map_as_sampled(h.maps[0].image, true, s.perspective, s.exemplar_scale));
      std::vector<std::uint32_t> sources;
      const Image colour = stitch_tiles(s, window, &sources);
      const Image normals = stitch_tiles(normal_set, window);
      const Image render = lit(colour, normals);
      const Image shading = lit(Image(colour.width, colour.height, Rgb{188, 188, 188}), normals);
      const SeamStatistics r = seam_statistics(render, s.tile_px, &sources);
      const SeamStatistics nm = seam_statistics(normals, s.tile_px, &sources);
      const SeamStatistics al = seam_statistics(colour, s.tile_px, &sources);
      const SeamStatistics sh = seam_statistics(shading, s.tile_px, &sources);
      double ring = 0;  // the same light from 8 azimuths
      const double up = kLight[2], out = std::hypot(kLight[0], kLight[1]);
      for (int k = 0; k < 8; ++k) {
        const double phi = std::atan2(kLight[1], kLight[0]) + k * std::numbers::pi / 4;
        ring +=
            seam_statistics(lit(colour, normals, {out * std::cos(phi), out * std::sin(phi), up}), s.tile_px, &sources)
                .cut_ratio /
            8;
      }
      const std::size_t side = all ? 1 : 0;
      if (!all)
        albedo_lit = r.cut_ratio;
      else
        tally.pairs += 1, tally.lit_pairs_lower += r.cut_ratio < albedo_lit;
      for (const auto& [key, v] : {std::pair<const char*, double>{"cut_ratio", r.cut_ratio},
                                   {"ring_cut_ratio", ring},
                                   {"shading_cut_ratio", sh.cut_ratio},
                                   {"normal_cut_ratio", nm.cut_ratio},
                                   {"albedo_cut_ratio", al.cut_ratio}})
        sums[key][side] += v / seeds;
      print({{"case", fmt::format("material-seams/{}/{}", name, all ? "all" : "albedo")},
             {"seed", seed},
             {"maps", h.maps.size() + 1},
             {"cut_ratio", r.cut_ratio},
             {"cut_step", r.cut_step},
             {"same_source_step", r.same_source_step},
             {"cut_pairs", r.cut_pairs},
             {"ring_cut_ratio", ring},
             {"shading_cut_ratio", sh.cut_ratio},
             {"seam_ratio", r.seam_ratio},
             {"normal_cut_ratio", nm.cut_ratio},
             {"albedo_cut_ratio", al.cut_ratio},
             {"cut_error", s.cut_error},
             {"period", {s.period.x, s.period.y}},
             {"thin_bands", s.thin_bands},
             {"shared_fraction", s.shared_fraction},
             {"window_tiles", "16x16"}});
      const char* dir = std::getenv("TILEKIT_BENCH_PICTURES");  // 256x256 crops of seed 1: lit, and the shading
      if (dir && seed == 1)
        for (const auto& [what, img] : {std::pair<const char*, const Image*>{"lit", &render}, {"shading", &shading}}) {
          Image crop(256, 256);
          for (int y = 0; y < 256; ++y) std::copy_n(img->at(0, y), 256 * 4, crop.at(0, y));
          write_png(fmt::format("{}/material-{}-{}-{}.png", dir, name, what, all ? "all" : "albedo"), crop);
        }
    }
  nlohmann::json mean = {{"case", fmt::format("material-seams-mean/{}", name)}, {"seeds", seeds}};
  for (const auto& [key, v] : sums) mean[key] = {{"albedo", v[0]}, {"all", v[1]}, {"change", v[1] / v[0] - 1}};
  print(mean);
  tally.lit_mean_lower = sums["cut_ratio"][1] < sums["cut_ratio"][0];
  tally.ring_mean_lower = sums["ring_cut_ratio"][1] < sums["ring_cut_ratio"][0];
  tally.shading_mean_lower = sums["shading_cut_ratio"][1] < sums["shading_cut_ratio"][0];
  return tally;
}

void speed(const std::string& name, int reps) {
  HeldOut h = held_out(name);
  // A four-map material: albedo, normal, specular and height (the normal map's alpha where it
  // holds one, else the albedo's luminance).
  std::vector<MaterialMap> maps = h.maps;
  MaterialMap height;
  height.name = "height", height.space = ColourSpace::Linear;
  height.image = Image(h.albedo.width, h.albedo.height);
  bool alpha = false;
  for (int y = 0; y < h.albedo.height; ++y)
    for (int x = 0; x < h.albedo.width; ++x) alpha = alpha || h.maps[0].image.at(x, y)[3] != 255;
  for (int y = 0; y < h.albedo.height; ++y)
    for (int x = 0; x < h.albedo.width; ++x) {
      const std::uint8_t v = alpha ? h.maps[0].image.at(x, y)[3] : std::uint8_t(luma(h.albedo.at(x, y)) + 0.5f);
      height.image.set(x, y, {v, v, v});
    }
  maps.push_back(height);
  while (maps.size() < 3) maps.push_back(height);  // no specular map: height twice, still four maps
  std::vector<double> one, four;
  for (int r = 0; r < reps; ++r) {
    one.push_back(bench::seconds_of([&] {
      SynthesisOptions o = options();
      o.record_coords = false;
      const TextureTileSet s = synthesize_tiles(exemplar_from_image(h.albedo, h.name, true), o);
      if (s.tiles.empty()) std::abort();
    }));
    four.push_back(bench::seconds_of([&] {
      TextureTileSet s = synthesize(h, true, maps);
      s.tiles = transfer_tiles(s.coords, s.tile_px, map_as_sampled(h.albedo, true, s.perspective, s.exemplar_scale));
      for (const MaterialMap& m : maps)
        if (transfer_tiles(s.coords, s.tile_px, map_as_sampled(m.image, true, s.perspective, s.exemplar_scale)).empty())
          std::abort();
    }));
  }
  const double a = bench::median_midpoint(one), b = bench::median_midpoint(four);
  print({{"case", fmt::format("material-speed/{}", name)},
         {"maps", maps.size() + 1},
         {"albedo_seconds", a},
         {"material_seconds", b},
         {"ratio", b / a},
         {"reps", reps},
         {"goal", "ratio <= 2"}});
}

}  // namespace

int main(int argc, char** argv) {
  int reps = 3, seeds = 3;
  std::string only;
  std::vector<std::string> names{"ufo-brick", "ufo-tile", "ufo-wood", "ufo-concrete", "ufo-dirt", "ufo-mud"};
  for (const char* r : {"brick1", "brick2", "concrete1", "concrete2a", "concrete4", "concrete5", "concrete6", "paint",
                        "painted2", "plaster1", "plaster3", "rust1", "rust2", "tile1", "tile2", "tile3", "wood1"})
    names.push_back(std::string("re-") + r);
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--reps") && i + 1 < argc)
      reps = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--seeds") && i + 1 < argc)
      seeds = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--only") && i + 1 < argc)
      only = argv[++i];
    else if (!std::strcmp(argv[i], "--textures") && i + 1 < argc) {
      names.clear();
      for (std::string list = argv[++i]; !list.empty();) {
        const std::size_t comma = list.find(',');
        names.push_back(list.substr(0, comma));
        list = comma == std::string::npos ? "" : list.substr(comma + 1);
      }
    }
  }
  const auto want = [&](const std::string& c) { return only.empty() || c.rfind(only, 0) == 0; };
  std::map<std::string, Tally> sets;  // per set (the name up to its first '-'): how often all-map is lower
  for (const std::string& name : names)
    if (want("material-seams/" + name)) sets[name.substr(0, name.find('-'))] += seams(name, seeds);
  for (const auto& [set, t] : sets)
    print({{"case", "material-seams-tally/" + set},
           {"textures", t.textures},
           {"lit_mean_lower", t.lit_mean_lower},
           {"ring_mean_lower", t.ring_mean_lower},
           {"shading_mean_lower", t.shading_mean_lower},
           {"pairs", t.pairs},
           {"lit_pairs_lower", t.lit_pairs_lower}});
  for (const std::string name : {"ufo-concrete", "ufo-dirt"})
    if (want("material-speed/" + name)) speed(name, reps);
}
