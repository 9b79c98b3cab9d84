// TIFF through libtiff (Debian libtiff-dev): the file is read from memory (read_image has read it
// whole through read_input_file), libtiff's errors and warnings go to this reader's handlers (per
// file, libtiff 4.5's TIFFOpenOptions: nothing reaches stderr, no global state), and its single
// allocations are capped. Grey and RGB images of 8 or 16 bits unsigned or 32-bit float are read
// as stored, strips or tiles, samples together or in planes; every other kind libtiff reads
// (palette, CMYK, YCbCr, 1-bit, ...) through its RGBA reader, at 8 bits. Samples read as stored
// are taken rows from the top as stored: an Orientation tag other than top-left is not applied.
#include <fmt/format.h>
#include <tiffio.h>

#include <algorithm>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "base/error.hpp"
#include "image/codecs.hpp"

namespace tilekit::image_codecs {

namespace {

struct MemoryFile {
  std::string_view bytes;
  std::uint64_t at = 0;
  std::string error;  // libtiff's first error message
};

tmsize_t read_proc(thandle_t h, void* buf, tmsize_t n) {
  auto* f = static_cast<MemoryFile*>(h);
  if (n <= 0 || f->at >= f->bytes.size()) return 0;
  const std::uint64_t count = std::min<std::uint64_t>(std::uint64_t(n), f->bytes.size() - f->at);
  std::memcpy(buf, f->bytes.data() + f->at, std::size_t(count));
  f->at += count;
  return tmsize_t(count);
}
tmsize_t write_proc(thandle_t, void*, tmsize_t) {
  return 0;  // read only
}
toff_t seek_proc(thandle_t h, toff_t off, int whence) {
  auto* f = static_cast<MemoryFile*>(h);
  const std::uint64_t base = whence == SEEK_CUR ? f->at : whence == SEEK_END ? f->bytes.size() : 0;
  if (off > UINT64_MAX - base) return toff_t(-1);
  f->at = base + off;  // past the end is allowed; reads there return nothing
  return f->at;
}
int close_proc(thandle_t) {
  return 0;
}
toff_t size_proc(thandle_t h) {
  return static_cast<MemoryFile*>(h)->bytes.size();
}
int map_proc(thandle_t, void**, toff_t*) {
  return 0;  // no memory mapping: libtiff reads through read_proc
}
void unmap_proc(thandle_t, void*, toff_t) {}

int on_error(TIFF*, void* user, const char* module, const char* format, va_list ap) {
  auto* f = static_cast<MemoryFile*>(user);
  if (f->error.empty()) {
    char text[512];
    std::vsnprintf(text, sizeof text, format, ap);
    f->error = module && *module ? fmt::format("{}: {}", module, text) : std::string(text);
  }
  return 1;  // handled: libtiff's global handler (stderr) is not called
}
int on_warning(TIFF*, void*, const char*, const char*, va_list) {
  return 1;  // warnings (unknown tags, ...) are dropped
}

struct CloseTiff {
  void operator()(TIFF* t) const { TIFFClose(t); }
};

template <typename T>
T field(TIFF* tif, ttag_t tag, T fallback) {
  T v = fallback;
  return TIFFGetFieldDefaulted(tif, tag, &v) == 1 ? v : fallback;
}

}  // namespace

bool is_tiff(std::string_view file) {
  return file.starts_with(std::string_view("II*\0", 4)) || file.starts_with(std::string_view("MM\0*", 4));
}

Image decode_tiff(const std::string& path, std::string_view file, int channels, bool keep_depth) {
  MemoryFile mf;
  mf.bytes = file;
  const auto fail = [&](std::string_view what) -> InputError {
    return InputError(fmt::format("{}: cannot read the TIFF ({}{})", path, what,
                                  mf.error.empty() ? "" : fmt::format(": {}", mf.error)));
  };
  TIFFOpenOptions* opts = TIFFOpenOptionsAlloc();
  if (!opts) throw fail("out of memory");
  TIFFOpenOptionsSetErrorHandlerExtR(opts, on_error, &mf);
  TIFFOpenOptionsSetWarningHandlerExtR(opts, on_warning, &mf);
  TIFFOpenOptionsSetMaxSingleMemAlloc(opts, tmsize_t(512) << 20);
  std::unique_ptr<TIFF, CloseTiff> tif(TIFFClientOpenExt(path.c_str(), "rm", &mf, read_proc, write_proc, seek_proc,
                                                         close_proc, size_proc, map_proc, unmap_proc, opts));
  TIFFOpenOptionsFree(opts);
  if (!tif) throw fail("damaged or not a TIFF");
  TIFF* t = tif.get();
  std::uint32_t w = 0, h = 0;
  if (TIFFGetField(t, TIFFTAG_IMAGEWIDTH, &w) != 1 || TIFFGetField(t, TIFFTAG_IMAGELENGTH, &h) != 1 || w == 0 || h == 0)
    throw fail("no image size");
  check_decoded_size(path, file.size(), w, h);
  const auto bits = field<std::uint16_t>(t, TIFFTAG_BITSPERSAMPLE, 1);
  const auto spp = field<std::uint16_t>(t, TIFFTAG_SAMPLESPERPIXEL, 1);
  const auto format = field<std::uint16_t>(t, TIFFTAG_SAMPLEFORMAT, SAMPLEFORMAT_UINT);
  const auto planar = field<std::uint16_t>(t, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
  std::uint16_t photometric = 0;
  if (TIFFGetField(t, TIFFTAG_PHOTOMETRIC, &photometric) != 1) photometric = spp >= 3 ? PHOTOMETRIC_RGB : 1;
  const bool as_stored =
      ((bits == 8 || bits == 16) && format == SAMPLEFORMAT_UINT) || (bits == 32 && format == SAMPLEFORMAT_IEEEFP);
  const bool grey = photometric == PHOTOMETRIC_MINISBLACK && spp >= 1;
  const bool rgb = photometric == PHOTOMETRIC_RGB && spp >= 3;
  if (format == SAMPLEFORMAT_IEEEFP && !(as_stored && (grey || rgb)))
    throw fail(
        fmt::format("{}-bit float samples, photometric {}: only 32-bit float grey or RGB is read", bits, photometric));
  if (as_stored && (grey || rgb)) {
    const int keep = grey ? std::min<int>(spp, 2) : std::min<int>(spp, 4);  // grey(+alpha), RGB(+alpha)
    const std::size_t bb = bits / 8;
    const int planes = planar == PLANARCONFIG_SEPARATE ? spp : 1, per_plane = planes == 1 ? spp : 1;
    std::vector<std::uint8_t> raw(std::size_t(w) * h * std::size_t(keep) * bb);
    // Samples s..s+per_plane of one buffer's texel i into texel (x, y) of raw (plane p).
    const auto take = [&](const std::uint8_t* texel, std::uint32_t x, std::uint32_t y, int p) {
      for (int s = 0; s < per_plane; ++s) {
        const int ch = planes == 1 ? s : p;
        if (ch < keep)
          std::memcpy(&raw[((std::size_t(y) * w + x) * std::size_t(keep) + std::size_t(ch)) * bb],
                      texel + std::size_t(s) * bb, bb);
      }
    };
    for (int p = 0; p < std::min(planes, keep); ++p) {
      if (TIFFIsTiled(t)) {
        const auto tw = field<std::uint32_t>(t, TIFFTAG_TILEWIDTH, 0),
                   th = field<std::uint32_t>(t, TIFFTAG_TILELENGTH, 0);
        const std::uint64_t need = std::uint64_t(tw) * th * std::uint64_t(per_plane) * bb;
        if (tw == 0 || th == 0 || TIFFTileSize64(t) < need || need > (std::uint64_t(512) << 20))
          throw fail(fmt::format("tiles of {}x{} texels", tw, th));
        std::vector<std::uint8_t> buf(std::size_t(TIFFTileSize64(t)));
        for (std::uint32_t ty = 0; ty < h; ty += th)
          for (std::uint32_t tx = 0; tx < w; tx += tw) {
            if (TIFFReadTile(t, buf.data(), tx, ty, 0, std::uint16_t(p)) < 0)
              throw fail(fmt::format("tile at ({}, {})", tx, ty));
            for (std::uint32_t y = 0; y < th && ty + y < h; ++y)
              for (std::uint32_t x = 0; x < tw && tx + x < w; ++x)
                take(&buf[(std::size_t(y) * tw + x) * std::size_t(per_plane) * bb], tx + x, ty + y, p);
          }
      } else {
        if (TIFFScanlineSize64(t) < std::uint64_t(w) * std::uint64_t(per_plane) * bb) throw fail("scanline size");
        std::vector<std::uint8_t> buf(std::size_t(TIFFScanlineSize64(t)));
        for (std::uint32_t y = 0; y < h; ++y) {
          if (TIFFReadScanline(t, buf.data(), y, std::uint16_t(p)) < 0) throw fail(fmt::format("row {}", y));
          for (std::uint32_t x = 0; x < w; ++x) take(&buf[std::size_t(x) * std::size_t(per_plane) * bb], x, y, p);
        }
      }
    }
    Image img = from_channels(int(w), int(h), int(bits), keep, std::move(raw), channels);
    return keep_depth ? img : img.to_depth(8);
  }
  // Everything else at 8 bits through libtiff's RGBA reader (TIFFRGBAImage), rows from the top.
  char why[1024] = "";
  if (!TIFFRGBAImageOK(t, why)) throw fail(why);
  std::vector<std::uint32_t> rgba(std::size_t(w) * h);
  if (!TIFFReadRGBAImageOriented(t, w, h, rgba.data(), ORIENTATION_TOPLEFT, 1)) throw fail("damaged image data");
  std::vector<std::uint8_t> bytes(rgba.size() * 4);
  for (std::size_t i = 0; i < rgba.size(); ++i) {
    bytes[4 * i] = std::uint8_t(TIFFGetR(rgba[i])), bytes[4 * i + 1] = std::uint8_t(TIFFGetG(rgba[i]));
    bytes[4 * i + 2] = std::uint8_t(TIFFGetB(rgba[i])), bytes[4 * i + 3] = std::uint8_t(TIFFGetA(rgba[i]));
  }
  return from_channels(int(w), int(h), 8, 4, std::move(bytes), channels);
}

}  // namespace tilekit::image_codecs
