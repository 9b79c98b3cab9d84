#pragma once
// Material sets: several aligned maps of one surface (albedo, normal, roughness, height, ...)
// made into texture tiles by one synthesis. The samples and cuts are chosen once, on the albedo
// with a weighted term per map in every seam cost (seam_cost_maps), and every map's tiles are then copies of its
// own texels at the positions the synthesis recorded (TextureTileSet::coords), so the maps stay
// aligned texel for texel. The positions are written as a map of their own (coordinate tiles), so
// a map made later can be carried over the same way (`texture transfer`).
#include <array>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "texture/exemplar.hpp"
#include "texture/mipmap.hpp"
#include "texture/perspective.hpp"
#include "texture/tile_synthesis.hpp"

namespace tilekit {

struct MaterialMap {
  std::string name;  // what its folder is called (DIR/maps/NAME)
  std::string file;
  ColourSpace space = ColourSpace::Srgb;  // srgb colour, linear data or tangent-space normals
  double weight = 1;                      // its term's weight in the seam costs (seam_cost_maps)
  Image image;                            // as read: 8 or 16 bits or float, RGBA; the exemplar's size after resize_maps
  bool resized = false;                   // resampled to the exemplar's grid (resize_maps)
};

// Reads NAME=FILE[:ROLE[:WEIGHT]] (ROLE srgb, linear or normal; default linear, "normal" for a
// map called normal); InputError (exit 2) naming the argument otherwise. 16-bit PNGs and TIFFs
// keep 16 bits, float TIFF and OpenEXR stay float (and may not have the role srgb: float is linear).
MaterialMap parse_material_map(const std::string& spec);

// Every map resampled (bilinear; normals renormalised) to w x h where it is not that size already.
void resize_maps(std::vector<MaterialMap>& maps, int w, int h, bool torus);

// The maps as the synthesis' seam costs weigh them (SynthesisOptions::cost_maps): cost = the
// albedo's own term (exactly the albedo-only cost) + the sum over the maps of WEIGHT x the map's
// distance (normals as vectors) in units of its mean neighbour distance. A cut that is invisible
// in the albedo but shows in the normals costs what it shows. A float map is weighed as 16 bits
// over its own range (the unit makes the scale irrelevant).
std::vector<SeamCostMap> seam_cost_maps(const std::vector<MaterialMap>& maps);

// A map of the exemplar's size as the synthesis saw the exemplar: rectified (perspective) and
// resampled to whole periods (exemplar_scale) as the tile set records; unchanged otherwise.
Image map_as_sampled(const Image& map, bool tileable, const PerspectiveFit& perspective,
                     std::array<double, 2> exemplar_scale);

// The tiles of a map: texel i of tile t is sampled_map's texel at s.coords[t][i]. InputError
// when the set has no coordinates or the map is smaller than they reach.
std::vector<Image> transfer_tiles(const std::vector<std::vector<std::uint32_t>>& coords, int tile_px,
                                  const Image& sampled_map);

// The coordinate tiles: 16-bit RGB, R = x, G = y of the exemplar texel (as sampled), B = 0.
std::vector<Image> coordinate_tiles(const std::vector<std::vector<std::uint32_t>>& coords, int tile_px);
// Back from those tiles (InputError unless they are 16-bit, tile_px square and as many as `count`).
std::vector<std::vector<std::uint32_t>> coords_from_tiles(const std::vector<Image>& tiles);

// A tangent-space normal map (RGB = (n + 1) / 2, 8-bit) of a height field: the luminance of
// `height` (0..1) times `strength` texels of relief per unit, central differences (a torus when
// `torus`). For tests, benchmarks and examples; real materials come with their own.
Image normal_map_from_height(const Image& height, double strength, bool torus);

// Writes FOLDER/tile-NNNN.png (float tiles: tile-NNNN.exr, OpenEXR 32-bit float) and
// FOLDER/tiles.json (`manifest` with the colour space, "bits" 8, 16 or 32 and "format" "png unorm"
// or "exr float"): a tile set of its own, as `texture atlas FOLDER` reads it (DIR/maps/NAME, DIR/coords).
void write_map_tiles(const std::string& folder, const std::vector<Image>& tiles, ColourSpace space,
                     const nlohmann::json& manifest);

}  // namespace tilekit
