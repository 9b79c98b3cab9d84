#include "render/gl_renderer.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cstring>
#include <stdexcept>
#include <type_traits>

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
  // Every call of a renderer makes its own context current: with two renderers alive (a
  // benchmark and its baseline), GL calls would otherwise go to the context made last.
  void make_current() const { eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context); }
};

}  // namespace

struct GlRenderer::State {
  Context ctx;
  int width = 0, height = 0;
  GLuint program = 0, fbo = 0, colour = 0, vao = 0;
  GlslMode mode = GlslMode::Texture;  // as drawn
  // the atlas or the exemplar, the row table, hpn's look-up table, the tiling's tables (units 3,
  // 4), FlatTexture's tiles of the view
  GLuint textures[6] = {0, 0, 0, 0, 0, 0};
  ~State() {
    glDeleteProgram(program);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(1, &colour);
    glDeleteTextures(6, textures);
    glDeleteVertexArrays(1, &vao);
  }
};

namespace {

GLuint link(const std::string& fragment_shader) {
  GLuint vs = compile(GL_VERTEX_SHADER, glsl_vertex_shader());
  GLuint fs = compile(GL_FRAGMENT_SHADER, fragment_shader);
  GLuint program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint linked = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &linked);
  if (!linked) {
    char log[4096] = {0};
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    throw std::logic_error(fmt::format("GLSL link error: {}", log));
  }
  glUseProgram(program);
  return program;
}

// An offscreen RGBA8 framebuffer of the given size, bound, with the viewport on it.
void offscreen(GLuint& colour, GLuint& fbo, GLuint& vao, int width, int height) {
  glGenRenderbuffers(1, &colour);
  glBindRenderbuffer(GL_RENDERBUFFER, colour);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glGenFramebuffers(1, &fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw GlUnavailable("OpenGL ES: the offscreen framebuffer is incomplete");
  glGenVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glViewport(0, 0, width, height);
  if (GLenum e = glGetError(); e != GL_NO_ERROR)
    throw std::logic_error(fmt::format("OpenGL ES error 0x{:04x} in set-up", e));
}

template <class Level>
void upload_chain(GLuint& texture, int unit, const std::vector<Level>& levels, GLenum internal, GLenum type) {
  glGenTextures(1, &texture);
  glActiveTexture(GLenum(GL_TEXTURE0 + unit));
  glBindTexture(GL_TEXTURE_2D, texture);
  for (std::size_t k = 0; k < levels.size(); ++k) {
    if constexpr (std::is_same_v<Level, Image>) {
      glTexImage2D(GL_TEXTURE_2D, GLint(k), GLint(internal), levels[k].width, levels[k].height, 0, GL_RGBA, type,
                   levels[k].pixels.data());
    } else {  // float texels as the half floats they already are (exemplar_surface.hpp)
      std::vector<std::uint16_t> half(levels[k].texels.size());
      for (std::size_t i = 0; i < half.size(); ++i) half[i] = float_to_half(levels[k].texels[i]);
      glTexImage2D(GL_TEXTURE_2D, GLint(k), GLint(internal), levels[k].width, levels[k].height, 0, GL_RGBA, type,
                   half.data());
    }
  }
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, GLint(levels.size() - 1));
  const bool mipmapped = levels.size() > 1;
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, mipmapped ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  const GLint wrap = mipmapped ? GL_REPEAT : GL_CLAMP_TO_EDGE;  // the look-up table clamps
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap);
}

// The hardware filter's anisotropy on the bound texture (EXT_texture_filter_anisotropic; without
// the extension the hardware filters isotropically and says so).
void set_max_anisotropy(int max_aniso) {
  const char* ext = reinterpret_cast<const char*>(glGetString(GL_EXTENSIONS));
  if (!ext || !std::strstr(ext, "GL_EXT_texture_filter_anisotropic")) {
    if (max_aniso > 1) throw GlUnavailable("this OpenGL ES has no GL_EXT_texture_filter_anisotropic");
    return;
  }
  constexpr GLenum kMaxAnisotropyExt = 0x84FE;  // GL_TEXTURE_MAX_ANISOTROPY_EXT
  glTexParameterf(GL_TEXTURE_2D, kMaxAnisotropyExt, float(max_aniso));
}

}  // namespace

