// Texture tiles, atlases and renderers, one JSON line per case, with a baseline timed
// in the same run. Usage: build/bench_texture [--reps R] [--quick] [--only PREFIX]
//   synthesis/*  complete corner / Wang sets from grass, one thread (goal: C=2 < 1 s, C=3 < 5 s);
//                baseline: naive tiles (copying the same pixels)
//   seams/*      seam ratio of a rendered 32x32-tile window, per texture and tile kind, for the
//                searched tiles, the first random draw (no search) and naive abutment
//   cpu-render/* Mpixel/s of the CPU renderer (tiles, hex, hpn; trilinear and 16x anisotropic), one
//                thread; baseline: plain trilinear sampling of one texture (no tiling), same pixels
//   glsl-render/* fragments/s through EGL + llvmpipe (LP_NUM_THREADS=2), the same cases; baseline:
//                one textureLod per fragment, no tiling
// --only PREFIX runs the cases whose name starts with PREFIX (e.g. glsl-render/flat).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include "atlas/lookup.hpp"
#include "base/parallel.hpp"
#include "bench/bench_common.hpp"
#include "render/cpu_renderer.hpp"
#include "render/exemplar_surface.hpp"
#include "render/gl_renderer.hpp"
#include "render/sampling.hpp"
#include "texture/seam_metrics.hpp"
#include "texture/texture_atlas.hpp"
#include "texture/tile_synthesis.hpp"

using namespace tilekit;
using tilekit::bench::median_midpoint;
using tilekit::bench::seconds_of;

