#include "texture/gl_renderer.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cstring>
#include <stdexcept>

#if TILEKIT_HAVE_EGL
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES3/gl3.h>
#endif

namespace tilekit {

#if TILEKIT_HAVE_EGL

namespace {

std::string egl_error(const char* what) {
  return fmt::format("{} failed (EGL error 0x{:04x})", what, eglGetError());
}

GLuint compile(GLenum type, const std::string& source) {
  GLuint s = glCreateShader(type);
  const char* text = source.c_str();
  glShaderSource(s, 1, &text, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096] = {0};
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    throw std::logic_error(fmt::format("GLSL compile error: {}", log));
  }
  return s;
}

// One surfaceless EGL display and OpenGL ES 3 context, current on this thread.
struct Context {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  Context() {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!client || !std::strstr(client, "EGL_MESA_platform_surfaceless"))
      throw GlUnavailable(
          "EGL: no surfaceless platform (EGL_MESA_platform_surfaceless; install libegl-mesa0 and "
          "libgl1-mesa-dri); the GLSL render is skipped");
    auto get_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (get_display) display = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY)
      throw GlUnavailable("EGL: " + egl_error("eglGetPlatformDisplayEXT(surfaceless)") +
                          "; the GLSL render is skipped");
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor))
      throw GlUnavailable("EGL: " + egl_error("eglInitialize on the surfaceless display") +
                          "; the GLSL render is skipped");
    if (!eglBindAPI(EGL_OPENGL_ES_API)) throw GlUnavailable("EGL: " + egl_error("eglBindAPI(OpenGL ES)"));
    const EGLint config_attr[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configs = 0;
    eglChooseConfig(display, config_attr, &config, 1, &configs);
    const EGLint context_attr[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 0, EGL_NONE};
    context = eglCreateContext(display, configs ? config : EGLConfig(nullptr), EGL_NO_CONTEXT, context_attr);
    if (context == EGL_NO_CONTEXT)
      throw GlUnavailable("EGL: " + egl_error("eglCreateContext(OpenGL ES 3.0)") + "; the GLSL render is skipped");
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
      eglDestroyContext(display, context);
      throw GlUnavailable("EGL: " + egl_error("eglMakeCurrent without a surface"));
    }
  }
  ~Context() {
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display, context);
  }
};

}  // namespace

struct GlRenderer::State {
  Context ctx;
  int width = 0, height = 0;
  GLuint program = 0, fbo = 0, colour = 0, atlas = 0, rows = 0, vao = 0;
  ~State() {
    glDeleteProgram(program);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(1, &colour);
    glDeleteTextures(1, &atlas);
    glDeleteTextures(1, &rows);
    glDeleteVertexArrays(1, &vao);
  }
};

