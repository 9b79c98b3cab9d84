// The stronger prune of issue 40 (surround with 5x5 patches to a fixed point), the stronger step
// operations, and the provenance of the three Jeandel-Rao files (tilesets/data/README.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <set>
#include <string>
#include <vector>

#include "aperiodic/canonical.hpp"
#include "aperiodic/colour_merge.hpp"
#include "aperiodic/convert.hpp"
#include "aperiodic/enumerate.hpp"
#include "aperiodic/prune.hpp"
#include "aperiodic/steps.hpp"
#include "base/error.hpp"
#include "base/signals.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit {
namespace {

TEST(StrongerPrune, FiveByFivePatchesTakeTheNinetyTwoSetToEightyNine) {
  TileSet set92;
  replay_chain("jeandel-rao-11-variant-2", {"blocks", "to-wang", "horizontal+prune"}, &set92);
  ASSERT_EQ(set92.size(), 92u);
  PruneReport rep;
  // 3x3 patches change nothing (the set is their fixed point); 5x5 patches remove 3 tiles.
  EXPECT_EQ(prune(set92, 3, &rep).size(), 92u);
  const TileSet set89 = prune(set92, 3, &rep, 2);
  EXPECT_EQ(set89.size(), 89u);
  EXPECT_EQ(rep.removed_by_surround, 3u);
  EXPECT_EQ(rep.removed_by_scc, 0u);
  // The chain with the stronger step gives the same 89 tiles, still conjugate.
  TileSet last;
  const auto links = replay_chain("jeandel-rao-11-variant-2", {"blocks", "to-wang", "horizontal+prune5"}, &last);
  EXPECT_EQ(links.back().tiles, 89u);
  EXPECT_EQ(links.back().label, "conjugate");
  EXPECT_EQ(links.back().hash, canonical_form(set89).hash);
}

// The long steps (the 5x5 surround, a colour-merge search) stop at a signal instead of running
// on for minutes (`aperiodic enumerate` then drops the batch and writes its checkpoint).
TEST(StrongerPrune, ASignalStopsTheLongStepsPartWay) {
  TileSet set92;
  replay_chain("jeandel-rao-11-variant-2", {"blocks", "to-wang", "horizontal+prune"}, &set92);
  const TileSet corner = resolve_tile_set("complete-corner-2");
  SignalCatcher catcher;
  ASSERT_EQ(std::raise(SIGTERM), 0);
  PruneReport rep;
  EXPECT_THROW(prune(set92, 3, &rep, 2), Interrupted);
  EXPECT_THROW(least_colour_merge(corner.corner_tiles(), false, 1, 0, 8), Interrupted);
}

TEST(StrongerPrune, FiveByFiveSurroundIsTheThreeByThreeOneAtRadiusOne) {
  const std::vector<WangTile> w = resolve_tile_set("culik-13").wang_tiles();
  EXPECT_EQ(surroundable(w, 1), surroundable(w));
  // Every tile of an aperiodic set occurs in its tilings here, so all are surrounded at radius 2.
  EXPECT_EQ(surroundable(w, 2).size(), w.size());
}

TEST(StrongerPrune, OperationsAreKnownAndCheckedByTheSearch) {
  for (const char* op : {"prune5", "horizontal+prune5", "merge-colours2"}) {
    const auto& all = all_step_operations();
    EXPECT_NE(std::find(all.begin(), all.end(), op), all.end()) << op;
    const auto& standard = step_operations();
    EXPECT_EQ(std::find(standard.begin(), standard.end(), op), standard.end()) << op;  // opt-in
  }
  EnumerateOptions o;
  o.sources = {"culik-13"};
  o.max_depth = 0;
  o.operations = {"prune", "squash"};
  EXPECT_THROW(enumerate_conversions(o), RequestError);
}

TEST(JeandelRaoSources, ThreeDifferentSetsAndVariantThreeIsNoSource) {
  const TileSet fig4 = resolve_tile_set("jeandel-rao-11");
  const TileSet fig3 = resolve_tile_set("jeandel-rao-11-variant-2");
  const TileSet fig10 = resolve_tile_set("jeandel-rao-11-variant-3");
  // Not renamings or symmetric images of one another.
  std::set<std::string> forms;
  for (const TileSet* s : {&fig4, &fig3, &fig10}) {
    const CanonicalForm f = canonical_form(*s);
    EXPECT_TRUE(f.exact);
    forms.insert(f.hash);
  }
  EXPECT_EQ(forms.size(), 3u);
  // Fig. 4 has 4 N/S colours against Fig. 3's 5; Fig. 10 differs from Fig. 3 in one tile.
  EXPECT_EQ(wang_horizontal_colours(fig4.wang_tiles()), 4u);
  EXPECT_EQ(wang_horizontal_colours(fig3.wang_tiles()), 5u);
  std::vector<WangTile> only3, only10;
  const auto& a = fig3.wang_tiles();
  const auto& b = fig10.wang_tiles();
  std::set<WangTile> sa(a.begin(), a.end()), sb(b.begin(), b.end());
  std::set_difference(sa.begin(), sa.end(), sb.begin(), sb.end(), std::back_inserter(only3));
  std::set_difference(sb.begin(), sb.end(), sa.begin(), sa.end(), std::back_inserter(only10));
  EXPECT_EQ(only3.size(), 1u);
  EXPECT_EQ(only10.size(), 1u);
  const auto& src = published_enumeration_sources();
  EXPECT_EQ(std::find(src.begin(), src.end(), "jeandel-rao-11-variant-3"), src.end());
  EXPECT_NE(std::find(src.begin(), src.end(), "jeandel-rao-11-variant-2"), src.end());
}

}  // namespace
}  // namespace tilekit
