#include "image/image.hpp"

#include <fmt/format.h>
#include <png.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string_view>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/input.hpp"
#include "image/codecs.hpp"

// stb as private, static implementations (no symbols shared with other translation units).
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#include <stb_image.h>
#include <stb_image_write.h>
#pragma GCC diagnostic pop

namespace tilekit {

Image::Image(int w, int h, Rgb fill) : width(w), height(h), pixels(std::size_t(w) * std::size_t(h) * 4) {
  for (std::size_t i = 0; i < pixels.size(); i += 4)
    pixels[i] = fill.r, pixels[i + 1] = fill.g, pixels[i + 2] = fill.b, pixels[i + 3] = 255;
}

namespace {

constexpr std::string_view kPngSignature("\x89PNG\r\n\x1a\n", 8);

// stb reads a PNM header's numbers into an int without a bound: a width of 23000023000 is
// signed overflow, undefined behaviour, before any size check of ours (found by
// fuzz/fuzz_texture_input.cpp). The header of a binary PNM (P5, P6: what stb reads) is checked
// here first: its width, height and maxval must have at most 9 digits.
void check_pnm_header(const std::string& path, std::string_view file) {
  if (file.size() < 2 || file[0] != 'P' || (file[1] != '5' && file[1] != '6')) return;
  std::size_t i = 2;
  for (int number = 0; number < 3; ++number) {
    for (;;) {  // whitespace and comments, as stb skips them
      while (i < file.size() && std::isspace(static_cast<unsigned char>(file[i]))) ++i;
      if (i < file.size() && file[i] == '#') {
        while (i < file.size() && file[i] != '\n' && file[i] != '\r') ++i;
        continue;
      }
      break;
    }
    std::size_t digits = 0;
    while (i < file.size() && std::isdigit(static_cast<unsigned char>(file[i]))) ++i, ++digits;
    if (digits > 9)
      throw InputError(fmt::format("{}: a number in its PNM header has {} digits (at most 9)", path, digits));
    if (digits == 0) return;  // malformed: stb refuses it
  }
}

// Beside PNG, JPEG and GIF, stb's formats (TGA, BMP, PNM, PSD, HDR, PIC) are raw or run-length
// coded: none holds more than 128 pixels a byte of file. A larger image from a small file is
// damaged, and stb would fill it by reading past the file's end (a 21-byte "TGA" of 39 Mpixels
// took 12 s under ASan, found by fuzz/fuzz_texture_input.cpp).
void check_pixels_per_byte(const std::string& path, std::string_view file, int w, int h) {
  if (file.starts_with(kPngSignature) || file.starts_with("\xff\xd8\xff") || file.starts_with("GIF8")) return;
  constexpr std::uint64_t kMaxPixelsPerByte = 256;  // twice the most run-length coding gives
  if (std::uint64_t(w) * std::uint64_t(h) > kMaxPixelsPerByte * file.size())
    throw InputError(
        fmt::format("{}: {}x{} pixels from {} bytes is damaged (a raw or run-length coded image holds "
                    "at most {} pixels a byte)",
                    path, w, h, file.size(), kMaxPixelsPerByte));
}

// A PNG whose first IDAT chunk is empty makes stb copy zero bytes from a null pointer (undefined
// behaviour; fuzz/fuzz_texture_input.cpp). Empty IDAT chunks hold no data, so they are dropped;
// every other byte stays as it was (a chunk's CRC covers only itself).
void drop_empty_idat_chunks(std::string& file) {
  if (!std::string_view(file).starts_with(kPngSignature)) return;
  std::string out(kPngSignature);
  std::size_t at = kPngSignature.size();
  while (at + 12 <= file.size()) {
    const auto byte = [&](std::size_t i) { return std::uint32_t(static_cast<unsigned char>(file[at + i])); };
    const std::uint64_t length = (byte(0) << 24) | (byte(1) << 16) | (byte(2) << 8) | byte(3);
    if (length > file.size() - at - 12) break;  // damaged from here: kept as it is, for stb to refuse
    if (!(length == 0 && file.compare(at + 4, 4, "IDAT") == 0)) out.append(file, at, std::size_t(length) + 12);
    at += std::size_t(length) + 12;
  }
  out.append(file, at, std::string::npos);
  file = std::move(out);
}

// stb's reason for its last failure; it gives none for some damaged files.
std::string_view failure_reason() {
  const char* r = stbi_failure_reason();
  return r && *r ? r : "damaged or not an image";
}

}  // namespace

Image Image::to_depth(int bits) const {
  if (bits == depth) return *this;
  Image out(width, height,
            std::vector<std::uint8_t>(std::size_t(width) * std::size_t(height) * std::size_t(channels) *
                                      std::size_t(bits / 8)),
            channels);
  out.depth = bits;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < channels; ++c) {
        if (depth == 32 || bits == 32) {  // float holds 0..1 for 0..max_value()
          const double v = value(x, y, c) / max_value();
          out.set_value(x, y, c, bits == 32 ? v : (v > 0 ? std::min(v, 1.0) : 0.0) * out.max_value());
          continue;
        }
        const unsigned v = sample(x, y, c);
        out.set_sample(x, y, c, bits == 16 ? v * 257 : (v * 255 + 32767) / 65535);
      }
  return out;
}

