// TIFF (libtiff) and OpenEXR input, OpenEXR output: 16-bit and float samples read as stored, in
// every layout libtiff writes (strips, tiles, planes, compression), half-float OpenEXR widened to
// float, and damaged files refused with one InputError line and nothing on stderr.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <gtest/gtest.h>
#include <half.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "image/image.hpp"
#include "tests/cli_runner.hpp"
#include "tiff_writer.hpp"

using namespace tilekit;

namespace {

// A 16-bit ramp over every channel (distinct values, all 16 bits used), alpha not opaque.
Image ramp_image(int w, int h, int channels, int depth) {
  Image img = Image(w, h).to_depth(depth);
  if (channels == 1) img = Image::grey(w, h).to_depth(depth);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c) {
        const double i = double((y * w + x) * channels + c);
        img.set_value(x, y, c, depth == 32 ? -3.5 + i * 0.25 : double(unsigned(i * 977) % (img.max_value() + 1u)));
      }
  return img;
}

void write_file_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}
std::string read_file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(TiffInput, SixteenBitSamplesReadAsStoredInEveryLayout) {
  test::TempDir d;
  const std::string path = d / "ramp.tif";
  for (const test::TiffLayout layout : {test::TiffLayout{}, test::TiffLayout{true, false, 8, 4},
                                        test::TiffLayout{false, true, 5, 4}, test::TiffLayout{true, true, 1, 3}}) {
    for (int channels : {1, 4}) {
      const Image ramp = ramp_image(37, 21, channels, 16);  // not a multiple of the tiles
      test::write_tiff(path, ramp, layout);
      const Image back = read_image(path, channels, true);
      ASSERT_EQ(back.depth, 16);
      ASSERT_EQ(back.channels, channels);
      const bool opaque = channels == 4 && layout.colour_channels == 3;
      for (int y = 0; y < 21; ++y)
        for (int x = 0; x < 37; ++x)
          for (int c = 0; c < channels; ++c)
            ASSERT_EQ(back.sample(x, y, c), opaque && c == 3 ? 65535u : ramp.sample(x, y, c))
                << "tiled " << layout.tiled << " planar " << layout.planar << " texel " << x << "," << y << " c" << c;
      // Without keep_depth: 8 bits, rounded as to_depth rounds.
      const Image eight = read_image(path, channels);
      EXPECT_EQ(eight.depth, 8);
      EXPECT_EQ(eight.sample(5, 3, 0), back.to_depth(8).sample(5, 3, 0));
    }
  }
  // An RGB TIFF read as grey: the luminance stb_image would give at this depth.
  Image rgb = ramp_image(8, 8, 4, 16);
  test::write_tiff(path, rgb);
  const Image grey = read_image(path, 1, true);
  EXPECT_EQ(grey.sample(3, 2, 0),
            (77 * rgb.sample(3, 2, 0) + 150 * rgb.sample(3, 2, 1) + 29 * rgb.sample(3, 2, 2)) / 256);
}

TEST(TiffInput, EightBitAndFloatSamplesReadAsStored) {
  test::TempDir d;
  const Image eight = ramp_image(20, 9, 4, 8);
  test::write_tiff(d / "e.tif", eight, {false, false, 5, 4});
  EXPECT_EQ(read_image(d / "e.tif", 4, true).pixels, eight.pixels);
  const Image heights = ramp_image(20, 9, 1, 32);  // -3.5, -3.25, ...: outside 0..1
  test::write_tiff(d / "f.tif", heights, {true, false, 8, 3});
  const Image f = read_image(d / "f.tif", 1, true);
  ASSERT_EQ(f.depth, 32);
  EXPECT_EQ(f.pixels, heights.pixels);  // bit for bit
  const Image rgba = read_image(d / "f.tif", 4, true);
  EXPECT_EQ(rgba.value(7, 4, 1), heights.value(7, 4, 0));
  EXPECT_EQ(rgba.value(7, 4, 3), 1.0);
  EXPECT_EQ(read_image(d / "f.tif").depth, 8);  // clamped to 0..1, then 8 bits
}

