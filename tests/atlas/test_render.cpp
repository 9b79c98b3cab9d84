#include <gtest/gtest.h>

#include <set>

#include "atlas/render.hpp"
#include "tests/cli_runner.hpp"
#include "tilesets/compact_sets.hpp"
#include "base/error.hpp"

using namespace tilekit;
using namespace tilekit::atlas;

namespace {

Rgb pixel(const std::vector<Rgb>& img, const Picture& p, int x, int y) {
  return img[std::size_t(y) * std::size_t(p.width()) + std::size_t(x)];
}

}  // namespace

TEST(Palette, FirstFiveColoursAreRedYellowGreenCyanBlue) {
  const Rgb red = palette_colour(0), yellow = palette_colour(1), green = palette_colour(2), cyan = palette_colour(3),
            blue = palette_colour(4);
  EXPECT_TRUE(red.r > 200 && red.g < 80 && red.b < 80);
  EXPECT_TRUE(yellow.r > 200 && yellow.g > 180 && yellow.b < 80);
  EXPECT_TRUE(green.g > 150 && green.r < 100 && green.b < 100);
  EXPECT_TRUE(cyan.g > 180 && cyan.b > 180 && cyan.r < 100);
  EXPECT_TRUE(blue.b > 200 && blue.r < 80 && blue.g < 120);
}

TEST(Palette, First256ColoursAreDistinct) {
  std::set<std::tuple<int, int, int>> seen;
  for (std::uint32_t c = 0; c < 256; ++c) {
    const Rgb v = palette_colour(c);
    seen.insert({v.r, v.g, v.b});
  }
  EXPECT_EQ(seen.size(), 256u);
  EXPECT_EQ(hex(Rgb{255, 0, 16}), "#ff0010");
}

TEST(Render, WangTileIsFourTrianglesOfItsEdgeColours) {
  Tiling t(TileKind::Wang, 5, 1, 1, false);
  t.at(0, 0) = wang_index(WangTile{0, 1, 2, 4}, 5);  // N red, E yellow, S green, W blue
  const Picture p = draw_tiling(t, {40, false});
  const auto img = rasterise(p);
  EXPECT_EQ(pixel(img, p, 20, 3), palette_colour(0));   // near the N edge
  EXPECT_EQ(pixel(img, p, 36, 20), palette_colour(1));  // near the E edge
  EXPECT_EQ(pixel(img, p, 20, 36), palette_colour(2));  // near the S edge
  EXPECT_EQ(pixel(img, p, 3, 20), palette_colour(4));   // near the W edge
}

TEST(Render, CornerTileHasQuarterDiscsAndALightCentre) {
  Tiling t(TileKind::Corner, 4, 1, 1, false);
  t.at(0, 0) = corner_index(CornerTile{0, 1, 2, 3}, 4);  // NE red, SE yellow, SW green, NW cyan
  const Picture p = draw_tiling(t, {40, false});
  const auto img = rasterise(p);
  EXPECT_EQ(pixel(img, p, 37, 2), palette_colour(0));
  EXPECT_EQ(pixel(img, p, 37, 37), palette_colour(1));
  EXPECT_EQ(pixel(img, p, 2, 37), palette_colour(2));
  EXPECT_EQ(pixel(img, p, 2, 2), palette_colour(3));
  EXPECT_EQ(pixel(img, p, 20, 20), kCornerBackground);
}

TEST(Render, BordersAreDrawnOnlyWhenAsked) {
  Tiling t(TileKind::Corner, 2, 2, 2, false);
  const auto plain = rasterise(draw_tiling(t, {24, false}));
  const Picture pb = draw_tiling(t, {24, true});
  const auto framed = rasterise(pb);
  EXPECT_EQ(pixel(framed, pb, 24, 10), kBorder);
  EXPECT_NE(plain[std::size_t(10) * 48 + 24], kBorder);
}

TEST(Render, TileSetLayoutHoldsEveryTileWithGaps) {
  const TileSet s = compact_wang_set(3);
  const Picture p = draw_tile_set(s, {20, true});
  EXPECT_EQ(p.tiles.size(), 18u);
  EXPECT_EQ(p.cols, 5);
  EXPECT_EQ(p.rows, 4);
  EXPECT_GT(p.gap, 0);
  EXPECT_EQ(p.width(), 5 * 20 + 6 * p.gap);
}

TEST(Render, SvgHasOneShapePerTilePartAndPngHasTheRightHeader) {
  Tiling t(TileKind::Wang, 2, 3, 4, false);
  const Picture p = draw_tiling(t, {10, true});
  const std::string svg = to_svg(p);
  std::size_t paths = 0, rects = 0;
  for (std::size_t i = svg.find("<path"); i != std::string::npos; i = svg.find("<path", i + 1)) ++paths;
  for (std::size_t i = svg.find("class=\"bd\""); i != std::string::npos; i = svg.find("class=\"bd\"", i + 1)) ++rects;
  EXPECT_EQ(paths, 4u * 12);
  EXPECT_EQ(rects, 12u);
  EXPECT_NE(svg.find("width=\"40\" height=\"30\""), std::string::npos);
  const std::string png = to_png(p);
  ASSERT_GT(png.size(), 24u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  auto be32 = [&](std::size_t at) {
    return (std::uint32_t(std::uint8_t(png[at])) << 24) | (std::uint32_t(std::uint8_t(png[at + 1])) << 16) |
           (std::uint32_t(std::uint8_t(png[at + 2])) << 8) | std::uint32_t(std::uint8_t(png[at + 3]));
  };
  EXPECT_EQ(be32(16), 40u);  // IHDR width
  EXPECT_EQ(be32(20), 30u);  // IHDR height
}

TEST(Render, WritePictureRejectsUnknownExtensionsAndWritesNothing) {
  test::TempDir d;
  Tiling t(TileKind::Corner, 2, 1, 1, false);
  EXPECT_THROW(write_picture(draw_tiling(t), d / "x.gif"), InputError);
  EXPECT_FALSE(std::filesystem::exists(d / "x.gif"));
  write_picture(draw_tiling(t), d / "x.svg");
  EXPECT_TRUE(std::filesystem::exists(d / "x.svg"));
}

TEST(Render, OversizedPictureIsAnInputError) {
  Tiling t(TileKind::Corner, 2, 10, 4000, false);
  EXPECT_THROW(draw_tiling(t, {32, false}), InputError);
}