namespace {

double load() {
  double l[1] = {0};
  return getloadavg(l, 1) == 1 ? l[0] : -1;
}

void print(nlohmann::json j) {
  j["bench"] = "texture";
  j["cores"] = std::thread::hardware_concurrency();
  j["load"] = load();
  fmt::print("{}\n", j.dump());
  std::fflush(stdout);
}

Exemplar texture(const std::string& name) {
  const std::string path = real_texture_path(name);
  if (path.empty()) {
    fmt::print(stderr, "bench_texture: {} not fetched: run scripts/fetch-textures.sh\n", name);
    std::exit(1);
  }
  return load_exemplar(path);
}

SynthesisOptions options(TileKind kind, std::uint32_t c, int px, int threads) {
  SynthesisOptions o;
  o.kind = kind;
  o.colours = c;
  o.tile_px = px;
  o.threads = threads;
  return o;
}

void synthesis(const Exemplar& e, int reps, bool quick) {
  for (TileKind kind : {TileKind::Corner, TileKind::Wang})
    for (std::uint32_t c : {2u, 3u}) {
      if (quick && c == 3) continue;
      const SynthesisOptions o = options(kind, c, 128, 1);
      std::vector<double> t, base;
      double cut = 0, initial = 0;
      for (int r = 0; r < reps; ++r) {
        t.push_back(seconds_of([&] {
          const TextureTileSet s = synthesize_tiles(e, o);
          cut = s.cut_error, initial = s.cut_error_initial;
        }));
        base.push_back(seconds_of([&] { naive_tiles(e, o); }));
      }
      print({{"case", fmt::format("synthesis/{}/C={}", kind_name(kind), c)},
             {"tiles", c * c * c * c},
             {"tile_px", 128},
             {"threads", 1},
             {"reps", reps},
             {"median_seconds", median_midpoint(t)},
             {"baseline_naive_seconds", median_midpoint(base)},
             {"cut_error", cut},
             {"cut_error_first_draw", initial}});
    }
}

void seams(int threads, bool quick) {
  for (const std::string name : {"brick", "grass", "gravel"}) {
    const Exemplar e = texture(name);
    for (TileKind kind : {TileKind::Corner, TileKind::Wang}) {
      const AtlasLookup lookup = atlas_lookup(kind, 2);
      const Tiling t = kind == TileKind::Corner ? DirectCornerTiling(2, HashKind::LongPeriod, 1).generate(32, 32)
                                                : DirectWangTiling(2, 2, HashKind::LongPeriod, 1).generate(32, 32);
      for (const char* method : {"searched", "no-search", "naive"}) {
        SynthesisOptions o = options(kind, 2, quick ? 64 : 128, threads);
        if (!std::strcmp(method, "no-search")) o.search = 0;
        const TextureTileSet s = std::strcmp(method, "naive") ? synthesize_tiles(e, o) : naive_tiles(e, o);
        std::vector<std::uint32_t> sources;
        const Image stitched = stitch_tiles(s, t, &sources);
        const SeamStatistics cut = seam_statistics(stitched, o.tile_px, &sources);
        double ratio = cut.seam_ratio;
        if (std::strcmp(method, "naive")) {  // the seam ratio of the rendered tiling (atlas + CPU renderer)
          const TextureAtlas atlas = build_texture_atlas(lookup, s.tiles);
          const Image img = render_cpu(atlas, View{32 * o.tile_px, 32 * o.tile_px, 1, 0, 0, 0},
                                       {HashKind::LongPeriod, 1, threads, false});
          ratio = seam_statistics(img, o.tile_px).seam_ratio;
        }
        print({{"case", fmt::format("seams/{}/{}/{}", name, kind_name(kind), method)},
               {"tile_px", o.tile_px},
               {"colors", 2},
               {"window_tiles", "32x32"},
               {"seam_ratio", ratio},
               {"cut_ratio", cut.cut_ratio},
               {"border_step", cut.border_step},
               {"interior_step", cut.interior_step},
               {"cut_error", s.cut_error},
               {"goal", "seam_ratio <= 1.10"}});
      }
    }
  }
}

// Trilinear sampling of the atlas as one plain texture (no tiling): the baseline of the renderer.
Image plain_render(const TextureAtlas& a, const View& v, int threads) {
  const ViewRows vr = view_rows(v, a.tile_px);
  Image out{v.width, v.height, std::vector<std::uint8_t>(std::size_t(v.width) * std::size_t(v.height) * 4)};
  parallel_for(v.height, threads, [&](std::int64_t j) {
    const ViewRow& r = vr.rows[std::size_t(j)];
    for (int x = 0; x < v.width; ++x) {
      const float u = float(x) / float(v.width), t = float(j) / float(v.height);
      const auto c = sample_trilinear(a.levels, u, t, view_lod(r, vr.dudy_step, x, a.tile_px));
      for (int k = 0; k < 4; ++k) out.at(x, int(j))[k] = std::uint8_t(std::lround(c[std::size_t(k)]));
    }
  });
  return out;
}

// CPU and GLSL renders of every method, trilinear (aniso 1) and anisotropic (16), flat and tilted.
// CPU baseline: plain trilinear sampling of the atlas (no tiling); GLSL baseline: one textureLod
// per fragment. "aniso_cost" is the anisotropic case's time over the trilinear case's, same view.
void renderers(const TextureAtlas& atlas, const ExemplarSurface& ex, int reps, const std::string& only) {
  const View flat{2048, 2048, 1.5, 100, 100, 0}, tilted{2048, 2048, 0.5, 0, 0, 8};
  const View cpu_flat{1024, 1024, 1.5, 100, 100, 0}, cpu_tilted{1024, 1024, 0.5, 0, 0, 8};
  const std::vector<RenderSource> sources = {
      {RenderMethod::Tiles, &atlas, nullptr}, {RenderMethod::Hex, nullptr, &ex}, {RenderMethod::Hpn, nullptr, &ex}};
  auto wanted = [&](const std::string& name) { return name.rfind(only, 0) == 0; };
  for (const auto& [vname, view] : {std::pair{"flat", cpu_flat}, std::pair{"tilted", cpu_tilted}})
    for (const RenderSource& src : sources) {
      std::map<int, double> seconds;
      for (int aniso : {1, 16}) {
        const std::string name = fmt::format("cpu-render/{}/{}/aniso-{}", vname, render_method_name(src.method), aniso);
        if (!wanted(name)) continue;
        std::vector<double> t, base;
        for (int r = 0; r < reps; ++r) {
          t.push_back(seconds_of([&] { render_cpu(src, view, {HashKind::LongPeriod, 1, 1, false, aniso}); }));
          base.push_back(seconds_of([&] { plain_render(atlas, view, 1); }));
        }
        seconds[aniso] = median_midpoint(t);
        const double px = double(view.width) * view.height;
        nlohmann::json j = {{"case", name},
                            {"threads", 1},
                            {"reps", reps},
                            {"pixels", px},
                            {"fetches_per_pixel", mean_fetches(src, view, aniso)},
                            {"median_seconds", seconds[aniso]},
                            {"mpixels_per_second", px / seconds[aniso] / 1e6},
                            {"baseline_plain_trilinear_mpixels_per_second", px / median_midpoint(base) / 1e6},
                            {"ratio_to_baseline", seconds[aniso] / median_midpoint(base)}};
        if (aniso > 1 && seconds.count(1)) j["aniso_cost"] = seconds[aniso] / seconds[1];
        print(j);
      }
    }
  const char* lp = std::getenv("LP_NUM_THREADS");
  for (const auto& [vname, view] : {std::pair{"flat", flat}, std::pair{"tilted", tilted}})
    for (const RenderSource& src : sources)
      for (HashKind h : {HashKind::LongPeriod, HashKind::Permutation}) {
        std::map<int, double> seconds;
        for (int aniso : {1, 16}) {
          const std::string name = fmt::format("glsl-render/{}/{}/{}/aniso-{}", vname, render_method_name(src.method),
                                               hash_kind_name(h), aniso);
          if (!wanted(name)) continue;
          try {
            const RenderOptions o{h, 1, 1, false, aniso};
            GlRenderer r(src, view, o), plain(atlas, view, o, GlslMode::PlainTexture);
            r.draw(1);
            plain.draw(1);  // compile and warm up
            const int frames = 3;
            std::vector<double> t, base;
            for (int k = 0; k < reps; ++k) {
              t.push_back(r.draw(frames));
              base.push_back(plain.draw(frames));
            }
            seconds[aniso] = median_midpoint(t);
            const double frags = double(view.width) * view.height * frames;
            nlohmann::json j = {{"case", name},
                                {"renderer", r.renderer()},
                                {"shader", r.mode() == GlslMode::FlatTexture ? "flat: level of detail uniform"
                                                                             : "footprint per fragment"},
                                {"lp_num_threads", lp ? lp : "unset"},
                                {"reps", reps},
                                {"frames", frames},
                                {"fetches_per_pixel", mean_fetches(src, view, aniso)},
                                {"mfragments_per_second", frags / seconds[aniso] / 1e6},
                                {"baseline_plain_texture_mfragments_per_second", frags / median_midpoint(base) / 1e6},
                                {"ratio_to_baseline", seconds[aniso] / median_midpoint(base)},
                                {"memory_bytes", src.memory_bytes()},
                                {"goal", ">= 150 M fragments/s flat on 2 cores"}};
            if (aniso > 1 && seconds.count(1)) j["aniso_cost"] = seconds[aniso] / seconds[1];
            print(j);
          } catch (const GlUnavailable& e) {
            print({{"case", "glsl-render"}, {"skipped", e.what()}});
            return;
          }
        }
      }
}

}  // namespace

