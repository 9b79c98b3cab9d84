#pragma once
// Inside image/: the TIFF (libtiff) and OpenEXR decoders that read_image hands a file to, and what
// they share. Not for other folders: they call read_image, which picks the decoder by the file's
// first bytes.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "image/image.hpp"

namespace tilekit::image_codecs {

bool is_tiff(std::string_view file);  // "II*\0" or "MM\0*" (classic TIFF; BigTIFF is refused by libtiff's reader)
bool is_exr(std::string_view file);   // the OpenEXR magic number 20000630

// InputError unless a w x h image may be decoded from `file_bytes` bytes: at most kMaxImagePixels,
// and at most kMaxPixelsPerByte pixels a byte of file (no compression of TIFF or EXR that a
// texture needs packs more; a header that claims more from a small file is damaged, and would
// make the decoder allocate gigabytes before it finds out).
inline constexpr std::int64_t kMaxPixelsPerByte = 1024;
void check_decoded_size(const std::string& path, std::size_t file_bytes, std::int64_t w, std::int64_t h);

// `src_channels` (1 grey, 2 grey + alpha, 3 RGB, 4 RGBA) samples of `depth` bits per texel as an
// Image of `channels` (4 RGBA or 1 grey, luminance by stb_image's weights 77, 150, 29 / 256);
// missing alpha is opaque (max_value()).
Image from_channels(int w, int h, int depth, int src_channels, std::vector<std::uint8_t> data, int channels);

// The decoders: TIFF (8 or 16 bits unsigned, or 32-bit float, grey or RGB with or without alpha,
// read as stored; any other TIFF libtiff reads, such as palette, CMYK or 1-bit, through its RGBA
// reader at 8 bits) and OpenEXR (half, float or uint channels R, G, B, A or Y, or a single channel
// of any name, as 32-bit float). Depth kept when keep_depth, else 8 bits. InputError naming
// `path` with libtiff's or OpenEXR's reason for a file they refuse; no output on stderr.
Image decode_tiff(const std::string& path, std::string_view file, int channels, bool keep_depth);
Image decode_exr(const std::string& path, std::string_view file, int channels, bool keep_depth);

}  // namespace tilekit::image_codecs
