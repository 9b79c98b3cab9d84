#include "texture/mipmap.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <vector>

namespace tilekit {

namespace {

struct Tap {
  int source;
  std::int32_t weight;  // the weights of one output texel sum to 256
};

// Tent filter from `in` texels to `out` = max(1, in / 2) texels: the output texel centred at
// (i + 0.5) r, r = in / out, weighs source texel j by max(0, 1 - |j + 0.5 - (i + 0.5) r| / r).
// For in = 2 out that is [1 3 3 1] / 8. Weights quantised to sum 256 (largest remainders).
std::vector<std::vector<Tap>> taps(int in, int out, MipEdge edge) {
  const double r = double(in) / double(out);
  std::vector<std::vector<Tap>> all(static_cast<std::size_t>(out));
  for (int i = 0; i < out; ++i) {
    const double centre = (i + 0.5) * r;
    std::vector<std::pair<int, double>> raw;
    double sum = 0;
    for (int j = int(std::floor(centre - r - 0.5)); j <= int(std::ceil(centre + r)); ++j) {
      const double wgt = std::max(0.0, 1.0 - std::abs(j + 0.5 - centre) / r);
      if (wgt <= 0) continue;
      raw.push_back({j, wgt});
      sum += wgt;
    }
    std::vector<Tap>& t = all[std::size_t(i)];
    std::vector<std::pair<double, std::size_t>> rest;
    int total = 0;
    for (std::size_t k = 0; k < raw.size(); ++k) {
      const double exact = raw[k].second / sum * 256.0;
      const int fl = int(std::floor(exact));
      int j = raw[k].first;
      j = edge == MipEdge::Wrap ? ((j % in) + in) % in : std::clamp(j, 0, in - 1);
      t.push_back({j, fl});
      total += fl;
      rest.push_back({exact - fl, k});
    }
    std::stable_sort(rest.begin(), rest.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    for (int k = 0; total < 256; ++k, ++total) ++t[rest[std::size_t(k)].second].weight;
  }
  return all;
}

// The texels as the quantities that are averaged (ColourSpace): linear light or data, times
// alpha; normals as vectors (alpha kept apart, never premultiplied into a normal). Float images
// (depth 32) hold linear values of any range: sRGB is not applied to them (OpenEXR colour is
// scene-linear), and nothing is clamped.
std::vector<double> to_work(const Image& img, ColourSpace space) {
  const int nc = img.channels;
  if (img.is_float() && space == ColourSpace::Srgb) space = ColourSpace::Linear;
  const double scale = 1.0 / img.max_value();
  std::vector<double> w(std::size_t(img.width) * std::size_t(img.height) * std::size_t(nc));
  std::size_t i = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x, i += std::size_t(nc)) {
      const double a = nc == 4 ? img.value(x, y, 3) * scale : 1.0;
      const int colour = nc == 4 ? 3 : 1;
      for (int c = 0; c < colour; ++c) {
        const double v = img.value(x, y, c) * scale;
        w[i + std::size_t(c)] = space == ColourSpace::Normal ? 2 * v - 1
                                : space == ColourSpace::Srgb ? srgb_to_linear(v) * a
                                                             : v * a;
      }
      if (nc == 4) w[i + 3] = a;
    }
  return w;
}

// Filters `work` (channels nc, in_w x in_h) to out_w x out_h with the tent taps.
std::vector<double> filter(const std::vector<double>& work, int nc, int in_w, int in_h, MipEdge edge, int& out_w,
                           int& out_h) {
  out_w = std::max(1, in_w / 2), out_h = std::max(1, in_h / 2);
  const auto tx = taps(in_w, out_w, edge), ty = taps(in_h, out_h, edge);
  const std::size_t c = std::size_t(nc);
  std::vector<double> tmp(std::size_t(out_w) * std::size_t(in_h) * c, 0.0);
  for (int y = 0; y < in_h; ++y)
    for (int x = 0; x < out_w; ++x) {
      double* o = &tmp[(std::size_t(y) * std::size_t(out_w) + std::size_t(x)) * c];
      for (const Tap& t : tx[std::size_t(x)]) {
        const double* p = &work[(std::size_t(y) * std::size_t(in_w) + std::size_t(t.source)) * c];
        for (std::size_t k = 0; k < c; ++k) o[k] += t.weight * p[k];
      }
    }
  std::vector<double> out(std::size_t(out_w) * std::size_t(out_h) * c, 0.0);
  for (int y = 0; y < out_h; ++y)
    for (int x = 0; x < out_w; ++x) {
      double* o = &out[(std::size_t(y) * std::size_t(out_w) + std::size_t(x)) * c];
      for (const Tap& t : ty[std::size_t(y)]) {
        const double* p = &tmp[(std::size_t(t.source) * std::size_t(out_w) + std::size_t(x)) * c];
        for (std::size_t k = 0; k < c; ++k) o[k] += t.weight * p[k];
      }
      for (std::size_t k = 0; k < c; ++k) o[k] /= 65536.0;
    }
  return out;
}

unsigned quantise(double v, int max) {
  return unsigned(std::lround(std::clamp(v, 0.0, 1.0) * max));
}

// v (1 = full intensity) into channel c: rounded and clamped at 8 and 16 bits, as it is in float.
void store(Image& img, int x, int y, int c, double v) {
  if (img.is_float())
    img.set_value(x, y, c, v);
  else
    img.set_sample(x, y, c, quantise(v, img.max_value()));
}

}  // namespace

std::string_view colour_space_name(ColourSpace c) {
  switch (c) {
    case ColourSpace::Srgb:
      return "srgb";
    case ColourSpace::Linear:
      return "linear";
    case ColourSpace::Normal:
      return "normal";
  }
  return "srgb";
}

bool parse_colour_space(std::string_view name, ColourSpace& out) {
  for (ColourSpace c : {ColourSpace::Srgb, ColourSpace::Linear, ColourSpace::Normal})
    if (name == colour_space_name(c)) {
      out = c;
      return true;
    }
  return false;
}

double srgb_to_linear(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

double linear_to_srgb(double v) {
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

Image downsample(const Image& img, MipEdge edge, ColourSpace space) {
  const int nc = img.channels;
  if (img.is_float() && space == ColourSpace::Srgb) space = ColourSpace::Linear;  // as to_work
  int w = 0, h = 0;
  const std::vector<double> avg = filter(to_work(img, space), nc, img.width, img.height, edge, w, h);
  Image out(w, h, std::vector<std::uint8_t>(std::size_t(w) * std::size_t(h) * std::size_t(img.texel_bytes())), nc);
  out.depth = img.depth;
  std::size_t i = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x, i += std::size_t(nc)) {
      const double* p = &avg[i];
      const double a = nc == 4 ? p[3] : 1.0;
      const int colour = nc == 4 ? 3 : 1;
      if (space == ColourSpace::Normal && colour == 3) {
        const double len = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        const double n[3] = {len > 0 ? p[0] / len : 0, len > 0 ? p[1] / len : 0, len > 0 ? p[2] / len : 1};
        for (int c = 0; c < 3; ++c) store(out, x, y, c, (n[c] + 1) / 2);
      } else {
        for (int c = 0; c < colour; ++c) {
          const double v = space == ColourSpace::Normal ? (p[c] + 1) / 2 : a > 0 ? p[c] / a : 0.0;
          store(out, x, y, c, space == ColourSpace::Srgb ? linear_to_srgb(std::clamp(v, 0.0, 1.0)) : v);
        }
      }
      if (nc == 4) store(out, x, y, 3, a);
    }
  return out;
}

std::vector<Image> mip_chain(const Image& level0, MipEdge edge, ColourSpace space) {
  std::vector<Image> levels{level0};
  while (levels.back().width > 1 || levels.back().height > 1) levels.push_back(downsample(levels.back(), edge, space));
  return levels;
}

std::vector<double> normal_lengths(const Image& normals, MipEdge edge) {
  int w = 0, h = 0;
  const std::vector<double> avg =
      filter(to_work(normals, ColourSpace::Normal), normals.channels, normals.width, normals.height, edge, w, h);
  std::vector<double> len(std::size_t(w) * std::size_t(h));
  const std::size_t nc = std::size_t(normals.channels);
  for (std::size_t i = 0; i < len.size(); ++i) {
    const double* p = &avg[i * nc];
    len[i] = nc >= 3 ? std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) : 1.0;
  }
  return len;
}

double toksvig_roughness(double r, double len) {
  len = std::clamp(len, 1e-3, 1.0);
  const double alpha2 = r * r * r * r + (1 - len) / len;
  return std::clamp(std::sqrt(std::sqrt(alpha2)), 0.0, 1.0);
}

std::vector<Image> toksvig_chain(const Image& roughness0, const std::vector<Image>& normals, MipEdge edge) {
  if (normals.empty() || normals[0].width != roughness0.width || normals[0].height != roughness0.height) return {};
  std::vector<Image> chain{roughness0};
  for (std::size_t k = 1; k < normals.size(); ++k) {
    Image r = downsample(chain.back(), edge, ColourSpace::Linear);
    const std::vector<double> len = normal_lengths(normals[k - 1], edge);
    if (r.width != normals[k].width || r.height != normals[k].height || len.size() != std::size_t(r.width) * r.height)
      return {};
    const double max = r.max_value();
    for (int y = 0; y < r.height; ++y)
      for (int x = 0; x < r.width; ++x) {
        const double l = len[std::size_t(y) * std::size_t(r.width) + std::size_t(x)];
        for (int c = 0; c < std::min(3, r.channels); ++c)
          r.set_value(x, y, c, toksvig_roughness(r.value(x, y, c) / max, l) * max);
      }
    chain.push_back(std::move(r));
  }
  return chain;
}

}  // namespace tilekit
