#pragma once
// The one image type of Tilekit: 8-bit (or 16-bit: `depth`) pixels with 1 (grey) or 4 (RGBA)
// channels, row-major, row 0 at the top, column 0 at the left. Decoding (PNG, JPEG and whatever else stb_image reads)
// and PNG encoding happen here and nowhere else; drawing (lines, discs, text for plots) is in
// image/draw.cpp.
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
  // Bits per channel: 8, or 16 (two bytes per channel in the machine's byte order; read them with
  // sample/set_sample). Only image/, the mip chains and the copies of tiles and atlases handle
  // 16-bit images; everything else takes `to_depth(8)`.
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
  int max_value() const { return depth == 16 ? 65535 : 255; }
  // Channel c of texel (x, y), 0..max_value(), at either depth.
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
  // The same picture at 8 or 16 bits (8 -> 16 multiplies by 257, 16 -> 8 rounds).
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
// missing, cannot be decoded, or would decode to more than kMaxImagePixels. A 16-bit PNG is
// rounded to 8 bits unless keep_16 (then depth 16).
Image read_image(const std::string& path, int channels = 4, bool keep_16 = false);

// The PNG encoding of `img` with the fewest channels that hold it exactly (grey, RGB, +alpha);
// a 16-bit image as a 16-bit PNG (libpng).
std::string encode_png(const Image& img);
// encode_png written atomically (temp file, fsync, rename). Throws InputError on failure.
void write_png(const std::string& path, const Image& img);

}  // namespace tilekit
