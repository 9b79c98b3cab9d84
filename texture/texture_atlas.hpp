#pragma once
// Texture atlases from packings (thesis sec. 5.4): the C^4 texture tiles laid out as the packing
// of the complete set that `atlas_lookup` finds (atlas/lookup.hpp), with a full mip chain. The
// atlas is a valid toroidal tiling, so bilinear and trilinear filtering across a tile border
// (wrap-around included) reads the texels of a correct neighbour: no gutters are needed, and
// the mip levels equal those of the infinite tiling near every border (tests/texture).
#include <string>
#include <vector>

#include "atlas/atlas_image.hpp"
#include "atlas/lookup.hpp"
#include "texture/mipmap.hpp"
#include "image/ktx2.hpp"

namespace tilekit {

struct TextureAtlas {
  AtlasLookup lookup;  // the packing: cells (atlas cell -> tile) and positions (tile -> cell)
  int tile_px = 0;
  std::vector<Image> levels;  // level 0 (rows * tile_px x cols * tile_px) down to 1x1
  std::string tiles_dir;      // where the tiles came from (informational)
  // How the levels were averaged and how a renderer samples them (mipmap.hpp): an sRGB atlas is
  // uploaded as SRGB8_ALPHA8 and filtered in linear light. The levels are 8-bit, or 16-bit or
  // float when the tiles were (levels[k].depth; float is linear or normal, never sRGB).
  ColourSpace colour_space = ColourSpace::Srgb;
};

// InputError unless there is one square image of tile_px pixels per tile of the lookup's set.
TextureAtlas build_texture_atlas(const AtlasLookup& lookup, const std::vector<Image>& tiles,
                                 ColourSpace space = ColourSpace::Srgb);
// The same from a folder written by `tilekit texture tiles` (or any folder of tile images named
// by tile index; atlas_from_tile_images reads it).
TextureAtlas build_texture_atlas(const AtlasLookup& lookup, const std::string& tiles_dir,
                                 ColourSpace space = ColourSpace::Srgb);

// Level-0 texels a tile: tile_px, but for an atlas resampled to a power of two
// (resample_to_power_of_two), its width over its columns (not a whole number).
inline float atlas_texels_per_tile(const TextureAtlas& a) {
  return a.levels.empty() ? float(a.tile_px) : float(a.levels[0].width) / float(a.lookup.cols);
}

// The atlas with level 0 resampled (on the torus: area-weighted, wrapping) to the power of two
// nearest its size on a log scale along each axis, and its mip chain made again: what engines
// like (KTX2 with every level, block compression); tile_px stays the tile size of the views. The
// sampler reads it through normalised coordinates, its level of detail through
// atlas_texels_per_tile. Tile borders fall inside texels, so each border texel blends the two
// tiles on either side: the atlas is a toroidal tiling, so they are a valid pair of neighbours.
TextureAtlas resample_to_power_of_two(const TextureAtlas& a);

// The atlas as one KTX2 texture (image/ktx2.hpp): every level, RGBA8 sRGB or UNORM by
// `transfer`, the key/value data "tilekit.atlas" naming the packing (kind, colors, rows, cols,
// tile_px, source) as JSON.
Ktx2Texture texture_atlas_ktx2(const TextureAtlas& a);

// Files written next to `png` (say atlas.png): atlas.png (level 0), atlas.mip1.png ...
// atlas.mipL.png (a float atlas: atlas.exr, atlas.mip1.exr, ..., OpenEXR 32-bit float),
// atlas.ktx2 (every level in one file), atlas.json (the manifest: tile size, levels, colour
// space, "bits" and "format", the lookup), atlas.h (C lookup table) and atlas.glsl (the GLSL ES 3.0
// sampler, render/glsl_sampler.hpp, with the given hash), and one file per entry of `shaders`
// (the stem plus its suffix, say ".hlsl": the sampler in other languages).
struct AtlasFiles {
  std::vector<std::string> levels;
  std::string ktx2, manifest, header, glsl;
  std::vector<std::string> shaders;
};
AtlasFiles write_texture_atlas(const TextureAtlas& a, const std::string& png, const std::string& glsl_source,
                               const std::vector<std::pair<std::string, std::string>>& shaders = {});
// Reads an atlas written by write_texture_atlas from its level-0 PNG (or its .json manifest).
// InputError (exit 2) naming the file for a missing or inconsistent file or a manifest whose
// cells are not a packing (checked by the independent validator).
TextureAtlas read_texture_atlas(const std::string& png_or_manifest);

// What `texture atlas` needs from the tiles.json that `texture tiles` writes beside the tile
// images: the kind (checked against the synthesis method) and the colours (1..64, checked
// against the tile count). InputError (exit 2) naming the file and the JSON path otherwise.
struct TileSetManifest {
  TileKind kind = TileKind::Corner;
  std::uint32_t colours = 0;
  ColourSpace colour_space = ColourSpace::Srgb;  // "colour_space" (absent: srgb)
};
TileSetManifest read_tile_set_manifest(const std::string& dir);

// The stem shared by an atlas's files: "dir/atlas" for "dir/atlas.png" or "dir/atlas.json".
std::string atlas_stem(const std::string& path);

}  // namespace tilekit
