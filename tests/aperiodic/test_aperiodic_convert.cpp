#include <gtest/gtest.h>

#include "aperiodic/convert.hpp"
#include "aperiodic/translation_lift.hpp"
#include "base/error.hpp"
#include "tilesets/tile_set_io.hpp"

using namespace tilekit;

namespace {
std::vector<WangTile> ref(const std::string& name) { return resolve_tile_set(name).wang_tiles(); }
}  // namespace

TEST(DiagonalTranslation, GivesThesisTable81SizesForTheThreeReferenceSets) {
  // thesis Table 8.1, column 2: 125/13, 214/14, 87/16
  Conversion c = diagonal_translation(ref("culik-13"));
  EXPECT_EQ(c.size(), 125u);
  EXPECT_EQ(c.colours, 13u);
  Conversion k = diagonal_translation(ref("kari-14"));
  EXPECT_EQ(k.size(), 214u);
  EXPECT_EQ(k.colours, 14u);
  Conversion a = diagonal_translation(ref("ammann-gs-16"));
  EXPECT_EQ(a.size(), 87u);
  EXPECT_EQ(a.colours, 16u);
  EXPECT_EQ(a.soundness, Soundness::Conjugate);
}

TEST(RotationConstruction, ReportsWhiteAndBlackCountsOfTable81) {
  // thesis Table 8.1, rotation column: 60(13+47)/9, 94(14+80)/9, 49(16+33)/12
  Conversion c = rotation(ref("culik-13"));
  EXPECT_EQ(c.white, 13u);
  EXPECT_EQ(c.black, 47u);
  EXPECT_EQ(c.colours, 9u);
  Conversion k = rotation(ref("kari-14"));
  EXPECT_EQ(k.white + k.black, 94u);
  EXPECT_EQ(k.black, 80u);
  Conversion a = rotation(ref("ammann-gs-16"));
  EXPECT_EQ(a.white + a.black, 49u);
  EXPECT_EQ(a.colours, 12u);
}

TEST(SubdivisionConstruction, GivesFourTilesPerWangTileAndTilesPlusEdgeColoursPlusOne) {
  // thesis Table 8.1, subdivision column: 52/19, 56/21, 64/23
  Conversion c = subdivision(ref("culik-13"));
  EXPECT_EQ(c.size(), 52u);
  EXPECT_EQ(c.colours, 19u);
  EXPECT_EQ(subdivision(ref("ammann-gs-16")).colours, 23u);
}

TEST(SubdivisionConstruction, CentreMergesNeverAddTilesAndStayConjugate) {
  for (const char* name : {"culik-13", "kari-14", "ammann-gs-16", "jeandel-rao-11"}) {
    Conversion plain = subdivision(ref(name));
    Conversion merged = subdivision(ref(name), {true, false});
    EXPECT_LE(merged.size(), plain.size()) << name;
    EXPECT_EQ(merged.soundness, Soundness::Conjugate);
  }
  Conversion star = subdivision(ref("culik-13"), {false, true});
  EXPECT_EQ(star.soundness, Soundness::Unverified);
  EXPECT_EQ(star.colours, 18u);  // the star shares an edge colour
}

TEST(TranslationConstructions, ReproduceTheThesisSizesAndLabelSoundness) {
  // thesis Table 8.1: horizontal 44/6 (ammann), vertical 86/6 (kari), 44/6 (ammann)
  Conversion h = horizontal_translation(ref("ammann-gs-16"));
  EXPECT_EQ(h.size(), 44u);
  EXPECT_EQ(h.colours, 6u);
  Conversion v = vertical_translation(ref("kari-14"));
  EXPECT_EQ(v.size(), 86u);
  EXPECT_EQ(v.colours, 6u);
  // kari-14's columns lift uniquely: the vertical translation is a conjugacy.
  EXPECT_EQ(v.soundness, Soundness::Conjugate);
  // ammann-gs-16's corner rows include one with no Wang lift: not proven sound.
  EXPECT_EQ(h.soundness, Soundness::Unverified);
}

TEST(CornerToWangPairs, KeepsTileCountAndCountsPairColoursAsTable82) {
  // thesis Table 8.2: 125/50, 214/86, 87/44 from the diagonal corner sets
  EXPECT_EQ(corner_to_wang_pairs(diagonal_translation(ref("culik-13")).corner).colours, 50u);
  EXPECT_EQ(corner_to_wang_pairs(diagonal_translation(ref("kari-14")).corner).colours, 86u);
  Conversion w = corner_to_wang_pairs(diagonal_translation(ref("ammann-gs-16")).corner);
  EXPECT_EQ(w.size(), 87u);
  EXPECT_EQ(w.colours, 44u);
  EXPECT_EQ(w.kind, TileKind::Wang);
}

TEST(ColourRelabelling, MakesEachDirectionDense) {
  std::vector<WangTile> w = {{5, 9, 7, 2}, {7, 2, 5, 9}};
  auto r = relabel_wang(w);
  EXPECT_EQ(r[0], (WangTile{0, 1, 1, 0}));
  EXPECT_EQ(r[1], (WangTile{1, 0, 0, 1}));
  EXPECT_EQ(wang_horizontal_colours(r), 2u);
}

TEST(ConvertDispatch, RejectsEmptySetsAndWrongKinds) {
  EXPECT_THROW(convert(TileSet::wang({}), ConversionMethod::Diagonal), InputError);
  EXPECT_THROW(convert(complete_corner_set(2), ConversionMethod::Rotation), InputError);
  EXPECT_THROW(convert(complete_wang_set(2, 2), ConversionMethod::ToWang), InputError);
  EXPECT_THROW(parse_method("diagonally"), InputError);
}

TEST(TranslationLift, FindsARowWithoutLift) {
  // Transducer edges A: 0->1 (a), B: 1->0 (b), C: 2->3 (b), D: 3->2 (c). The pairs ab, ba,
  // bc, cb are each allowed, but no path reads "a b c": the corner row ...abcba... has no lift.
  std::vector<WangTile> w = {{0, 1, 0, 0}, {1, 0, 1, 1}, {1, 3, 1, 2}, {2, 2, 2, 3}};  // n e s w; label (n,s)
  LiftReport r = translation_lift(w, true);
  EXPECT_TRUE(r.decided);
  EXPECT_FALSE(r.lifts);
}

TEST(TranslationLift, AcceptsUniqueLabelsAndDetectsNonInjectiveRows) {
  // Two tiles, labels distinct: every corner row lifts uniquely.
  std::vector<WangTile> w = {{0, 1, 0, 0}, {1, 0, 1, 1}};
  LiftReport ok = translation_lift(w, true);
  EXPECT_TRUE(ok.lifts);
  EXPECT_TRUE(ok.injective);
  // Two loops (states 0 and 1) with the same label: two rows, one label sequence.
  std::vector<WangTile> twin = {{0, 0, 0, 0}, {0, 1, 0, 1}};
  LiftReport tw = translation_lift(twin, true);
  EXPECT_TRUE(tw.lifts);
  EXPECT_FALSE(tw.injective);
}
