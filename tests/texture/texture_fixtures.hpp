#pragma once
// Shared pieces of the texture tests: a synthetic exemplar, the fetched real textures, and small
// tile sets and atlases built once per test binary.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "atlas/lookup.hpp"
#include "base/hash.hpp"
#include "base/random.hpp"
#include "texture/exemplar.hpp"
#include "texture/texture_atlas.hpp"
#include "texture/tile_synthesis.hpp"

namespace tilekit::test {

// A colourful procedural texture (sines plus seeded noise): no files needed.
inline Image synthetic_image(int w, int h, std::uint64_t seed = 3) {
  Image img{w, h, std::vector<std::uint8_t>(std::size_t(w) * std::size_t(h) * 4)};
  SplitMix64 rng(seed);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double v = 0.5 + 0.25 * std::sin(x * 0.31 + 0.7 * std::sin(y * 0.13)) * std::cos(y * 0.23);
      std::uint8_t* p = img.at(x, y);
      for (int c = 0; c < 3; ++c)
        p[c] =
            std::uint8_t(std::clamp(int(255 * v + 40 * (rng.uniform() - 0.5) + 30 * c * std::sin(x * 0.05)), 0, 255));
      p[3] = 255;
    }
  return img;
}
// Grey blobs (Gaussians of 4-18 px, lighter or darker) at random places: nothing repeats, not
// even once smoothed (synthetic_image's sines do: dominant_period finds them at its second look).
inline Image blob_image(int side, std::uint64_t seed = 9) {
  Image img(side, side, Rgb{128, 128, 128});
  SplitMix64 rng(seed);
  for (int k = 0; k < side * side / 600; ++k) {
    const double cx = rng.uniform() * side, cy = rng.uniform() * side, r = 4 + rng.uniform() * 14;
    const int v = int(rng.uniform() * 200) - 100;
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) {
        const double d2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
        const int c = std::clamp(int(img.at(x, y)[0] + v * std::exp(-d2 / (r * r))), 0, 255);
        img.set(x, y, Rgb{std::uint8_t(c), std::uint8_t(c), std::uint8_t(c)});
      }
  }
  return img;
}
inline Exemplar synthetic_exemplar(int side = 160) {
  return exemplar_from_image(synthetic_image(side, side), "synthetic");
}

// A fetched real texture (scripts/fetch-textures.sh, run by scripts/setup.sh) when it is in the
// cache; otherwise a 512x512 procedural exemplar seeded by the name, so that the tests need no
// network (a note on stderr says which).
inline Exemplar real_exemplar(const std::string& name) {
  const std::string path = real_texture_path(name);
  if (!path.empty()) return load_exemplar(path);
  std::fprintf(stderr, "note: real texture '%s' not in %s (scripts/fetch-textures.sh): using a procedural exemplar\n",
               name.c_str(), texture_cache_dir().c_str());
  return exemplar_from_image(synthetic_image(512, 512, fnv1a64(name)), "procedural-" + name);
}

inline SynthesisOptions small_options(TileKind kind, std::uint32_t colours, int tile_px, int threads = 1) {
  SynthesisOptions o;
  o.kind = kind;
  o.colours = colours;
  o.tile_px = tile_px;
  o.threads = threads;
  o.seed = 5;
  o.search = 32;
  o.rounds = 2;
  o.centre_candidates = 8;
  return o;
}

// The same atlas cells in a seeded random arrangement (not a packing), with positions to match.
inline AtlasLookup shuffled_lookup(AtlasLookup l, std::uint64_t seed) {
  SplitMix64 rng(seed);
  shuffle(l.cells.begin(), l.cells.end(), rng);
  for (std::size_t cell = 0; cell < l.cells.size(); ++cell)
    l.positions[l.cells[cell]] = {int(cell) / l.cols, int(cell) % l.cols};
  return l;
}

// Grass tiles (C = 2, 64 px) of either kind and their atlas from the constructions, built once.
inline const TextureTileSet& grass_tiles(TileKind kind) {
  static std::map<TileKind, TextureTileSet> cache;
  auto it = cache.find(kind);
  if (it == cache.end())
    it = cache.emplace(kind, synthesize_tiles(real_exemplar("grass"), small_options(kind, 2, 64, 2))).first;
  return it->second;
}
inline const TextureAtlas& grass_atlas(TileKind kind) {
  static std::map<TileKind, TextureAtlas> cache;
  auto it = cache.find(kind);
  if (it == cache.end())
    it = cache.emplace(kind, build_texture_atlas(atlas_lookup(kind, 2), grass_tiles(kind).tiles)).first;
  return it->second;
}

}  // namespace tilekit::test