namespace image_codecs {

void check_decoded_size(const std::string& path, std::size_t file_bytes, std::int64_t w, std::int64_t h) {
  if (w * h > kMaxImagePixels)
    throw InputError(
        fmt::format("{}: {}x{} pixels is more than the {} pixels an image may have", path, w, h, kMaxImagePixels));
  if (w * h > kMaxPixelsPerByte * std::int64_t(file_bytes))
    throw InputError(fmt::format("{}: {}x{} pixels from {} bytes is damaged (at most {} pixels a byte)", path, w, h,
                                 file_bytes, kMaxPixelsPerByte));
}

Image from_channels(int w, int h, int depth, int src_channels, std::vector<std::uint8_t> data, int channels) {
  Image src(w, h, std::move(data), src_channels);
  src.depth = depth;
  if (src_channels == channels) return src;
  Image out(w, h,
            std::vector<std::uint8_t>(std::size_t(w) * std::size_t(h) * std::size_t(channels) * std::size_t(depth / 8)),
            channels);
  out.depth = depth;
  const bool colour = src_channels >= 3, alpha = src_channels == 2 || src_channels == 4;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (channels == 1) {  // luminance as stb_image converts to grey
        const double v = colour ? (77 * src.value(x, y, 0) + 150 * src.value(x, y, 1) + 29 * src.value(x, y, 2)) / 256
                                : src.value(x, y, 0);
        out.set_value(x, y, 0, depth == 32 ? v : std::floor(v));
        continue;
      }
      for (int c = 0; c < 3; ++c) out.set_value(x, y, c, src.value(x, y, colour ? c : 0));
      out.set_value(x, y, 3, alpha ? src.value(x, y, colour ? 3 : 1) : src.max_value());
    }
  return out;
}

}  // namespace image_codecs

Image read_image(const std::string& path, int channels, bool keep_depth) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(fmt::format("{}: no such image file", path));
  std::string file = read_input_file(path, "image");
  if (image_codecs::is_tiff(file)) return image_codecs::decode_tiff(path, file, channels, keep_depth);
  if (image_codecs::is_exr(file)) return image_codecs::decode_exr(path, file, channels, keep_depth);
  check_pnm_header(path, file);
  drop_empty_idat_chunks(file);
  const auto* bytes = reinterpret_cast<const stbi_uc*>(file.data());
  if (file.size() > std::size_t(std::numeric_limits<int>::max()))
    throw InputError(fmt::format("{}: {} bytes is more than an image file may have", path, file.size()));
  const int size = int(file.size());
  int w = 0, h = 0, n = 0;
  if (!stbi_info_from_memory(bytes, size, &w, &h, &n))
    throw InputError(fmt::format("{}: cannot read the image ({})", path, failure_reason()));
  if (std::int64_t(w) * std::int64_t(h) > kMaxImagePixels)
    throw InputError(
        fmt::format("{}: {}x{} pixels is more than the {} pixels an image may have", path, w, h, kMaxImagePixels));
  check_pixels_per_byte(path, file, w, h);
  // stb's 16-bit decoders other than PNG's (PNM with a maxval over 255, PSD) can write past their
  // buffer on a damaged file (found by fuzz/fuzz_texture_input.cpp): such images are refused.
  if (stbi_is_16_bit_from_memory(bytes, size) && !std::string_view(file).starts_with(kPngSignature))
    throw InputError(fmt::format("{}: a 16-bit image that is not a PNG (convert it to PNG or TIFF)", path));
  if (keep_depth && stbi_is_16_bit_from_memory(bytes, size)) {
    stbi_us* wide = stbi_load_16_from_memory(bytes, size, &w, &h, &n, channels);
    if (!wide) throw InputError(fmt::format("{}: cannot read the image ({})", path, failure_reason()));
    const std::size_t count = std::size_t(w) * std::size_t(h) * std::size_t(channels);
    Image img(w, h, std::vector<std::uint8_t>(count * 2), channels);
    img.depth = 16;
    std::memcpy(img.pixels.data(), wide, count * 2);
    stbi_image_free(wide);
    return img;
  }
  stbi_uc* data = stbi_load_from_memory(bytes, size, &w, &h, &n, channels);
  if (!data) throw InputError(fmt::format("{}: cannot read the image ({})", path, failure_reason()));
  Image img(w, h, std::vector<std::uint8_t>(data, data + std::size_t(w) * std::size_t(h) * std::size_t(channels)),
            channels);
  stbi_image_free(data);
  return img;
}

