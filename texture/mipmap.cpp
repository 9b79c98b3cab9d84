#include "texture/mipmap.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>

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

}  // namespace

Image downsample(const Image& img, MipEdge edge) {
  const int w = std::max(1, img.width / 2), h = std::max(1, img.height / 2);
  const auto tx = taps(img.width, w, edge), ty = taps(img.height, h, edge);
  // Horizontal pass into 32-bit sums (x 256), then vertical, then round (/ 65536).
  std::vector<std::int32_t> tmp(std::size_t(w) * std::size_t(img.height) * 4);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < w; ++x) {
      std::int32_t* o = &tmp[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4];
      for (const Tap& t : tx[std::size_t(x)]) {
        const std::uint8_t* p = img.at(t.source, y);
        for (int c = 0; c < 4; ++c) o[c] += t.weight * p[c];
      }
    }
  Image out{w, h, std::vector<std::uint8_t>(std::size_t(w) * std::size_t(h) * 4)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::int32_t acc[4] = {0, 0, 0, 0};
      for (const Tap& t : ty[std::size_t(y)]) {
        const std::int32_t* p = &tmp[(std::size_t(t.source) * std::size_t(w) + std::size_t(x)) * 4];
        for (int c = 0; c < 4; ++c) acc[c] += t.weight * p[c];
      }
      for (int c = 0; c < 4; ++c) out.at(x, y)[c] = std::uint8_t((acc[c] + 32768) >> 16);
    }
  return out;
}

std::vector<Image> mip_chain(const Image& level0, MipEdge edge) {
  std::vector<Image> levels{level0};
  while (levels.back().width > 1 || levels.back().height > 1) levels.push_back(downsample(levels.back(), edge));
  return levels;
}

}  // namespace tilekit
