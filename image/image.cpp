#include "image/image.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string_view>

#include "base/atomic_file.hpp"
#include "base/error.hpp"

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

// stb reads a PNM header's numbers into an int without a bound: a width of 23000023000 is
// signed overflow, undefined behaviour, before any size check of ours (found by
// fuzz/fuzz_texture_input.cpp). The header of a binary PNM (P5, P6: what stb reads) is checked
// here first: its width, height and maxval must have at most 9 digits.
void check_pnm_header(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(4096, '\0');
  in.read(head.data(), std::streamsize(head.size()));
  head.resize(std::size_t(in.gcount()));
  if (head.size() < 2 || head[0] != 'P' || (head[1] != '5' && head[1] != '6')) return;
  std::size_t i = 2;
  for (int number = 0; number < 3; ++number) {
    for (;;) {  // whitespace and comments, as stb skips them
      while (i < head.size() && std::isspace(static_cast<unsigned char>(head[i]))) ++i;
      if (i < head.size() && head[i] == '#') {
        while (i < head.size() && head[i] != '\n' && head[i] != '\r') ++i;
        continue;
      }
      break;
    }
    std::size_t digits = 0;
    while (i < head.size() && std::isdigit(static_cast<unsigned char>(head[i]))) ++i, ++digits;
    if (digits > 9)
      throw InputError(fmt::format("{}: a number in its PNM header has {} digits (at most 9)", path, digits));
    if (digits == 0) return;  // malformed: stb refuses it
  }
}

// Beside PNG, JPEG and GIF, stb's formats (TGA, BMP, PNM, PSD, HDR, PIC) are raw or run-length
// coded: none holds more than 128 pixels a byte of file. A larger image from a small file is
// damaged, and stb would fill it by reading past the file's end (a 21-byte "TGA" of 39 Mpixels
// took 12 s under ASan, found by fuzz/fuzz_texture_input.cpp).
void check_pixels_per_byte(const std::string& path, int w, int h) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  const auto size = std::uint64_t(std::max<std::streamoff>(in.tellg(), 0));
  in.seekg(0);
  char magic[4] = {};
  in.read(magic, sizeof magic);
  const std::string_view m(magic, sizeof magic);
  if (m == std::string_view("\x89PNG", 4) || m.substr(0, 3) == std::string_view("\xff\xd8\xff", 3) || m == "GIF8") return;
  constexpr std::uint64_t kMaxPixelsPerByte = 256;  // twice the most run-length coding gives
  if (std::uint64_t(w) * std::uint64_t(h) > kMaxPixelsPerByte * size)
    throw InputError(fmt::format("{}: {}x{} pixels from {} bytes is damaged (a raw or run-length coded image holds "
                                 "at most {} pixels a byte)",
                                 path, w, h, size, kMaxPixelsPerByte));
}

}  // namespace

Image read_image(const std::string& path, int channels) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(fmt::format("{}: no such image file", path));
  check_pnm_header(path);
  int w = 0, h = 0, n = 0;
  if (!stbi_info(path.c_str(), &w, &h, &n))
    throw InputError(fmt::format("{}: cannot read the image ({})", path, stbi_failure_reason()));
  if (std::int64_t(w) * std::int64_t(h) > kMaxImagePixels)
    throw InputError(fmt::format("{}: {}x{} pixels is more than the {} pixels an image may have", path, w, h,
                                 kMaxImagePixels));
  check_pixels_per_byte(path, w, h);
  // stb's 16-bit decoders other than PNG's (PNM with a maxval over 255, PSD) can write past their
  // buffer on a damaged file (found by fuzz/fuzz_texture_input.cpp): such images are refused.
  if (stbi_is_16_bit(path.c_str())) {
    std::ifstream in(path, std::ios::binary);
    char magic[8] = {};
    in.read(magic, sizeof magic);
    if (std::string_view(magic, sizeof magic) != std::string_view("\x89PNG\r\n\x1a\n", 8))
      throw InputError(fmt::format("{}: a 16-bit image that is not a PNG (convert it to PNG)", path));
  }
  stbi_uc* data = stbi_load(path.c_str(), &w, &h, &n, channels);
  if (!data) throw InputError(fmt::format("{}: cannot read the image ({})", path, stbi_failure_reason()));
  Image img(w, h, std::vector<std::uint8_t>(data, data + std::size_t(w) * std::size_t(h) * std::size_t(channels)),
            channels);
  stbi_image_free(data);
  return img;
}

std::string encode_png(const Image& img) {
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

void write_png(const std::string& path, const Image& img) {
  std::string bytes;
  try {
    bytes = encode_png(img);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", path, e.what()));
  }
  write_file_atomic(path, bytes);
}

}  // namespace tilekit
