#include "texture/material.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "base/atomic_file.hpp"
#include "base/error.hpp"

namespace tilekit {

namespace fs = std::filesystem;

MaterialMap parse_material_map(const std::string& spec) {
  MaterialMap m;
  const std::size_t eq = spec.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == spec.size())
    throw InputError(fmt::format("map '{}': expected NAME=FILE[:ROLE[:WEIGHT]]", spec));
  m.name = spec.substr(0, eq);
  for (char c : m.name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'))
      throw InputError(fmt::format("map '{}': a name of letters, digits, - and _ (it names a folder)", spec));
  if (m.name == "coords") throw InputError(fmt::format("map '{}': the name coords is taken by the coordinates", spec));
  std::string rest = spec.substr(eq + 1);
  std::vector<std::string> parts;
  // FILE[:ROLE[:WEIGHT]]: the role and weight are the last fields when they parse as such, so a
  // file name with a colon still reads.
  const auto is_role = [](const std::string& r) {
    ColourSpace c;
    return parse_colour_space(r, c);
  };
  m.space = m.name == "normal" ? ColourSpace::Normal : ColourSpace::Linear;
  if (const std::size_t c1 = rest.rfind(':'); c1 != std::string::npos) {
    const std::string last = rest.substr(c1 + 1);
    const std::size_t c0 = rest.rfind(':', c1 == 0 ? std::string::npos : c1 - 1);
    char* end = nullptr;
    const double w = std::strtod(last.c_str(), &end);
    if (c0 != std::string::npos && is_role(rest.substr(c0 + 1, c1 - c0 - 1)) && !last.empty() && end && *end == 0) {
      if (!(w >= 0 && w <= 1000)) throw InputError(fmt::format("map '{}': the weight must be 0..1000", spec));
      m.weight = w;
      parse_colour_space(rest.substr(c0 + 1, c1 - c0 - 1), m.space);
      rest = rest.substr(0, c0);
    } else if (is_role(last)) {
      parse_colour_space(last, m.space);
      rest = rest.substr(0, c1);
    }
  }
  m.file = rest;
  m.image = read_image(m.file, 4, true);
  // Float (OpenEXR, float TIFF) is scene-linear data of any range: there is no sRGB float to
  // average in linear light, so the role srgb is refused rather than quietly changed.
  if (m.image.is_float() && m.space == ColourSpace::Srgb)
    throw InputError(fmt::format("map '{}': {} holds float samples, which are linear: give the role linear (or normal)",
                                 spec, m.file));
  return m;
}

namespace {

void renormalise(Image& img) {
  const double max = img.max_value();
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      double n[3], len = 0;
      for (int c = 0; c < 3; ++c) n[c] = 2 * img.value(x, y, c) / max - 1, len += n[c] * n[c];
      len = std::sqrt(len);
      if (len <= 0) continue;
      for (int c = 0; c < 3; ++c) img.set_value(x, y, c, std::clamp((n[c] / len + 1) / 2, 0.0, 1.0) * max);
    }
}

// A float map as the seam costs see it: 16 bits over its own range (min .. max of R, G, B). The
// costs count a map's steps in units of its mean step, so this changes nothing but rounding, and
// the synthesis reads 8- and 16-bit samples only.
Image cost_image(const Image& img) {
  double lo = 0, hi = 0;
  bool any = false;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < std::min(3, img.channels); ++c)
        if (const double v = img.value(x, y, c); std::isfinite(v)) {
          lo = any ? std::min(lo, v) : v, hi = any ? std::max(hi, v) : v;
          any = true;
        }
  Image out = Image(img.width, img.height, Rgb{0, 0, 0}).to_depth(16);
  const double scale = hi > lo ? 65535 / (hi - lo) : 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const double v = img.value(x, y, std::min(c, img.channels - 1));
        out.set_value(x, y, c, std::isfinite(v) ? (v - lo) * scale : 0);
      }
  return out;
}

}  // namespace

void resize_maps(std::vector<MaterialMap>& maps, int w, int h, bool torus) {
  for (MaterialMap& m : maps) {
    if (m.image.width == w && m.image.height == h) continue;
    m.image = resample_image(m.image, m.image.width, m.image.height, double(w) / m.image.width,
                             double(h) / m.image.height, torus);
    if (m.image.width != w || m.image.height != h) {  // rounding of the scale: crop or clamp to w x h
      Image fit(w, h, std::vector<std::uint8_t>(std::size_t(w) * std::size_t(h) * std::size_t(m.image.texel_bytes())),
                m.image.channels);
      fit.depth = m.image.depth;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          std::copy_n(m.image.at(std::min(x, m.image.width - 1), std::min(y, m.image.height - 1)), fit.texel_bytes(),
                      fit.at(x, y));
      m.image = std::move(fit);
    }
    if (m.space == ColourSpace::Normal) renormalise(m.image);
    m.resized = true;
  }
}

std::vector<SeamCostMap> seam_cost_maps(const std::vector<MaterialMap>& maps) {
  std::vector<SeamCostMap> out;
  for (const MaterialMap& m : maps)
    out.push_back({!m.image.is_float()              ? m.image
                   : m.space == ColourSpace::Normal ? m.image.to_depth(16)  // (n + 1) / 2 in 0..1
                                                    : cost_image(m.image),
                   m.space == ColourSpace::Normal, m.weight});
  return out;
}

