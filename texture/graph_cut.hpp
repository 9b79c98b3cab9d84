#pragma once
// Graph-cut patch merging (Kwatra, Schoedl, Essa, Turk and Bobick 2003, "Graphcut textures"), as
// Ng et al. use it to lay a tile-unique centre patch over the cross-shaped seam of a corner tile
// (thesis sec. 5.3). Every pixel of `region` is a node that may keep the old image A or take the
// new patch B; pixels outside the region keep A, pixels in `forced` take B. The seam between
// neighbours s and t costs the steps it would show, |A(s) - B(t)| + |B(s) - A(t)| (the two ways
// round; Kwatra et al.'s match cost compares A and B at the same pixel instead, and their
// gradient-normalised one divides by the local gradients, which sends seams through busy texture
// where the step across them is large: both saw more visible cuts, by texture/README.md's cut
// visibility, on every texture tried). The minimum cut is Boost.Graph's boykov_kolmogorov_max_flow.
#include <cstdint>
#include <functional>
#include <vector>

#include "image/image.hpp"

namespace tilekit {

struct GraphCutResult {
  std::vector<std::uint8_t> take_new;  // per pixel: 1 = from B
  double cost = 0;                     // the cut's summed M
  int nodes = 0;
};

// A and B are the same size; region and forced hold one byte per pixel. Pixels of the region
// must not lie on the image border (the gradients look one pixel further). keep_cost (in the
// units of colour_distance) is paid for every pixel of the region, not forced, that keeps A: a
// pull towards B, so the cut leaves a pixel to A only where that makes the seam cheaper by as
// much. The result's cost includes it.
// Material sets: `extra(i, j)`, when given, is the further cost (the maps' terms) of A's texel
// at pixel i shown next to B's at pixel j; the seam then costs colour_weight times the colour's
// steps plus extra(s, t) + extra(t, s).
GraphCutResult graph_cut_merge(const Image& a, const Image& b, const std::vector<std::uint8_t>& region,
                               const std::vector<std::uint8_t>& forced, double keep_cost = 0,
                               const std::function<float(std::size_t, std::size_t)>& extra = {},
                               float colour_weight = 1);

}  // namespace tilekit