GlRenderer::GlRenderer(const TextureAtlas& a, const View& view, const RenderOptions& o, GlslMode mode)
    : s_(std::make_unique<State>()) {
  const ViewRows vr = view_rows(view, a.tile_px);
  State& s = *s_;
  s.width = view.width;
  s.height = view.height;
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  if (a.levels[0].width > max_size || view.width > max_size || view.height > max_size)
    throw InputError(fmt::format("the atlas ({}x{}) or the window ({}x{}) exceeds GL_MAX_TEXTURE_SIZE {}",
                                 a.levels[0].width, a.levels[0].height, view.width, view.height, max_size));
  const VirtualTiling tiling(a.lookup.kind, a.lookup.colours, o.hash, o.seed);
  GLuint vs = compile(GL_VERTEX_SHADER, glsl_vertex_shader());
  GLuint fs = compile(GL_FRAGMENT_SHADER, glsl_fragment_shader(a.lookup, a.tile_px, tiling, mode));
  s.program = glCreateProgram();
  glAttachShader(s.program, vs);
  glAttachShader(s.program, fs);
  glLinkProgram(s.program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint linked = 0;
  glGetProgramiv(s.program, GL_LINK_STATUS, &linked);
  if (!linked) {
    char log[4096] = {0};
    glGetProgramInfoLog(s.program, sizeof log, nullptr, log);
    throw std::logic_error(fmt::format("GLSL link error: {}", log));
  }
  glUseProgram(s.program);
  // The atlas and its mip chain exactly as the CPU renderer samples them.
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glGenTextures(1, &s.atlas);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, s.atlas);
  for (std::size_t k = 0; k < a.levels.size(); ++k)
    glTexImage2D(GL_TEXTURE_2D, GLint(k), GL_RGBA8, a.levels[k].width, a.levels[k].height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 a.levels[k].pixels.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, GLint(a.levels.size() - 1));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  glUniform1i(glGetUniformLocation(s.program, "tk_atlas"), 0);
  // The view's row table (texture/view.hpp), two RGBA32I texels per row.
  std::vector<GLint> table;
  for (const ViewRow& r : vr.rows) {
    GLint bits[3];
    std::memcpy(&bits[0], &r.dudx, 4);
    std::memcpy(&bits[1], &r.dvdy, 4);
    std::memcpy(&bits[2], &r.dudy0, 4);
    table.insert(table.end(),
                 {r.tile_u0, GLint(r.frac_u0), GLint(r.step_u), r.tile_v, GLint(r.frac_v), bits[0], bits[1], bits[2]});
  }
  glGenTextures(1, &s.rows);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, s.rows);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32I, 2, view.height, 0, GL_RGBA_INTEGER, GL_INT, table.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glUniform1i(glGetUniformLocation(s.program, "tk_rows"), 1);
  glUniform1f(glGetUniformLocation(s.program, "tk_dudy_step"), vr.dudy_step);
  glUniform1i(glGetUniformLocation(s.program, "tk_height"), view.height);
  glUniform2i(glGetUniformLocation(s.program, "tk_origin"), 0, 0);
  // Offscreen RGBA8 framebuffer.
  glGenRenderbuffers(1, &s.colour);
  glBindRenderbuffer(GL_RENDERBUFFER, s.colour);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, view.width, view.height);
  glGenFramebuffers(1, &s.fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, s.fbo);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, s.colour);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw GlUnavailable("OpenGL ES: the offscreen framebuffer is incomplete");
  glGenVertexArrays(1, &s.vao);
  glBindVertexArray(s.vao);
  glViewport(0, 0, view.width, view.height);
  if (GLenum e = glGetError(); e != GL_NO_ERROR)
    throw std::logic_error(fmt::format("OpenGL ES error 0x{:04x} in set-up", e));
}

GlRenderer::~GlRenderer() = default;

void GlRenderer::set_origin(int x, int y) {
  glUniform2i(glGetUniformLocation(s_->program, "tk_origin"), x, y);
}

double GlRenderer::draw(int frames) {
  const auto t0 = std::chrono::steady_clock::now();
  for (int f = 0; f < frames; ++f) glDrawArrays(GL_TRIANGLES, 0, 3);
  glFinish();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Image GlRenderer::read() {
  Image img{s_->width, s_->height, std::vector<std::uint8_t>(std::size_t(s_->width) * std::size_t(s_->height) * 4)};
  std::vector<std::uint8_t> flipped(img.pixels.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, s_->width, s_->height, GL_RGBA, GL_UNSIGNED_BYTE, flipped.data());
  const std::size_t row = std::size_t(s_->width) * 4;
  for (int y = 0; y < s_->height; ++y)  // GL's row 0 is the bottom
    std::copy_n(&flipped[std::size_t(s_->height - 1 - y) * row], row, img.at(0, y));
  return img;
}

std::string GlRenderer::renderer() const {
  return fmt::format("{} ({})", reinterpret_cast<const char*>(glGetString(GL_RENDERER)),
                     reinterpret_cast<const char*>(glGetString(GL_VERSION)));
}

std::string gl_renderer_name() {
  Context c;
  return fmt::format("{} ({})", reinterpret_cast<const char*>(glGetString(GL_RENDERER)),
                     reinterpret_cast<const char*>(glGetString(GL_VERSION)));
}

#else  // built without EGL

struct GlRenderer::State {};
namespace {
[[noreturn]] void unavailable() {
  throw GlUnavailable("tilekit was built without EGL/OpenGL ES (libegl-dev, libgles-dev); the GLSL render is skipped");
}
}  // namespace
GlRenderer::GlRenderer(const TextureAtlas&, const View&, const RenderOptions&, GlslMode) {
  unavailable();
}
GlRenderer::~GlRenderer() = default;
void GlRenderer::set_origin(int, int) {
  unavailable();
}
double GlRenderer::draw(int) {
  unavailable();
}
Image GlRenderer::read() {
  unavailable();
}
std::string GlRenderer::renderer() const {
  unavailable();
}
std::string gl_renderer_name() {
  unavailable();
}

#endif

Image render_glsl(const TextureAtlas& a, const View& view, const RenderOptions& o) {
  GlRenderer r(a, view, o);
  r.draw(1);
  return r.read();
}

}  // namespace tilekit
