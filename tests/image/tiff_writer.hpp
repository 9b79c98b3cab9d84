#pragma once
// TIFF files for the tests, written by libtiff itself (Tilekit reads TIFF but writes none): grey,
// RGB or RGBA at 8 or 16 bits or 32-bit float, in strips or tiles, samples together or in planes,
// compressed or not. Tests that include it link TIFF::TIFF (tests/CMakeLists.txt).
#include <tiffio.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "image/image.hpp"

namespace tilekit::test {

struct TiffLayout {
  bool tiled = false;       // 16x16 tiles, else strips of 4 rows
  bool planar = false;      // one plane per sample (PLANARCONFIG_SEPARATE)
  int compression = 1;      // COMPRESSION_NONE; 5 LZW, 8 Adobe deflate
  int colour_channels = 3;  // of an RGBA image: 3 (RGB, alpha dropped) or 4 (RGBA)
};

// `img` (1 channel: grey; 4: RGB or RGBA by layout) as a TIFF at img.depth bits.
inline void write_tiff(const std::string& path, const Image& img, const TiffLayout& l = {}) {
  TIFF* t = TIFFOpen(path.c_str(), "w");
  if (!t) throw std::runtime_error("cannot write " + path);
  const int spp = img.channels == 1 ? 1 : l.colour_channels;
  const int bb = img.depth / 8;
  TIFFSetField(t, TIFFTAG_IMAGEWIDTH, std::uint32_t(img.width));
  TIFFSetField(t, TIFFTAG_IMAGELENGTH, std::uint32_t(img.height));
  TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, std::uint16_t(img.depth));
  TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, std::uint16_t(spp));
  TIFFSetField(t, TIFFTAG_SAMPLEFORMAT, std::uint16_t(img.is_float() ? SAMPLEFORMAT_IEEEFP : SAMPLEFORMAT_UINT));
  TIFFSetField(t, TIFFTAG_PHOTOMETRIC, std::uint16_t(spp == 1 ? PHOTOMETRIC_MINISBLACK : PHOTOMETRIC_RGB));
  TIFFSetField(t, TIFFTAG_PLANARCONFIG, std::uint16_t(l.planar ? PLANARCONFIG_SEPARATE : PLANARCONFIG_CONTIG));
  TIFFSetField(t, TIFFTAG_COMPRESSION, std::uint16_t(l.compression));
  if (spp == 4) {
    const std::uint16_t extra[1] = {EXTRASAMPLE_UNASSALPHA};
    TIFFSetField(t, TIFFTAG_EXTRASAMPLES, std::uint16_t(1), extra);
  }
  if (l.tiled) {
    TIFFSetField(t, TIFFTAG_TILEWIDTH, std::uint32_t(16));
    TIFFSetField(t, TIFFTAG_TILELENGTH, std::uint32_t(16));
  } else {
    TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, std::uint32_t(4));
  }
  const int planes = l.planar ? spp : 1, per_plane = l.planar ? 1 : spp;
  const auto put = [&](std::uint8_t* to, int x, int y, int p) {
    for (int s = 0; s < per_plane; ++s)
      std::memcpy(to + std::size_t(s) * bb, img.at(x, y) + std::size_t(l.planar ? p : s) * bb, bb);
  };
  bool ok = true;
  for (int p = 0; p < planes; ++p) {
    if (l.tiled) {
      std::vector<std::uint8_t> buf(std::size_t(TIFFTileSize(t)));
      for (int ty = 0; ty < img.height; ty += 16)
        for (int tx = 0; tx < img.width; tx += 16) {
          std::fill(buf.begin(), buf.end(), 0);
          for (int y = 0; y < 16 && ty + y < img.height; ++y)
            for (int x = 0; x < 16 && tx + x < img.width; ++x)
              put(&buf[(std::size_t(y) * 16 + std::size_t(x)) * std::size_t(per_plane * bb)], tx + x, ty + y, p);
          ok = ok && TIFFWriteTile(t, buf.data(), std::uint32_t(tx), std::uint32_t(ty), 0, std::uint16_t(p)) >= 0;
        }
    } else {
      std::vector<std::uint8_t> row(std::size_t(img.width) * std::size_t(per_plane * bb));
      for (int y = 0; y < img.height; ++y) {
        for (int x = 0; x < img.width; ++x) put(&row[std::size_t(x) * std::size_t(per_plane * bb)], x, y, p);
        ok = ok && TIFFWriteScanline(t, row.data(), std::uint32_t(y), std::uint16_t(p)) >= 0;
      }
    }
  }
  TIFFClose(t);
  if (!ok) throw std::runtime_error("libtiff could not write " + path);
}

}  // namespace tilekit::test
