#pragma once
// The headless GLSL renderer: the sampler of glsl_sampler.hpp drawn into an offscreen
// framebuffer through EGL on Mesa's surfaceless platform (EGL_MESA_platform_surfaceless), so
// no X server and no GPU are needed: Mesa's llvmpipe runs the shader on the CPU (set
// LP_NUM_THREADS to choose its threads). Where no EGL display or OpenGL ES 3 context can be
// made, every entry point throws GlUnavailable (an InputError: exit 2) saying why.
#include <memory>
#include <string>

#include "base/error.hpp"
#include "render/cpu_renderer.hpp"
#include "render/glsl_sampler.hpp"

namespace tilekit {

struct GlUnavailable : InputError {
  using InputError::InputError;
};

// The GL_RENDERER and GL_VERSION strings of a context, or GlUnavailable.
std::string gl_renderer_name();

class GlRenderer {
 public:
  // Compiles the shader for `mode` and uploads the textures (the atlas or the exemplar surface,
  // all levels, and hpn's look-up table), the hash tables and the view's row table. Tiles in
  // mode Texture over a view with one footprint everywhere (uniform_footprint: flat) draw with
  // FlatTexture, the same pixels with the level of detail a uniform.
  GlRenderer(const RenderSource& source, const View& view, const RenderOptions& o, GlslMode mode = GlslMode::Texture);
  GlRenderer(const TextureAtlas& atlas, const View& view, const RenderOptions& o, GlslMode mode = GlslMode::Texture)
      : GlRenderer(RenderSource{RenderMethod::Tiles, &atlas, nullptr}, view, o, mode) {}
  ~GlRenderer();
  GlRenderer(const GlRenderer&) = delete;
  GlRenderer& operator=(const GlRenderer&) = delete;

  // A bare program: `fragment_shader` over a width x height framebuffer (run_fragment_shader).
  GlRenderer(const std::string& fragment_shader, int width, int height);

  void set_origin(int x, int y);  // tk_origin of the test modes
  // Draws `frames` times and waits for the GPU (glFinish); returns the seconds that took.
  double draw(int frames = 1);
  Image read();  // the framebuffer, row 0 at the top
  std::string renderer() const;
  GlslMode mode() const;  // the shader drawn (FlatTexture where Texture was asked for a flat view of tiles)

 private:
  struct State;
  std::unique_ptr<State> s_;
};

Image render_glsl(const RenderSource& source, const View& view, const RenderOptions& o);
inline Image render_glsl(const TextureAtlas& atlas, const View& view, const RenderOptions& o) {
  return render_glsl(RenderSource{RenderMethod::Tiles, &atlas, nullptr}, view, o);
}

// Compiles `fragment_shader` (with glsl_vertex_shader) and draws it once into a width x height
// framebuffer: for tests of generated GLSL that is not a renderer's (the atlas lookup snippet).
Image run_fragment_shader(const std::string& fragment_shader, int width, int height);

}  // namespace tilekit
