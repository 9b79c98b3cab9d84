// Round trips for every conjugate construction: a random tiling (patch) of the source maps
// to a valid tiling of the result (independent validator) and back to the same tiling.
#include <gtest/gtest.h>

#include "aperiodic_test_util.hpp"
#include "aperiodic/maps.hpp"
#include "base/error.hpp"
#include "tilesets/tile_set_io.hpp"
#include "tilesets/validator.hpp"

using namespace tilekit;

namespace {

constexpr int kSize = 7;  // odd: the rotation map needs it

Patch source_patch(const TileSet& w, std::uint64_t seed) {
  auto p = test::random_wang_patch(w.wang_tiles(), kSize, kSize, seed);
  if (!p) ADD_FAILURE() << "no random patch of " << w.name();
  return p ? *p : Patch(kSize, kSize);
}

void expect_valid(const TileSet& set, const Patch& p, const std::string& what) {
  ASSERT_EQ(p.holes(), 0u) << what;
  ValidationReport rep = validate(patch_to_tiling(set, p), &set);
  EXPECT_TRUE(rep.valid) << what << ": " << (rep.errors.empty() ? "" : rep.errors[0]);
}

// Source patch -> result patch (valid) -> source patch; returns the back-mapped patch.
Patch round_trip(const TileSet& src, ConversionMethod m, const Patch& p, const SubdivisionOptions& o = {}) {
  Conversion c = convert(src, m, o);
  EXPECT_EQ(c.soundness, Soundness::Conjugate) << method_name(m);
  TileSet result = conversion_tile_set(c, "result", "");
  Patch q = map_forward(src, c, p);
  expect_valid(result, q, src.name() + " " + method_name(m));
  return map_backward(src, c, q);
}

class ConjugateRoundTrip : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(ConjugateRoundTrip, DiagonalTranslationMapsTilingsBothWays) {
  TileSet w = resolve_tile_set(GetParam());
  Patch p = source_patch(w, 11);
  expect_valid(w, p, "source");
  Patch back = round_trip(w, ConversionMethod::Diagonal, p);
  EXPECT_EQ(back.cells, p.cells);
}

TEST_P(ConjugateRoundTrip, RotationMapsTilingsBothWays) {
  TileSet w = resolve_tile_set(GetParam());
  Patch p = source_patch(w, 12);
  Patch back = round_trip(w, ConversionMethod::Rotation, p);
  std::size_t recovered = 0;
  for (std::size_t k = 0; k < p.cells.size(); ++k)
    if (back.cells[k] >= 0) {
      EXPECT_EQ(back.cells[k], p.cells[k]) << "cell " << k;
      ++recovered;
    }
  EXPECT_GE(recovered, std::size_t(kSize * kSize / 2));  // the diamond inside the turned square
}

TEST_P(ConjugateRoundTrip, SubdivisionMapsTilingsBothWays) {
  TileSet w = resolve_tile_set(GetParam());
  Patch p = source_patch(w, 13);
  EXPECT_EQ(round_trip(w, ConversionMethod::Subdivision, p).cells, p.cells);
  EXPECT_EQ(round_trip(w, ConversionMethod::Subdivision, p, {true, false}).cells, p.cells);
}

TEST_P(ConjugateRoundTrip, CornerToWangToCornerPreservesTilings) {
  // A random tiling of a corner set (the diagonal one), read as a Wang tiling of its
  // pair-coloured set (8.4), and back.
  TileSet w = resolve_tile_set(GetParam());
  TileSet corner = conversion_tile_set(convert(w, ConversionMethod::Diagonal), "corner", "");
  Conversion to_wang = convert(corner, ConversionMethod::ToWang);
  TileSet wang = conversion_tile_set(to_wang, "wang", "");
  auto q = test::random_wang_patch(wang.wang_tiles(), 6, 6, 14);
  ASSERT_TRUE(q);
  expect_valid(wang, *q, "Wang form");
  Patch as_corner = map_backward(corner, to_wang, *q);
  expect_valid(corner, as_corner, "corner form");
  EXPECT_EQ(map_forward(corner, to_wang, as_corner).cells, q->cells);
}

INSTANTIATE_TEST_SUITE_P(PublishedSets, ConjugateRoundTrip,
                         ::testing::Values("culik-13", "kari-14", "ammann-gs-16", "jeandel-rao-11"),
                         [](const auto& info) {
                           std::string n = info.param;
                           for (char& ch : n)
                             if (ch == '-') ch = '_';
                           return n;
                         });

TEST(TranslationRoundTrip, VerticalTranslationOfKari14LiftsBackToAValidTiling) {
  // kari-14's vertical translation is conjugate (thesis 86/6): columns lift uniquely.
  TileSet w = resolve_tile_set("kari-14");
  Patch p = source_patch(w, 15);
  Conversion c = convert(w, ConversionMethod::Vertical);
  ASSERT_EQ(c.soundness, Soundness::Conjugate);
  TileSet result = conversion_tile_set(c, "v", "");
  Patch q = map_forward(w, c, p);
  expect_valid(result, q, "vertical");
  Patch back = map_backward(w, c, q);
  expect_valid(w, back, "lifted");
  EXPECT_EQ(map_forward(w, c, back).cells, q.cells);
}

TEST(TranslationRoundTrip, UnverifiedTranslationsHaveNoInverseMap) {
  TileSet w = resolve_tile_set("ammann-gs-16");
  Conversion c = convert(w, ConversionMethod::Horizontal);
  Patch p = source_patch(w, 16);
  Patch q = map_forward(w, c, p);
  EXPECT_EQ(q.holes(), 0u);
  EXPECT_THROW(map_backward(w, c, q), InputError);
}