int main(int argc, char** argv) {
  int reps = 3;
  bool quick = false;
  std::string only;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--reps") && i + 1 < argc) reps = std::max(1, std::atoi(argv[++i]));
    if (!std::strcmp(argv[i], "--only") && i + 1 < argc) only = argv[++i];
    if (!std::strcmp(argv[i], "--quick")) quick = true;
  }
  setenv("LP_NUM_THREADS", "2", 0);  // llvmpipe on 2 cores (the goal's setting) unless set
  const Exemplar grass = texture("grass");
  // A group runs when --only names a prefix of it or a case inside it.
  auto runs = [&](const std::string& group) { return group.rfind(only, 0) == 0 || only.rfind(group, 0) == 0; };
  if (runs("synthesis")) synthesis(grass, reps, quick);
  if (runs("seams")) seams(2, quick);
  if (!runs("cpu-render") && !runs("glsl-render")) return 0;
  SynthesisOptions o = options(TileKind::Corner, 3, 128, 2);
  const TextureAtlas atlas = build_texture_atlas(atlas_lookup(TileKind::Corner, 3), synthesize_tiles(grass, o).tiles);
  const ExemplarSurface ex = make_exemplar_surface(grass.image, grass.name);
  renderers(atlas, ex, reps, only);
  return 0;
}
