#pragma once
// Mip chains for texture atlases (thesis sec. 5.4). Each level halves the previous one (sizes
// floor(w/2), as OpenGL expects) with a tent filter as wide as two source texels on either side
// of the output texel ([1 3 3 1]/8 per axis for even sizes): wider than a 2x2 box, so a texel
// near a tile border mixes in the neighbouring tile. In an atlas that is a packing (a valid
// toroidal tiling) those are the texels of a correct neighbour, and the levels equal the levels
// of the infinite tiling. The weights are integers summing to 256 per axis, so a level is the
// same on every machine.
//
// What is averaged depends on the map's colour space (ColourSpace): sRGB colour is averaged in
// linear light (a 1-pixel black-and-white checker gives 188 at every level, not 128), with alpha
// premultiplied so that transparent texels lend no colour (no dark fringe); linear data is
// averaged as stored, alpha premultiplied too; tangent-space normals (RGB = (n + 1) / 2) are
// averaged as vectors and renormalised, and the length the average lost (Toksvig 2005: |mean n|
// < 1 where the normals disagree) can be read off with `normal_lengths` before renormalising.
// 16-bit images (Image::depth 16) keep 16 bits at every level, float images (depth 32) stay float:
// averaged as stored, never clamped (heights of -3.5 .. 1200.25 average to what they average to),
// and as linear data even when called sRGB (float colour is scene-linear, as OpenEXR's is; the
// CLI refuses sRGB for float maps).
#include <string>
#include <string_view>
#include <vector>

#include "image/image.hpp"

namespace tilekit {

enum class MipEdge {
  Wrap,   // the image is a torus (an atlas of a packing)
  Clamp,  // the image ends at its border (a window of a tiling)
};

enum class ColourSpace {
  Srgb,    // colour in the sRGB transfer function (albedo, base colour): averaged in linear light
  Linear,  // data stored linearly (roughness, height, masks, labels): averaged as stored
  Normal,  // tangent-space normals, RGB = (n + 1) / 2: averaged as vectors, renormalised
};
// "srgb", "linear", "normal": the manifests' names.
std::string_view colour_space_name(ColourSpace c);
// The colour space named by `name`, or false for a name that is none of them.
bool parse_colour_space(std::string_view name, ColourSpace& out);

// sRGB transfer function (IEC 61966-2-1), 0..1 both ways.
double srgb_to_linear(double v);
double linear_to_srgb(double v);

Image downsample(const Image& img, MipEdge edge, ColourSpace space = ColourSpace::Srgb);
// Level 0 (the image itself) down to 1x1.
std::vector<Image> mip_chain(const Image& level0, MipEdge edge, ColourSpace space = ColourSpace::Srgb);

// Per texel of downsample(normals), the length of the averaged normal before it was renormalised
// (1: the normals under it agree). Toksvig's factor: a roughness map's level can take the lost
// length as extra variance (toksvig_roughness).
std::vector<double> normal_lengths(const Image& normals, MipEdge edge);
// Roughness r (GGX alpha = r^2) widened by the variance a normal of length `len` shows:
// alpha'^2 = alpha^2 + (1 - len) / len (Toksvig 2005), back as roughness.
double toksvig_roughness(double r, double len);
// The mip chain of a roughness map (linear data, roughness in R, G and B) that goes with the
// normal map whose chain is `normals` (levels of the same sizes): level k is level k - 1 of this
// chain downsampled, each texel widened (toksvig_roughness) by the length the normals lost from
// normals[k - 1] to level k (normal_lengths), so the variances of successive levels add up.
// Level 0 is `roughness0` itself; alpha is left as it is. Empty when the sizes differ.
std::vector<Image> toksvig_chain(const Image& roughness0, const std::vector<Image>& normals, MipEdge edge);

}  // namespace tilekit
