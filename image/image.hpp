#pragma once
// The one image type of Tilekit: 8-bit (or 16-bit, or 32-bit float: `depth`) pixels with 1 (grey)
// or 4 (RGBA) channels, row-major, row 0 at the top, column 0 at the left. Decoding (PNG, JPEG and
// whatever else stb_image reads; TIFF through libtiff, OpenEXR through the OpenEXR library) and PNG
// and OpenEXR encoding happen here and nowhere else; drawing (lines, discs, text for plots) is in
// image/draw.cpp.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace tilekit {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb&, const Rgb&) = default;
};

// Decoded images larger than this are refused before they are decoded (about 1 GiB of RGBA).
inline constexpr std::int64_t kMaxImagePixels = std::int64_t(1) << 28;

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // width * height * channels * depth / 8 bytes
  int channels = 4;                  // 4: RGBA; 1: grey
  // Bits per channel: 8, 16 (two bytes per channel in the machine's byte order; read them with
  // sample/set_sample) or 32 (IEEE 754 single-precision floats of any range, such as heights in
  // metres or HDR colour: OpenEXR and float TIFF data; read them with value/set_value). Only
  // image/, the mip chains and the copies of tiles and atlases handle 16-bit and float images;
  // everything else takes `to_depth(8)`.
  int depth = 8;

  Image() = default;
  Image(int w, int h, std::vector<std::uint8_t> px, int ch = 4)
      : width(w), height(h), pixels(std::move(px)), channels(ch) {}
  // An opaque RGBA image filled with one colour.
  Image(int w, int h, Rgb fill = {255, 255, 255});
  // A grey image of `w` x `h` zeros.
  static Image grey(int w, int h) { return Image(w, h, std::vector<std::uint8_t>(std::size_t(w) * std::size_t(h)), 1); }

  std::uint8_t* at(int x, int y) { return &pixels[offset(x, y)]; }
  const std::uint8_t* at(int x, int y) const { return &pixels[offset(x, y)]; }
  std::size_t offset(int x, int y) const {
    return (std::size_t(y) * std::size_t(width) + std::size_t(x)) * std::size_t(texel_bytes());
  }
  int texel_bytes() const { return channels * (depth / 8); }
  bool is_float() const { return depth == 32; }
  // The sample that means 1 (full intensity): 255, 65535, or 1.0 for float.
  int max_value() const { return depth == 16 ? 65535 : depth == 32 ? 1 : 255; }
  // Channel c of texel (x, y), 0..max_value(), at 8 or 16 bits (not float: see value).
  unsigned sample(int x, int y, int c) const {
    const std::uint8_t* p = at(x, y);
    if (depth == 8) return p[c];
    std::uint16_t v;
    std::memcpy(&v, p + 2 * c, 2);
    return v;
  }
  void set_sample(int x, int y, int c, unsigned v) {
    std::uint8_t* p = at(x, y);
    if (depth == 8) {
      p[c] = std::uint8_t(v);
      return;
    }
    const auto w = std::uint16_t(v);
    std::memcpy(p + 2 * c, &w, 2);
  }
  // Channel c of texel (x, y) as a number at any depth: the sample (0..max_value()) at 8 or 16
  // bits, the float itself at 32.
  double value(int x, int y, int c) const {
    if (depth != 32) return sample(x, y, c);
    float f;
    std::memcpy(&f, at(x, y) + 4 * c, 4);
    return f;
  }
  // Stores v: at 8 or 16 bits rounded and clamped to 0..max_value() (NaN as 0), at 32 as a float.
  void set_value(int x, int y, int c, double v) {
    if (depth == 32) {
      const float f = float(v);
      std::memcpy(at(x, y) + 4 * c, &f, 4);
      return;
    }
    set_sample(x, y, c, unsigned(std::lround(v > 0 ? std::min(v, double(max_value())) : 0.0)));
  }
  // The same picture at 8, 16 or 32 bits (8 -> 16 multiplies by 257, 16 -> 8 rounds; to float
  // divides by max_value(), from float clamps to 0..1 first).
  Image to_depth(int bits) const;

  // Drawing on RGBA images (image/draw.cpp); pixels outside the image are skipped.
  void set(int x, int y, Rgb c) {
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    std::uint8_t* p = at(x, y);
    p[0] = c.r, p[1] = c.g, p[2] = c.b, p[3] = 255;
  }
  Rgb get(int x, int y) const {
    const std::uint8_t* p = at(x, y);
    return {p[0], p[1], p[2]};
  }
  void line(double x0, double y0, double x1, double y1, Rgb c, int thickness = 1);
  void disc(double cx, double cy, double radius, Rgb c);
  void rect(int x0, int y0, int x1, int y1, Rgb c);  // filled, inclusive
  // Text in a 5x7 font (capitals, digits, . - + / = ( ) , : _ %), `scale` pixels per font
  // pixel. Returns the width drawn.
  int text(int x, int y, const std::string& s, Rgb c, int scale = 1);
  static int text_width(const std::string& s, int scale = 1) { return int(s.size()) * 6 * scale; }
  // This image scaled down by an integer factor (box filter, every channel).
  Image downsampled(int factor) const;
};

// An image file as `channels` (4: RGBA, 1: grey) channels. InputError naming the file when it is
// missing, cannot be decoded, or would decode to more than kMaxImagePixels. A 16-bit PNG or TIFF
// and a float TIFF or OpenEXR image are rounded to 8 bits unless keep_depth (then depth 16, or 32
// for float: OpenEXR's half and uint channels become float too).
Image read_image(const std::string& path, int channels = 4, bool keep_depth = false);

// The PNG encoding of `img` with the fewest channels that hold it exactly (grey, RGB, +alpha);
// a 16-bit image as a 16-bit PNG (libpng).
std::string encode_png(const Image& img);
// encode_png written atomically (temp file, fsync, rename). Throws InputError on failure.
void write_png(const std::string& path, const Image& img);
// The OpenEXR encoding of a float image (depth 32; 1 channel as Y, 4 as R, G, B, A; 32-bit float
// channels, lossless ZIP compression): what float tiles and atlases are written as.
std::string encode_exr(const Image& img);
void write_exr(const std::string& path, const Image& img);
// Whatever holds the image exactly: PNG at 8 or 16 bits, OpenEXR for float; and its extension.
std::string encode_image(const Image& img);
inline const char* image_extension(const Image& img) {
  return img.depth == 32 ? ".exr" : ".png";
}

}  // namespace tilekit