GlRenderer::GlRenderer(const RenderSource& src, const View& view, const RenderOptions& o, GlslMode mode)
    : s_(std::make_unique<State>()) {
  const ViewRows vr = view_rows(view, src.unit_px());
  State& s = *s_;
  s.width = view.width;
  s.height = view.height;
  GLint max_size = 0, max_vectors = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  glGetIntegerv(GL_MAX_FRAGMENT_UNIFORM_VECTORS, &max_vectors);
  const int texture_width = src.method == RenderMethod::Tiles ? src.atlas->levels[0].width : src.exemplar->width;
  if (texture_width > max_size || view.width > max_size || view.height > max_size)
    throw InputError(fmt::format("the texture ({} wide) or the window ({}x{}) exceeds GL_MAX_TEXTURE_SIZE {}",
                                 texture_width, view.width, view.height, max_size));
  const auto tables = glsl_table_uniforms(src, o);
  std::size_t vectors = 0;
  for (const auto& t : tables) vectors += t.second.size() / 4;
  if (vectors + 16 > std::size_t(max_vectors))
    throw InputError(
        fmt::format("the hash tables need {} uniform vectors, more than this GPU's {}", vectors, max_vectors));
  // a view of tiles with one footprint everywhere: its level of detail and its tiles' cells given
  Footprint flat;
  std::optional<GlslTileWindow> window;
  if (mode == GlslMode::Texture && src.method == RenderMethod::Tiles &&
      uniform_footprint(vr, src.texels_per_unit(), o.max_aniso, &flat) &&
      (window = glsl_tile_window(*src.atlas, vr, view.width, o)))
    mode = GlslMode::FlatTexture;
  s.mode = mode;
  s.program = link(glsl_fragment_shader(src, o, mode));
  // The textures exactly as the CPU renderer samples them.
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  const char* main_sampler = "tk_exemplar";
  if (src.method == RenderMethod::Tiles) {
    // An sRGB atlas as SRGB8_ALPHA8: filtered in linear light (the shader encodes the result).
    upload_chain(s.textures[0], 0, atlas_levels_8bit(*src.atlas),
                 src.atlas->colour_space == ColourSpace::Srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, GL_UNSIGNED_BYTE);
    main_sampler = "tk_atlas";
    if (o.hardware_filter) set_max_anisotropy(o.max_aniso);
  } else if (src.method == RenderMethod::Hex) {
    upload_chain(s.textures[0], 0, src.exemplar->levels, GL_RGBA8, GL_UNSIGNED_BYTE);
  } else {
    upload_chain(s.textures[0], 0, src.exemplar->gaussian, GL_RGBA16F, GL_HALF_FLOAT);
    upload_chain(s.textures[2], 2, std::vector<FloatImage>{src.exemplar->lut}, GL_RGBA16F, GL_HALF_FLOAT);
    glUniform1i(glGetUniformLocation(s.program, "tk_lut"), 2);
  }
  glUniform1i(glGetUniformLocation(s.program, main_sampler), 0);
  for (const auto& [name, values] : tables)
    glUniform4iv(glGetUniformLocation(s.program, name.c_str()), GLsizei(values.size() / 4), values.data());
  for (const GlslTableTexture& t : glsl_table_textures(src, o)) {
    GLuint& texture = s.textures[t.unit];
    glGenTextures(1, &texture);
    glActiveTexture(GLenum(GL_TEXTURE0 + t.unit));
    glBindTexture(GL_TEXTURE_2D, texture);
    const bool rg = t.channels == 2;
    glTexImage2D(GL_TEXTURE_2D, 0, rg ? GL_RG8UI : GL_RGBA8UI, t.width, t.height, 0,
                 rg ? GL_RG_INTEGER : GL_RGBA_INTEGER, GL_UNSIGNED_BYTE, t.texels.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glUniform1i(glGetUniformLocation(s.program, t.sampler.c_str()), t.unit);
  }
  // The view's row table (render/view.hpp), two RGBA32I texels per row.
  std::vector<GLint> table;
  for (const ViewRow& r : vr.rows) {
    GLint bits[3];
    std::memcpy(&bits[0], &r.dudx, 4);
    std::memcpy(&bits[1], &r.dvdy, 4);
    std::memcpy(&bits[2], &r.dudy0, 4);
    table.insert(table.end(),
                 {r.tile_u0, GLint(r.frac_u0), GLint(r.step_u), r.tile_v, GLint(r.frac_v), bits[0], bits[1], bits[2]});
  }
  glGenTextures(1, &s.textures[1]);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, s.textures[1]);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32I, 2, view.height, 0, GL_RGBA_INTEGER, GL_INT, table.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glUniform1i(glGetUniformLocation(s.program, "tk_rows"), 1);
  glUniform1f(glGetUniformLocation(s.program, "tk_dudy_step"), vr.dudy_step);
  glUniform1i(glGetUniformLocation(s.program, "tk_height"), view.height);
  glUniform1i(glGetUniformLocation(s.program, "tk_max_aniso"), o.max_aniso);
  glUniform2i(glGetUniformLocation(s.program, "tk_origin"), 0, 0);
  if (mode == GlslMode::FlatTexture) {
    glUniform1f(glGetUniformLocation(s.program, "tk_lod"), flat.lod);
    glGenTextures(1, &s.textures[5]);
    glActiveTexture(GL_TEXTURE5);
    glBindTexture(GL_TEXTURE_2D, s.textures[5]);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RG16UI, window->cols, window->rows, 0, GL_RG_INTEGER, GL_UNSIGNED_SHORT,
                 window->cells.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glUniform1i(glGetUniformLocation(s.program, "tk_window"), 5);
    glUniform2i(glGetUniformLocation(s.program, "tk_window0"), window->u0, window->v0);
  }
  offscreen(s.colour, s.fbo, s.vao, view.width, view.height);
}

