// Window tori (de Bruijn tori): the index, the independent validator, the files, the agreement
// with corner packings and the window colour lift.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "base/error.hpp"
#include "tilesets/construct_internal.hpp"
#include "tilesets/constructions.hpp"
#include "tilesets/tile_set.hpp"
#include "tilesets/validator.hpp"
#include "tilesets/window_torus.hpp"

using namespace tilekit;

namespace {

// The (4,4;2,2)_2 torus (every binary 2x2 window once).
const std::vector<Colour> kB2 = {0, 1, 0, 0, 0, 1, 1, 1, 1, 1, 1, 0, 0, 0, 1, 0};

}  // namespace

TEST(WindowTorus, TheIndexReadsTheWindowRowByRowFirstSymbolMostSignificant) {
  const std::vector<Colour> pegs = {1, 0, 0, 2, 1, 0};  // 2 x 3 over 3 symbols
  const Tiling t = window_torus_from_pegs(pegs, 2, 3, 3, 2, 2);
  // window at (0,1): rows (0, 0) over (1, 0) -> digits 0 0 1 0
  EXPECT_EQ(t.at(0, 1), 3u);
  // window at (1,2): (0, 2) over (0, 1) with wrap-around -> 0 2 0 1
  EXPECT_EQ(t.at(1, 2), 0u * 27 + 2 * 9 + 0 * 3 + 1);
  EXPECT_EQ(pegs_of_window_torus(t), pegs);
}

TEST(WindowTorus, ValidatorAcceptsADeBruijnTorusAndRejectsAChangedSymbol) {
  Tiling t = window_torus_from_pegs(kB2, 4, 4, 2, 2, 2);
  ValidationReport ok = validate(t);
  EXPECT_TRUE(ok.valid);
  EXPECT_TRUE(ok.packing);
  std::vector<Colour> flipped = kB2;
  flipped[5] ^= 1;
  ValidationReport rep = validate(window_torus_from_pegs(flipped, 4, 4, 2, 2, 2));
  EXPECT_TRUE(rep.valid);  // still the windows of a colouring
  EXPECT_FALSE(rep.packing);  // but some window twice
  t.at(1, 1) ^= 1;  // a window index that does not overlap its neighbours
  ValidationReport bad = validate(t);
  EXPECT_FALSE(bad.valid);
  ASSERT_FALSE(bad.errors.empty());
  EXPECT_NE(bad.errors.front().find("overlap"), std::string::npos);
}

TEST(WindowTorus, CornerPackingsAreExactlyTheTwoByTwoWindowTori) {
  for (std::uint32_t c : {2u, 3u, 4u, 5u}) {
    const Tiling corner = construct_packing(TileKind::Corner, c)->tiling;
    const Tiling w = window_torus_of_corner_torus(corner);
    EXPECT_TRUE(validate(w, nullptr).packing) << c;
    const TileSet set = complete_window_set(c, 2, 2);
    EXPECT_TRUE(validate(w, &set).packing) << c;
    EXPECT_EQ(corner_torus_of_window_torus(w).cells, corner.cells) << c;
  }
  // and back: a window torus with a repeated window is no corner packing either
  std::vector<Colour> flipped = kB2;
  flipped[0] ^= 1;
  const Tiling w = window_torus_from_pegs(flipped, 4, 4, 2, 2, 2);
  EXPECT_FALSE(validate(w).packing);
  EXPECT_FALSE(validate(corner_torus_of_window_torus(w)).packing);
}

TEST(WindowTorus, StoredToriAreDeBruijnToriOfTheirNames) {
  const auto t33 = stored_window_tori(2, 3, 3);
  ASSERT_EQ(t33.size(), 1u);
  EXPECT_EQ(t33[0].rows, 16);
  EXPECT_EQ(t33[0].cols, 32);
  EXPECT_TRUE(validate(t33[0]).packing);
  EXPECT_EQ(stored_window_tori(2, 2, 3).size(), 2u);  // 8x8 and 16x4
  EXPECT_EQ(stored_window_tori(2, 3, 2).size(), 1u);
  EXPECT_EQ(stored_window_tori(3, 2, 2).size(), 1u);
  EXPECT_TRUE(stored_window_tori(2, 4, 4).empty());
  auto c = construct_window_torus(5, 2, 2, 25, 25);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->how, "corner debruijn-triangular");
  EXPECT_FALSE(construct_window_torus(2, 4, 4, 256, 256));
}

TEST(WindowTorus, FilesRoundTripInCellsAndPegForms) {
  const Tiling t = stored_window_tori(2, 3, 2).front();
  const Tiling cells = tiling_from_json(nlohmann::json::parse(tiling_to_json(t).dump()), "cells");
  EXPECT_EQ(cells.cells, t.cells);
  EXPECT_EQ(cells.window_rows, 3);
  EXPECT_EQ(cells.window_cols, 2);
  const Tiling pegs = tiling_from_json(nlohmann::json::parse(tiling_to_peg_json(t).dump()), "pegs");
  EXPECT_EQ(pegs.cells, t.cells);
  nlohmann::json j = tiling_to_json(t);
  j.erase("window");
  EXPECT_THROW(tiling_from_json(j, "no window"), InputError);
}

TEST(WindowTorus, ShapeChecksNameTheReason) {
  auto message = [](auto f) {
    try {
      f();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message([] { check_window_torus_shape(2, 3, 3, 2, 256); }).find("larger than"), std::string::npos);
  EXPECT_NE(message([] { check_window_torus_shape(2, 3, 3, 16, 16); }).find("rows*cols = 512, not 256"),
            std::string::npos);
  EXPECT_NE(message([] { check_window_torus_shape(2, 0, 3, 1, 8); }).find("K >= 1"), std::string::npos);
  EXPECT_NO_THROW(check_window_torus_shape(4, 3, 3, 512, 512));
}

TEST(WindowTorus, ColourLiftOfTheBinaryTorusByItsLiftQuotientIsAFourSymbolTorus) {
  // The 2x2 case is the corner binary lift (construct_lift.cpp): B = B2 (period 4), E its quotient.
  const Tiling base = window_torus_from_pegs(kB2, 4, 4, 2, 2, 2);
  const Tiling quotient = window_torus_from_pegs(binary_lift_quotient_pegs(4), 16, 16, 2, 2, 2);
  const Tiling a = window_colour_lift(base, quotient);
  EXPECT_EQ(a.colours, 4u);
  EXPECT_TRUE(validate(a).packing);
  // A quotient that is not one per class (the base itself tiled) does not lift to a torus.
  std::vector<Colour> tiled(256);
  for (int r = 0; r < 16; ++r)
    for (int c = 0; c < 16; ++c) tiled[std::size_t(r * 16 + c)] = kB2[std::size_t((r % 4) * 4 + c % 4)];
  EXPECT_FALSE(validate(window_colour_lift(base, window_torus_from_pegs(tiled, 16, 16, 2, 2, 2))).packing);
}
