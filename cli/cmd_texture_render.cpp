// tilekit texture render: a window of the infinite textured plane, by tiles (an atlas laid out by a
// packing, thesis 5.4) or by a baseline that samples the exemplar directly (hex tiling, histogram-
// preserving blending), on the CPU or through GLSL (headless EGL, Mesa llvmpipe).
#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <memory>

#include "base/error.hpp"
#include "base/parallel.hpp"
#include "cli/cmd_texture.hpp"
#include "render/anisotropic.hpp"
#include "render/gl_renderer.hpp"
#include "texture/exemplar.hpp"

namespace tilekit::cli {

namespace {

struct RenderArgs {
  SourceArgs source;
  std::string size = "1024x1024", origin, out;
  double scale = 1, tilt = 0;
  int threads = 0, frames = 1;
  bool glsl = false, compare = false, quiet = false;
};

struct Difference {
  int max = 0;
  double mean = 0;
};

Difference difference(const Image& a, const Image& b) {
  Difference d;
  double sum = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const int v = std::abs(int(a.pixels[i]) - int(b.pixels[i]));
    d.max = std::max(d.max, v);
    sum += v;
  }
  d.mean = a.pixels.empty() ? 0 : sum / double(a.pixels.size());
  return d;
}

double seconds_of(const std::function<void()>& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// --glsl or --compare: the GLSL sampler's image, with its timings in `j` and, with --compare,
// its difference from the CPU reference `cpu`. No EGL: one line on stderr and exit 2.
Image render_glsl(const RenderArgs& a, const RenderSource& src, const View& view, const RenderOptions& o,
                  const Image& cpu, nlohmann::json& j) {
  Image img;
  try {
    GlRenderer r(src, view, o);
    double s = r.draw(1);
    if (a.frames > 1) {  // the first draw compiled the shader's variant: time the others
      s = r.draw(a.frames) / a.frames;
      j["glsl_mfragments_per_second"] = double(view.width) * view.height / s / 1e6;
    }
    img = r.read();
    j["gl_renderer"] = r.renderer();
    j["glsl_seconds"] = s;
  } catch (const GlUnavailable& e) {
    std::cerr << "tilekit: texture render --glsl skipped: " << e.what() << std::endl;
    throw Exit{2};
  }
  if (a.compare) {
    const Difference d = difference(cpu, img);
    j["max_difference"] = d.max;
    j["mean_difference"] = d.mean;
  }
  return img;
}

void print_render(const RenderArgs& a, const RenderSource& src, const View& view, const RenderOptions& o,
                  const nlohmann::json& j) {
  fmt::print("{}: {}x{} window ({} method, scale {}, tilt {}, anisotropy {}x), {} renderer{}\n", a.out, view.width,
             view.height, render_method_name(src.method), view.scale, view.tilt, o.max_aniso,
             j["renderer"].get<std::string>(),
             j.contains("gl_renderer") ? " on " + j["gl_renderer"].get<std::string>() : "");
  fmt::print("{:.2f} texture fetches per pixel, {:.1f} MiB of texture memory\n", j["fetches_per_pixel"].get<double>(),
             double(src.memory_bytes()) / (1 << 20));
  if (j.contains("cpu_seconds"))
    fmt::print("CPU reference: {:.3f} s, {:.1f} Mpixel/s on {} threads\n", j["cpu_seconds"].get<double>(),
               j["cpu_mpixels_per_second"].get<double>(), o.threads);
  if (a.compare)
    fmt::print("GLSL vs CPU: largest difference {}/255, mean {:.4f}/255\n", j["max_difference"].get<int>(),
               j["mean_difference"].get<double>());
}

void run_render(const RenderArgs& a, const Context& ctx) {
  View view = parse_view(a.size, a.scale, a.origin, a.tilt);
  const std::unique_ptr<LoadedSource> loaded = load_source(a.source);
  const RenderSource& src = loaded->source;
  RenderOptions o = loaded->options;
  o.threads = resolve_threads(a.threads);
  o.progress = !a.quiet;
  view_rows(view, src.unit_px());  // bad views are exit 2 before anything runs
  if ((a.glsl || a.compare) && !std::getenv("LP_NUM_THREADS"))
    setenv("LP_NUM_THREADS", std::to_string(o.threads).c_str(), 1);  // llvmpipe reads it when the context is made
  nlohmann::json j = source_json(*loaded);
  j.update({{"out", a.out},
            {"width", view.width},
            {"height", view.height},
            {"scale", view.scale},
            {"tilt", view.tilt},
            {"origin", {view.origin_u, view.origin_v}},
            {"threads", o.threads},
            {"fetches_per_pixel", mean_fetches(src, view, o.max_aniso)}});
  Image img, cpu;
  if (!a.glsl || a.compare) {
    const double s = seconds_of([&] { cpu = render_cpu(src, view, o); });
    j["cpu_seconds"] = s;
    j["cpu_mpixels_per_second"] = double(view.width) * view.height / s / 1e6;
    img = cpu;
  }
  if (a.glsl || a.compare) img = render_glsl(a, src, view, o, cpu, j);
  j["renderer"] = a.glsl || a.compare ? "glsl" : "cpu";
  write_png(a.out, img);
  emit(ctx, j, [&] {
    if (!a.quiet) print_render(a, src, view, o, j);
  });
}

}  // namespace

void add_texture_render(CLI::App& texture, Context& ctx) {
  auto* cmd = texture.add_subcommand(
      "render", "Render a window of the infinite texture: tiles (atlas), or the hex / hpn baselines (exemplar)");
  auto a = std::make_shared<RenderArgs>();
  add_source_options(cmd, a->source);
  cmd->add_option("--size", a->size, "Window in pixels, WxH")->capture_default_str();
  cmd->add_option("--scale", a->scale, "Texels of the virtual texture per pixel (at the bottom, when tilted)")
      ->capture_default_str();
  cmd->add_option("--origin", a->origin, "Texel of the virtual texture at the window's top-left, U,V (default 0,0)");
  cmd->add_option("--tilt", a->tilt, "Perspective: rows at the top are (1+T)^2 times farther (0: flat)")
      ->capture_default_str();
  cmd->add_option("--threads", a->threads,
                  "CPU renderer threads, and llvmpipe's unless LP_NUM_THREADS is set (default: every core)");
  cmd->add_option("--out", a->out, "Image to write (PNG)")->required();
  cmd->add_flag("--glsl", a->glsl, "Render with the GLSL sampler through EGL (surfaceless Mesa, llvmpipe)");
  cmd->add_option("--frames", a->frames, "GLSL: draw this many frames after a first one and report the mean time")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_flag("--compare", a->compare, "Render both ways, write the GLSL image, report the largest difference");
  cmd->add_flag("--quiet", a->quiet, "No progress output on stderr and no summary on stdout");
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_render(*a, ctx); });
}

}  // namespace tilekit::cli
