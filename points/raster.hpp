#pragma once
// RGB images for the pictures of points/ (point sets, spectra, plots, zone plates): pixels,
// lines, discs and a 5x7 bitmap font for plot labels. Encoding to PNG happens in the CLI
// (atlas/ writes PNG files); points/ only draws.
#include <cstdint>
#include <string>
#include <vector>

namespace tilekit::points {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
};

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, row 0 at the top

  Image() = default;
  Image(int w, int h, Rgb fill = {255, 255, 255});
  void set(int x, int y, Rgb c) {
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    std::uint8_t* p = &rgb[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3];
    p[0] = c.r, p[1] = c.g, p[2] = c.b;
  }
  Rgb get(int x, int y) const {
    const std::uint8_t* p = &rgb[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3];
    return {p[0], p[1], p[2]};
  }
  void line(double x0, double y0, double x1, double y1, Rgb c, int thickness = 1);
  void disc(double cx, double cy, double radius, Rgb c);
  void rect(int x0, int y0, int x1, int y1, Rgb c);  // filled, inclusive
  // Text in the 5x7 font (capitals, digits, . - + / = ( ) , : _ %), `scale` pixels per font pixel.
  // Returns the width drawn.
  int text(int x, int y, const std::string& s, Rgb c, int scale = 1);
  static int text_width(const std::string& s, int scale = 1) { return int(s.size()) * 6 * scale; }
  // This image scaled down by an integer factor (box filter).
  Image downsampled(int factor) const;
};

}  // namespace tilekit::points