GlRenderer::GlRenderer(const std::string& fragment_shader, int width, int height) : s_(std::make_unique<State>()) {
  s_->width = width;
  s_->height = height;
  s_->program = link(fragment_shader);
  offscreen(s_->colour, s_->fbo, s_->vao, width, height);
}

GlRenderer::~GlRenderer() = default;

void GlRenderer::set_origin(int x, int y) {
  s_->ctx.make_current();
  glUniform2i(glGetUniformLocation(s_->program, "tk_origin"), x, y);
}

double GlRenderer::draw(int frames) {
  s_->ctx.make_current();
  const auto t0 = std::chrono::steady_clock::now();
  for (int f = 0; f < frames; ++f) glDrawArrays(GL_TRIANGLES, 0, 3);
  glFinish();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Image GlRenderer::read() {
  s_->ctx.make_current();
  Image img{s_->width, s_->height, std::vector<std::uint8_t>(std::size_t(s_->width) * std::size_t(s_->height) * 4)};
  std::vector<std::uint8_t> flipped(img.pixels.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, s_->width, s_->height, GL_RGBA, GL_UNSIGNED_BYTE, flipped.data());
  const std::size_t row = std::size_t(s_->width) * 4;
  for (int y = 0; y < s_->height; ++y)  // GL's row 0 is the bottom
    std::copy_n(&flipped[std::size_t(s_->height - 1 - y) * row], row, img.at(0, y));
  return img;
}

GlslMode GlRenderer::mode() const {
  return s_->mode;
}

std::string GlRenderer::renderer() const {
  s_->ctx.make_current();
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
GlRenderer::GlRenderer(const RenderSource&, const View&, const RenderOptions&, GlslMode) {
  unavailable();
}
GlRenderer::GlRenderer(const std::string&, int, int) {
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
GlslMode GlRenderer::mode() const {
  unavailable();
}
std::string GlRenderer::renderer() const {
  unavailable();
}
std::string gl_renderer_name() {
  unavailable();
}

#endif

Image render_glsl(const RenderSource& source, const View& view, const RenderOptions& o) {
  GlRenderer r(source, view, o);
  r.draw(1);
  return r.read();
}

Image run_fragment_shader(const std::string& fragment_shader, int width, int height) {
  GlRenderer r(fragment_shader, width, height);
  r.draw(1);
  return r.read();
}

}  // namespace tilekit
