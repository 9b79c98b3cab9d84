// Colour-quotient lifts: the lift theorem against the independent validator, the
// binary lift construction, and corner packings for every C from 2 to 32 without search.
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <set>

#include "base/error.hpp"
#include "base/random.hpp"
#include "tilesets/construct_internal.hpp"
#include "tilesets/constructions.hpp"
#include "tilesets/validator.hpp"

using namespace tilekit;

namespace {

// The lift condition checked directly: every k-colour tile once on each residue class mod P.
bool each_class_holds_every_tile_once(const Tiling& q, int period) {
  const std::size_t tiles = complete_size(q.ch(), q.cv());
  std::vector<char> seen(std::size_t(period) * std::size_t(period) * tiles, 0);
  for (int r = 0; r < q.rows; ++r)
    for (int c = 0; c < q.cols; ++c) {
      char& s = seen[(std::size_t((r % period) * period + c % period)) * tiles + q.at(r, c)];
      if (s) return false;
      s = 1;
    }
  return true;
}

Tiling binary_quotient(int period) {
  const int n = 4 * period;
  return corner_torus_from_pegs(binary_lift_quotient_pegs(std::uint64_t(period)), n, n, 2);
}

}  // namespace

TEST(BinaryLift, FourByFourTorusSeparatesBothRowPairFamilies) { EXPECT_TRUE(binary_lift_torus_ok()); }

TEST(BinaryLift, QuotientHoldsEveryBinaryWindowOncePerClass) {
  for (int period : {2, 4, 16, 64}) EXPECT_TRUE(each_class_holds_every_tile_once(binary_quotient(period), period)) << period;
}

TEST(BinaryLift, LiftOfTheStoredTwoColourPackingIsAFourColourPacking) {
  // Independent of the stored C=4 packing: stored C=2 (B) + 2 * quotient of period 4.
  Tiling a = colour_lift(*stored_packing(TileKind::Corner, 2), binary_quotient(4));
  EXPECT_EQ(a.colours, 4u);
  EXPECT_EQ(a.rows, 16);
  ValidationReport rep = validate(a);
  EXPECT_TRUE(rep.packing) << (rep.errors.empty() ? "" : rep.errors[0]);
}

TEST(ColourLift, IsAPackingExactlyWhenEveryClassHoldsEveryTileOnce) {
  // The lift theorem (construct_lift.cpp) against the validator: random perturbations of a
  // quotient give a packing exactly when the per-class condition holds.
  const Tiling base = *stored_packing(TileKind::Corner, 2);
  const int period = 4, n = 16;
  std::vector<Colour> good = binary_lift_quotient_pegs(period);
  SplitMix64 rng(11);
  int packings = 0, others = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<Colour> pegs = good;
    const int flips = trial % 3;  // 0 flips: the construction itself
    for (int f = 0; f < flips; ++f) pegs[rng.next() % pegs.size()] ^= 1;
    if (trial % 7 == 6) std::swap(pegs[rng.next() % pegs.size()], pegs[rng.next() % pegs.size()]);
    Tiling q = corner_torus_from_pegs(pegs, n, n, 2);
    const bool lifted = validate(colour_lift(base, q)).packing;
    ASSERT_EQ(lifted, each_class_holds_every_tile_once(q, period)) << "trial " << trial;
    (lifted ? packings : others) += 1;
  }
  EXPECT_GE(packings, 86);  // the 86 unperturbed trials at least
  EXPECT_GE(others, 100);
}

TEST(ColourLift, RejectsMismatchedKindsAndSizes) {
  const Tiling base = *stored_packing(TileKind::Corner, 2);
  EXPECT_THROW(colour_lift(base, Tiling(TileKind::Corner, 2, 10, 10, true)), InputError);
  EXPECT_THROW(colour_lift(base, Tiling(TileKind::Wang, 2, 16, 16, true)), InputError);
}

TEST(Constructions, EveryCornerColourCountFromTwoToThirtyTwoIsConstructible) {
  std::vector<std::uint32_t> all(32);
  for (std::uint32_t c = 1; c <= 32; ++c) all[c - 1] = c;
  EXPECT_EQ(constructible_colours(TileKind::Corner, 32), all);
}

TEST(BinaryLift, ChainFromTheTwoColourPackingReachesThirtyTwoColours) {
  // Independent of the stored C=4..32 packings (found by search): 2 -> 4 -> 8 -> 16 -> 32.
  Tiling a = *stored_packing(TileKind::Corner, 2);
  for (std::uint32_t c = 4; c <= 32; c *= 2) {
    a = colour_lift(a, binary_quotient(a.rows));
    ASSERT_EQ(a.colours, c);
    ValidationReport rep = validate(a);
    EXPECT_TRUE(rep.packing) << "C=" << c << ": " << (rep.errors.empty() ? "" : rep.errors[0]);
  }
}

TEST(BinaryLift, PositionFindsTheCellOfEveryWindowInItsClass) {
  for (int period : {4, 16}) {
    const Tiling q = binary_quotient(period);
    for (int r = 0; r < q.rows; ++r)
      for (int c = 0; c < q.cols; ++c)
        ASSERT_EQ(binary_lift_position(std::uint64_t(period), {r % period, c % period}, q.at(r, c)), std::make_pair(r, c));
  }
}

TEST(Constructions, PowersOfTwoUpToThirtyTwoAreValidPackings) {
  for (std::uint32_t c : {8u, 16u, 32u}) {
    auto p = construct_packing(TileKind::Corner, c);
    ASSERT_TRUE(p) << c;
    ASSERT_EQ(p->tiling.rows, int(c * c));
    ValidationReport rep = validate(p->tiling);
    EXPECT_TRUE(rep.packing) << "corner C=" << c << ": " << (rep.errors.empty() ? "" : rep.errors[0]);
  }
}

TEST(Constructions, StoredAndProductPositionsAgreeWithThePacking) {
  for (std::uint32_t c : {8u, 16u, 24u}) {
    const Tiling t = construct_packing(TileKind::Corner, c)->tiling;
    for (int r = 0; r < t.rows; ++r)
      for (int col = 0; col < t.cols; ++col)
        ASSERT_EQ(packing_position(TileKind::Corner, c, t.at(r, col)), std::make_pair(r, col)) << "C=" << c;
  }
}

TEST(Constructions, SearchFoundPackingsAreStoredInThePegForm) {
  for (std::uint32_t c : {8u, 16u, 32u}) {
    auto s = stored_packing(TileKind::Corner, c);
    ASSERT_TRUE(s) << "tilesets/data/packing-corner-" << c << ".json (scripts/stored-packings.sh) is missing";
    EXPECT_TRUE(validate(*s).packing) << c;
    EXPECT_EQ(construct_packing(TileKind::Corner, c)->how, "stored");
  }
}

TEST(TilingFile, PegFormRoundTripsAndRejectsBadDigits) {
  const Tiling t = construct_packing(TileKind::Corner, 12)->tiling;
  const nlohmann::json j = tiling_to_peg_json(t);
  EXPECT_FALSE(j.contains("cells"));
  EXPECT_EQ(j["pegs"].size(), 144u);
  EXPECT_EQ(tiling_from_json(j, "pegs").cells, t.cells);
  nlohmann::json bad = j;
  bad["pegs"][3] = std::string(144, 'c');  // colour 12 is not below 12
  EXPECT_THROW(tiling_from_json(bad, "bad"), InputError);
  Tiling broken = t;
  broken.at(0, 0) = 0;  // no longer the window grid of a peg colouring
  EXPECT_THROW(tiling_to_peg_json(broken), InputError);
}
