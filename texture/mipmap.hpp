#pragma once
// Mip chains for texture atlases (thesis sec. 5.4). Each level halves the previous one (sizes
// floor(w/2), as OpenGL expects) with a tent filter as wide as two source texels on either side
// of the output texel ([1 3 3 1]/8 per axis for even sizes): wider than a 2x2 box, so a texel
// near a tile border mixes in the neighbouring tile. In an atlas that is a packing (a valid
// toroidal tiling) those are the texels of a correct neighbour, and the levels equal the levels
// of the infinite tiling. Integer weights, so the chain is exact and reproducible.
#include <vector>

#include "image/image.hpp"

namespace tilekit {

enum class MipEdge {
  Wrap,   // the image is a torus (an atlas of a packing)
  Clamp,  // the image ends at its border (a window of a tiling)
};

Image downsample(const Image& img, MipEdge edge);
// Level 0 (the image itself) down to 1x1.
std::vector<Image> mip_chain(const Image& level0, MipEdge edge);

}  // namespace tilekit