Image map_as_sampled(const Image& map, bool tileable, const PerspectiveFit& perspective,
                     std::array<double, 2> exemplar_scale) {
  Image out = map;
  if (perspective.applied)
    if (Image r = rectify_image(map, perspective); r.width > 0) out = std::move(r);
  if (exemplar_scale[0] != 1 || exemplar_scale[1] != 1)
    out = resample_image(out, out.width, out.height, exemplar_scale[0], exemplar_scale[1], tileable);
  return out;
}

std::vector<Image> transfer_tiles(const std::vector<std::vector<std::uint32_t>>& coords, int tile_px,
                                  const Image& map) {
  if (coords.empty()) throw InputError("the tile set has no texel coordinates to carry a map by");
  std::vector<Image> tiles;
  tiles.reserve(coords.size());
  const std::size_t bytes = std::size_t(map.texel_bytes());
  for (const auto& c : coords) {
    Image t(tile_px, tile_px, std::vector<std::uint8_t>(std::size_t(tile_px) * std::size_t(tile_px) * bytes),
            map.channels);
    t.depth = map.depth;
    for (std::size_t i = 0; i < c.size(); ++i) {
      const int x = int(c[i] & 0xffff), y = int(c[i] >> 16);
      if (x >= map.width || y >= map.height)
        throw InputError(fmt::format("the map ({}x{}) does not reach texel ({}, {}) that the tiles copy", map.width,
                                     map.height, x, y));
      std::copy_n(map.at(x, y), bytes, t.pixels.data() + i * bytes);
    }
    tiles.push_back(std::move(t));
  }
  return tiles;
}

std::vector<Image> coordinate_tiles(const std::vector<std::vector<std::uint32_t>>& coords, int tile_px) {
  std::vector<Image> tiles;
  for (const auto& c : coords) {
    Image t = Image(tile_px, tile_px, Rgb{0, 0, 0}).to_depth(16);
    for (std::size_t i = 0; i < c.size(); ++i) {
      const int x = int(i % std::size_t(tile_px)), y = int(i / std::size_t(tile_px));
      t.set_sample(x, y, 0, c[i] & 0xffff);
      t.set_sample(x, y, 1, c[i] >> 16);
    }
    tiles.push_back(std::move(t));
  }
  return tiles;
}

std::vector<std::vector<std::uint32_t>> coords_from_tiles(const std::vector<Image>& tiles) {
  std::vector<std::vector<std::uint32_t>> coords;
  for (const Image& t : tiles) {
    if (t.depth != 16 || t.width != t.height)
      throw InputError("coordinate tiles must be square 16-bit PNGs (the coords folder of a material tile set)");
    auto& c = coords.emplace_back(std::size_t(t.width) * std::size_t(t.height));
    for (int y = 0; y < t.height; ++y)
      for (int x = 0; x < t.width; ++x)
        c[std::size_t(y) * std::size_t(t.width) + std::size_t(x)] = t.sample(x, y, 0) | t.sample(x, y, 1) << 16;
  }
  return coords;
}

Image normal_map_from_height(const Image& height, double strength, bool torus) {
  const int w = height.width, h = height.height;
  const double max = height.max_value();
  auto lum = [&](int x, int y) {
    x = torus ? (x % w + w) % w : std::clamp(x, 0, w - 1);
    y = torus ? (y % h + h) % h : std::clamp(y, 0, h - 1);
    if (height.channels < 3) return height.value(x, y, 0) / max;
    return (0.299 * height.value(x, y, 0) + 0.587 * height.value(x, y, 1) + 0.114 * height.value(x, y, 2)) / max;
  };
  Image out(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double dx = (lum(x + 1, y) - lum(x - 1, y)) / 2 * strength,
                   dy = (lum(x, y + 1) - lum(x, y - 1)) / 2 * strength;
      const double len = std::sqrt(dx * dx + dy * dy + 1);
      const double n[3] = {-dx / len, -dy / len, 1 / len};
      std::uint8_t* p = out.at(x, y);
      for (int c = 0; c < 3; ++c) p[c] = std::uint8_t(std::lround((n[c] + 1) / 2 * 255));
    }
  return out;
}

void write_map_tiles(const std::string& dir, const std::vector<Image>& tiles, ColourSpace space,
                     const nlohmann::json& manifest) {
  const fs::path folder(dir);
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw InputError(fmt::format("{}: cannot create the folder ({})", folder.string(), ec.message()));
  const bool is_float = !tiles.empty() && tiles[0].is_float();
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    const std::string stem = (folder / fmt::format("tile-{:04d}", t)).string();
    write_file_atomic(stem + image_extension(tiles[t]), encode_image(tiles[t]));
    // A tile of the other format from an earlier run would hold the same tile index.
    fs::remove(stem + (is_float ? ".png" : ".exr"), ec);
  }
  nlohmann::json j = manifest;
  j["colour_space"] = std::string(colour_space_name(space));
  j["bits"] = tiles.empty() ? 8 : tiles[0].depth;
  j["format"] = is_float ? "exr float" : "png unorm";
  write_file_atomic((folder / "tiles.json").string(), j.dump(2) + "\n");
}

}  // namespace tilekit
