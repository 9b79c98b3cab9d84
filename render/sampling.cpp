#include "render/sampling.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "texture/mipmap.hpp"

namespace tilekit {

namespace {

int wrap(long i, int n) {
  return int(((i % n) + n) % n);
}
const std::uint8_t* texel(const Image& img, int x, int y) {
  return img.at(x, y);
}
const float* texel(const FloatImage& img, int x, int y) {
  return img.at(x, y);
}

// What a texel contributes: its own value, or for an sRGB texture (SRGB8_ALPHA8) its colour in
// linear light (x 255), as GL decodes it before filtering.
struct Plain {
  float operator()(std::uint8_t v, int) const { return float(v); }
  float operator()(float v, int) const { return v; }
};
struct SrgbDecode {
  float table[256];
  SrgbDecode() {
    for (int i = 0; i < 256; ++i) table[i] = float(srgb_to_linear(i / 255.0) * 255.0);
  }
  float operator()(std::uint8_t v, int c) const { return c < 3 ? table[v] : float(v); }
};

// Bilinear filtering of one level (GL_LINEAR, GL_REPEAT), accumulated into acc with weight w.
template <class Level, class Decode = Plain>
void bilinear(const Level& img, float s, float t, float w, float* acc, const Decode& d = Decode()) {
  const float u = s * float(img.width) - 0.5f, v = t * float(img.height) - 0.5f;
  const float fu = std::floor(u), fv = std::floor(v), a = u - fu, b = v - fv;
  const int i0 = wrap(long(fu), img.width), i1 = wrap(long(fu) + 1, img.width);
  const int j0 = wrap(long(fv), img.height), j1 = wrap(long(fv) + 1, img.height);
  const auto *p00 = texel(img, i0, j0), *p10 = texel(img, i1, j0), *p01 = texel(img, i0, j1), *p11 = texel(img, i1, j1);
  const float w00 = (1 - a) * (1 - b) * w, w10 = a * (1 - b) * w, w01 = (1 - a) * b * w, w11 = a * b * w;
  for (int c = 0; c < 4; ++c)
    acc[c] += w00 * d(p00[c], c) + w10 * d(p10[c], c) + w01 * d(p01[c], c) + w11 * d(p11[c], c);
}

template <class Level, class Decode = Plain>
std::array<float, 4> trilinear(const std::vector<Level>& levels, float s, float t, float lambda,
                               const Decode& d = Decode()) {
  std::array<float, 4> acc{0, 0, 0, 0};
  const int q = int(levels.size()) - 1;
  if (!(lambda > 0)) {  // magnification (c = 0 for LINEAR with LINEAR_MIPMAP_LINEAR)
    bilinear(levels[0], s, t, 1, acc.data(), d);
  } else if (lambda >= float(q)) {
    bilinear(levels[std::size_t(q)], s, t, 1, acc.data(), d);
  } else {
    const int d1 = int(std::floor(lambda));
    const float f = lambda - float(d1);
    bilinear(levels[std::size_t(d1)], s, t, 1 - f, acc.data(), d);
    bilinear(levels[std::size_t(d1 + 1)], s, t, f, acc.data(), d);
  }
  return acc;
}

const SrgbDecode kSrgbDecode;

}  // namespace

std::array<float, 4> sample_trilinear(const std::vector<Image>& levels, float s, float t, float lambda) {
  return trilinear(levels, s, t, lambda);
}

std::array<float, 4> sample_trilinear_srgb(const std::vector<Image>& levels, float s, float t, float lambda) {
  return trilinear(levels, s, t, lambda, kSrgbDecode);
}

float srgb_encode_255(float linear_255) {
  return float(linear_to_srgb(std::clamp(double(linear_255) / 255.0, 0.0, 1.0)) * 255.0);
}

std::array<float, 4> sample_trilinear(const std::vector<FloatImage>& levels, float s, float t, float lambda) {
  return trilinear(levels, s, t, lambda);
}

std::array<float, 4> sample_bilinear_clamped(const FloatImage& img, float s, float t) {
  const float u = std::clamp(s * float(img.width) - 0.5f, 0.0f, float(img.width - 1));
  const float v = std::clamp(t * float(img.height) - 0.5f, 0.0f, float(img.height - 1));
  const int i0 = int(u), j0 = int(v), i1 = std::min(i0 + 1, img.width - 1), j1 = std::min(j0 + 1, img.height - 1);
  const float a = u - float(i0), b = v - float(j0);
  std::array<float, 4> acc{};
  for (int c = 0; c < 4; ++c)
    acc[std::size_t(c)] = (1 - a) * (1 - b) * img.at(i0, j0)[c] + a * (1 - b) * img.at(i1, j0)[c] +
                          (1 - a) * b * img.at(i0, j1)[c] + a * b * img.at(i1, j1)[c];
  return acc;
}

}  // namespace tilekit
