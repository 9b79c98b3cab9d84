// The image library's decoder on files the fuzz harness (fuzz/fuzz_texture_input.cpp) made:
// damaged files decode to the right pixels or are refused with an InputError, never undefined
// behaviour inside stb (the ASan+UBSan suite runs these too).
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "base/error.hpp"
#include "image/image.hpp"
#include "tests/cli_runner.hpp"

using namespace tilekit;

namespace {

Image gradient(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.set(x, y, Rgb{std::uint8_t(x * 7), std::uint8_t(y * 11), std::uint8_t(x ^ y)});
  return img;
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// `png` with a zero-length IDAT chunk put before its first IDAT chunk (CRC of "IDAT" alone).
std::string with_empty_idat_first(const std::string& png) {
  const std::size_t idat = png.find("IDAT");
  EXPECT_NE(idat, std::string::npos);
  const std::string empty("\0\0\0\0IDAT\x35\xaf\x06\x1e", 12);
  return png.substr(0, idat - 4) + empty + png.substr(idat - 4);
}

}  // namespace

TEST(ImageDecode, APngRoundTripsThroughTheDecoder) {
  tilekit::test::TempDir d;
  const Image img = gradient(37, 23);
  write_png(d / "g.png", img);
  const Image back = read_image(d / "g.png");
  ASSERT_EQ(back.width, 37);
  ASSERT_EQ(back.height, 23);
  EXPECT_EQ(back.pixels, img.pixels);
}

// stb copied zero bytes from a null pointer for an empty first IDAT chunk (UBSan, found by
// fuzz_texture_input at 763,416 runs). Empty IDAT chunks carry no data, so the image is the same.
TEST(ImageDecode, AnEmptyFirstIdatChunkDecodesToTheSamePixels) {
  tilekit::test::TempDir d;
  const Image img = gradient(19, 31);
  write_bytes(d / "e.png", with_empty_idat_first(encode_png(img)));
  const Image back = read_image(d / "e.png");
  EXPECT_EQ(back.pixels, img.pixels);
}

TEST(ImageDecode, ATruncatedPngIsAnInputErrorNamingTheFile) {
  tilekit::test::TempDir d;
  const std::string png = encode_png(gradient(40, 40));
  write_bytes(d / "t.png", png.substr(0, png.size() / 2));
  try {
    read_image(d / "t.png");
    FAIL() << "a truncated PNG was decoded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("t.png"), std::string::npos) << e.what();
  }
}

// The same with a damaged chunk after the empty one (its length runs past the file's end): the
// empty chunk is still dropped, and the damaged rest is refused (fuzz_texture_input, 138,304 runs).
TEST(ImageDecode, AnEmptyIdatBeforeADamagedChunkIsRefused) {
  tilekit::test::TempDir d;
  const std::string png = with_empty_idat_first(encode_png(gradient(16, 16)));
  const std::size_t second = png.find("IDAT", png.find("IDAT") + 4) - 4;
  std::string bad = png.substr(0, second) + std::string("\x78\x5e\x7c\x7c", 4) + png.substr(second + 4);
  write_bytes(d / "d.png", bad);
  EXPECT_THROW(read_image(d / "d.png"), InputError);
}