TEST(ExrInput, FloatRoundTripsBitForBitAndHalfWidensToFloat) {
  test::TempDir d;
  for (int channels : {1, 4}) {
    const Image img = ramp_image(33, 17, channels, 32);
    write_exr(d / "f.exr", img);
    const Image back = read_image(d / "f.exr", channels, true);
    ASSERT_EQ(back.depth, 32);
    EXPECT_EQ(back.pixels, img.pixels);
  }
  // Half-float Y (a height map as many tools write it), with a data window off the origin.
  {
    Imf::Header h(Imath::Box2i({0, 0}, {9, 4}), Imath::Box2i({3, -2}, {9, 4}));
    h.channels().insert("Y", Imf::Channel(Imf::HALF));
    std::vector<half> ys(7 * 7);
    for (std::size_t i = 0; i < ys.size(); ++i) ys[i] = half(1200.25f - float(i) * 0.5f);
    Imf::OutputFile out((d / "h.exr").c_str(), h);
    Imf::FrameBuffer fb;
    fb.insert("Y", Imf::Slice::Make(Imf::HALF, ys.data(), h.dataWindow(), sizeof(half), 7 * sizeof(half)));
    out.setFrameBuffer(fb);
    out.writePixels(7);
  }
  const Image y = read_image(d / "h.exr", 4, true);
  ASSERT_EQ(y.width, 7);
  ASSERT_EQ(y.height, 7);
  EXPECT_EQ(y.value(0, 0, 0), 1200.0);  // half holds 1200.25 as 1200
  EXPECT_EQ(y.value(2, 1, 2), double(float(half(1200.25f - 9 * 0.5f))));
  EXPECT_EQ(y.value(2, 1, 3), 1.0);
}

// Damaged TIFF and OpenEXR files: an InputError of one line naming the file, nothing on stderr
// (libtiff's default handlers print there), never a crash (the sanitizer suites run this too).
TEST(TiffExrInput, DamagedFilesAreOneLineErrorsAndStderrStaysQuiet) {
  test::TempDir d;
  test::write_tiff(d / "ok.tif", ramp_image(40, 40, 4, 16), {true, false, 8, 4});
  write_exr(d / "ok.exr", ramp_image(40, 40, 4, 32));
  const std::string tif = read_file_bytes(d / "ok.tif"), exr = read_file_bytes(d / "ok.exr");
  std::vector<std::pair<std::string, std::string>> bad = {
      {"short.tif", tif.substr(0, 8)},
      {"cut.tif", tif.substr(0, tif.size() / 2)},
      {"noise.tif", std::string("II*\0", 4) + std::string(200, '\x5a')},
      {"short.exr", exr.substr(0, 8)},
      {"cut.exr", exr.substr(0, exr.size() * 2 / 3)},
      {"noise.exr", std::string("\x76\x2f\x31\x01", 4) + std::string(200, '\x5a')},
  };
  // A TIFF whose directory claims 10000 x 10000 texels from a few kilobytes (at most 1024 a byte).
  std::string huge = tif;
  for (std::size_t i = 8; i + 12 < huge.size(); ++i)
    if ((huge[i] == '\x00' || huge[i] == '\x01') && huge[i + 1] == '\x01' && huge[i + 2] == '\x03' &&
        huge[i + 3] == 0 && huge[i + 4] == 1 && huge[i + 5] == 0) {
      huge[i + 8] = char(0x10), huge[i + 9] = char(0x27);  // 10000 (the entry's SHORT value)
    }
  ASSERT_NE(huge, tif);
  bad.push_back({"huge.tif", huge});
  for (const auto& [name, bytes] : bad) {
    write_file_bytes(d / name, bytes);
    for (int channels : {4, 1}) {
      testing::internal::CaptureStderr();
      try {
        read_image(d / name, channels, true);
        ADD_FAILURE() << name << " was read";
      } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        EXPECT_NE(what.find(name), std::string::npos) << what;
      }
      EXPECT_EQ(testing::internal::GetCapturedStderr(), "") << name;
    }
  }
}

}  // namespace