namespace {

void append_to_string(png_structp p, png_bytep d, png_size_t n) {
  static_cast<std::string*>(png_get_io_ptr(p))->append(reinterpret_cast<const char*>(d), n);
}
void flush_nothing(png_structp) {}

// libpng reports errors by longjmp: nothing here lives across the setjmp but what libpng owns.
bool png16_to(std::string& bytes, png_uint_32 w, png_uint_32 h, int colour_type, png_bytepp rows) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, &bytes, append_to_string, flush_nothing);
  png_set_IHDR(png, info, w, h, 16, colour_type, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_set_rows(png, info, rows);
  png_write_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

// A 16-bit PNG through libpng's write API (stb_image_write writes 8 bits only): the fewest
// channels that hold the image, big-endian samples as PNG stores them.
std::string encode_png16(const Image& img) {
  bool grey = true, opaque = true;
  if (img.channels == 4)
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        grey = grey && img.sample(x, y, 0) == img.sample(x, y, 1) && img.sample(x, y, 0) == img.sample(x, y, 2);
        opaque = opaque && img.sample(x, y, 3) == 65535;
      }
  std::vector<int> keep = img.channels == 1 ? std::vector<int>{0}
                          : grey            ? std::vector<int>{0}
                                            : std::vector<int>{0, 1, 2};
  if (img.channels == 4 && !opaque) keep.push_back(3);
  const int colour_type = keep.size() == 1   ? PNG_COLOR_TYPE_GRAY
                          : keep.size() == 2 ? PNG_COLOR_TYPE_GRAY_ALPHA
                          : keep.size() == 3 ? PNG_COLOR_TYPE_RGB
                                             : PNG_COLOR_TYPE_RGBA;
  std::vector<std::uint8_t> rows(std::size_t(img.width) * std::size_t(img.height) * keep.size() * 2);
  std::size_t i = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c : keep) {
        const unsigned v = img.sample(x, y, c);
        rows[i++] = std::uint8_t(v >> 8), rows[i++] = std::uint8_t(v & 255);
      }
  std::vector<png_bytep> row_pointers(std::size_t(img.height));
  for (int y = 0; y < img.height; ++y)
    row_pointers[std::size_t(y)] = rows.data() + std::size_t(y) * std::size_t(img.width) * keep.size() * 2;
  std::string bytes;
  if (!png16_to(bytes, png_uint_32(img.width), png_uint_32(img.height), colour_type, row_pointers.data()))
    throw InputError(fmt::format("cannot encode a {}x{} 16-bit PNG", img.width, img.height));
  return bytes;
}

}  // namespace

std::string encode_png(const Image& img) {
  if (img.depth == 32) throw InputError("a float image is written as OpenEXR, not PNG");
  if (img.depth == 16) return encode_png16(img);
  // The fewest channels that hold the picture exactly (grey, grey+alpha, RGB or RGBA): pictures
  // of grey textures take a quarter of the space.
  const std::size_t ch = std::size_t(img.channels);
  bool grey = true, opaque = true;
  if (ch == 4)
    for (std::size_t i = 0; i < img.pixels.size(); i += 4) {
      grey = grey && img.pixels[i] == img.pixels[i + 1] && img.pixels[i] == img.pixels[i + 2];
      opaque = opaque && img.pixels[i + 3] == 255;
    }
  const int channels = (grey ? 1 : 3) + (opaque ? 0 : 1);
  std::vector<std::uint8_t> packed;
  const std::uint8_t* data = img.pixels.data();
  if (std::size_t(channels) != ch) {
    packed.reserve(img.pixels.size() / ch * std::size_t(channels));
    for (std::size_t i = 0; i < img.pixels.size(); i += ch) {
      packed.push_back(img.pixels[i]);
      if (!grey) packed.insert(packed.end(), {img.pixels[i + 1], img.pixels[i + 2]});
      if (!opaque) packed.push_back(img.pixels[i + 3]);
    }
    data = packed.data();
  }
  std::string bytes;
  auto sink = [](void* ctx, void* d, int size) {
    static_cast<std::string*>(ctx)->append(static_cast<const char*>(d), std::size_t(size));
  };
  if (!stbi_write_png_to_func(sink, &bytes, img.width, img.height, channels, data, img.width * channels))
    throw InputError(fmt::format("cannot encode a {}x{} PNG", img.width, img.height));
  return bytes;
}

std::string encode_image(const Image& img) {
  return img.depth == 32 ? encode_exr(img) : encode_png(img);
}

namespace {

// `encode`'s bytes written atomically; an encoding error names the file.
void write_encoded(const std::string& path, const Image& img, std::string (*encode)(const Image&)) {
  std::string bytes;
  try {
    bytes = encode(img);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", path, e.what()));
  }
  write_file_atomic(path, bytes);
}

}  // namespace

void write_png(const std::string& path, const Image& img) {
  write_encoded(path, img, encode_png);
}
void write_exr(const std::string& path, const Image& img) {
  write_encoded(path, img, encode_exr);
}

}  // namespace tilekit
