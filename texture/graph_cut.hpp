#pragma once
// Graph-cut patch merging (Kwatra, Schoedl, Essa, Turk and Bobick 2003, "Graphcut textures"), as
// Ng et al. use it to lay a tile-unique centre patch over the cross-shaped seam of a corner tile
// (thesis sec. 5.3). Every pixel of `region` is a node that may keep the old image A or take the
// new patch B; pixels outside the region keep A, pixels in `forced` take B. The seam between
// neighbours s and t costs Kwatra's gradient-normalised match cost
//   M(s, t) = (|A(s) - B(s)| + |A(t) - B(t)|) / (|G_A(s)| + |G_A(t)| + |G_B(s)| + |G_B(t)| + eps),
// G the gradient along the direction s -> t, so a seam prefers to run through busy texture where
// it is hard to see. The minimum cut is Boost.Graph's boykov_kolmogorov_max_flow.
#include <cstdint>
#include <vector>

#include "atlas/atlas_image.hpp"

namespace tilekit {

struct GraphCutResult {
  std::vector<std::uint8_t> take_new;  // per pixel: 1 = from B
  double cost = 0;                     // the cut's summed M
  int nodes = 0;
};

// A and B are the same size; region and forced hold one byte per pixel. Pixels of the region
// must not lie on the image border (the gradients look one pixel further).
GraphCutResult graph_cut_merge(const Image& a, const Image& b, const std::vector<std::uint8_t>& region,
                               const std::vector<std::uint8_t>& forced);

}  // namespace tilekit
