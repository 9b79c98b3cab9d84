// What `texture tiles`, `texture atlas` and `texture render` read from outside. Byte 0 picks:
//   0: an image file (PNG, JPEG, TIFF, OpenEXR, ... through image/image.hpp's one decoder, as RGBA
//      and as grey, at 8 bits and at its own depth):
//      headers that claim more than kMaxImagePixels are refused before decoding;
//   1: an atlas manifest (atlas.json, texture/texture_atlas.hpp) beside a valid two-colour atlas's
//      mip levels: read_texture_atlas must load it or refuse it, and what loads is a packing whose
//      level 0 is cols * tile_px x rows * tile_px pixels;
//   2: a texture tile-set manifest (tiles.json, read_tile_set_manifest).
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "atlas/lookup.hpp"
#include "base/error.hpp"
#include "image/image.hpp"
#include "texture/texture_atlas.hpp"
#include "tilesets/tile_set.hpp"

namespace {

using namespace tilekit;

const std::string& workdir() {
  static const std::string dir = [] {
    std::string t = (std::filesystem::exists("/dev/shm") ? std::string("/dev/shm") : std::string("/tmp")) +
                    "/tilekit-fuzz-texture-XXXXXX";
    std::string d = ::mkdtemp(t.data());
    // A valid atlas of the two-colour corner packing with 16-pixel tiles, like the seed that
    // `texture atlas` writes (scripts/fuzz.sh): its PNG levels stay, the manifest is the input.
    const AtlasLookup lookup = atlas_lookup(TileKind::Corner, 2);
    std::vector<Image> tiles;
    for (std::size_t i = 0; i < lookup.cells.size(); ++i) tiles.emplace_back(16, 16, Rgb{std::uint8_t(i * 16), 0, 0});
    write_texture_atlas(build_texture_atlas(lookup, tiles), d + "/atlas.png", "// glsl\n");
    std::filesystem::create_directories(d + "/tiles");
    return d;
  }();
  return dir;
}

void write(const std::string& path, const std::uint8_t* data, std::size_t size) {
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), std::streamsize(size));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string& dir = workdir();
  try {
    switch (data[0] % 3) {
      case 0: {
        const std::string path = dir + "/image";
        write(path, data + 1, size - 1);
        for (int channels : {4, 1})
          for (bool keep_depth : {false, true}) {  // 16-bit PNG and TIFF, float TIFF and OpenEXR kept
            const Image img = read_image(path, channels, keep_depth);
            if (std::int64_t(img.width) * img.height > kMaxImagePixels || (!keep_depth && img.depth != 8) ||
                img.pixels.size() != std::size_t(img.width) * std::size_t(img.height) * std::size_t(channels) *
                                         std::size_t(img.depth / 8))
              __builtin_trap();
          }
        break;
      }
      case 1: {
        write(dir + "/atlas.json", data + 1, size - 1);
        const TextureAtlas a = read_texture_atlas(dir + "/atlas.json");
        if (a.levels.empty() || a.levels[0].width != a.lookup.cols * a.tile_px ||
            a.levels[0].height != a.lookup.rows * a.tile_px || a.lookup.cells.size() != a.lookup.positions.size())
          __builtin_trap();
        break;
      }
      default: {
        write(dir + "/tiles/tiles.json", data + 1, size - 1);
        const TileSetManifest m = read_tile_set_manifest(dir + "/tiles");
        if (m.colours < 1 || m.colours > kMaxCompleteSetColours) __builtin_trap();
      }
    }
  } catch (const InputError&) {
  }
  return 0;
}
