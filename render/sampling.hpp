#pragma once
// OpenGL's texture filtering on the CPU (OpenGL ES 3.0 sec. 3.8.10-3.8.11), what the CPU
// renderers sample with and what the GPU's textureLod does: GL_LINEAR with GL_REPEAT within a
// level, GL_LINEAR_MIPMAP_LINEAR between levels (magnification, lambda <= 0, is level 0).
#include <array>
#include <vector>

#include "image/image.hpp"
#include "render/exemplar_surface.hpp"

namespace tilekit {

// At texture coordinate (s, t) (1 = the level's width and height; any real, wrapped) and level of
// detail lambda. RGBA8 levels give components 0..255, float levels their own values.
std::array<float, 4> sample_trilinear(const std::vector<Image>& levels, float s, float t, float lambda);
std::array<float, 4> sample_trilinear(const std::vector<FloatImage>& levels, float s, float t, float lambda);
// The same for RGBA8 levels uploaded as SRGB8_ALPHA8: R, G and B decoded to linear light before
// filtering (x 255), alpha as it is.
std::array<float, 4> sample_trilinear_srgb(const std::vector<Image>& levels, float s, float t, float lambda);
// Linear light (x 255) back to sRGB (x 255), as a render into an sRGB framebuffer (or the
// shader's tk_srgb_encode) stores it.
float srgb_encode_255(float linear_255);
// GL_LINEAR with GL_CLAMP_TO_EDGE on one float image (a look-up table).
std::array<float, 4> sample_bilinear_clamped(const FloatImage& img, float s, float t);

}  // namespace tilekit
