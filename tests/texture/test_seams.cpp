// Seams of rendered tilings of real textures: the mean step across tile borders of a
// 32x32-tile render over the mean step inside tiles stays within 1.10 for corner and Wang tiles
// (C = 2, 64 px) of grass, gravel and brick, where abutting random squares of the same textures
// does not. Below 0.8 would mean borders blander than the texture (seams hidden, not matched).
// Without the fetched textures, procedural exemplars stand in (texture_fixtures.hpp).
#include <gtest/gtest.h>

#include "render/cpu_renderer.hpp"
#include "texture/seam_metrics.hpp"
#include "texture_fixtures.hpp"

namespace tilekit {
namespace {

TEST(Seams, RenderedTilingsOfRealTexturesHaveSeamRatioAtMostOnePointOne) {
  for (const std::string name : {"brick", "grass", "gravel"}) {
    const Exemplar e = test::real_exemplar(name);
    for (TileKind kind : {TileKind::Corner, TileKind::Wang}) {
      const int px = 64;
      SynthesisOptions o = test::small_options(kind, 2, px, 2);
      const TextureTileSet s = synthesize_tiles(e, o);
      const TextureAtlas atlas = build_texture_atlas(atlas_lookup(kind, 2), s.tiles);
      const Image img = render_cpu(atlas, View{32 * px, 32 * px, 1, 0, 0, 0}, {HashKind::LongPeriod, 1, 2, false});
      const SeamStatistics st = seam_statistics(img, px);
      EXPECT_LE(st.seam_ratio, 1.10) << name << " " << kind_name(kind);
      EXPECT_GT(st.seam_ratio, 0.8) << name << " " << kind_name(kind);
      // the baseline: every tile an independent square of the exemplar
      const TextureTileSet naive = naive_tiles(e, o);
      const Tiling t = kind == TileKind::Corner ? DirectCornerTiling(2, HashKind::LongPeriod, 1).generate(32, 32)
                                                : DirectWangTiling(2, 2, HashKind::LongPeriod, 1).generate(32, 32);
      const SeamStatistics nv = seam_statistics(stitch_tiles(naive, t), px);
      EXPECT_GT(nv.seam_ratio, 1.5) << name << " naive";
    }
  }
}

}  // namespace
}  // namespace tilekit
