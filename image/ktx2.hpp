#pragma once
// KTX 2.0 (Khronos Texture Container, KTX File Format Specification 2.0): one 2-D texture with its
// mip chain, uncompressed RGBA of 8 or 16 bits a channel or 32-bit float, its Vulkan format, a basic data format
// descriptor (the colour model RGBSDA, BT.709 primaries, the transfer function: sRGB for colour,
// linear for data such as normals and roughness), key/value data (sorted by key) and the levels,
// smallest first in the file as the specification orders them. What engines (Unity, Unreal,
// Godot, three.js's KTX2Loader, libktx) import with every level.
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tilekit {

// The Vulkan formats written and read (VkFormat values).
inline constexpr std::uint32_t kVkR8G8B8A8Unorm = 37, kVkR8G8B8A8Srgb = 43, kVkR16G16B16A16Unorm = 91,
                               kVkR32G32B32A32Sfloat = 109;

enum class Ktx2Transfer { Linear, Srgb };  // the data format descriptor's transfer function

struct Ktx2Texture {
  int width = 0, height = 0;
  // 1 (RGBA8), 2 (RGBA16 UNORM) or 4 (RGBA32 SFLOAT); 2 and 4 little-endian and linear only.
  int bytes_per_channel = 1;
  Ktx2Transfer transfer = Ktx2Transfer::Srgb;
  // Level 0 first, each width_k * height_k * 4 * bytes_per_channel bytes, rows from the top
  // (KTXorientation "rd"), width_k = max(1, width >> k).
  std::vector<std::vector<std::uint8_t>> levels;
  // Key/value pairs; each value is written as a NUL-terminated string. KTXwriter and
  // KTXorientation are added by encode_ktx2 unless present.
  std::vector<std::pair<std::string, std::string>> key_values;

  std::uint32_t vk_format() const;  // InputError for a combination without a format above
};

// The file's bytes. InputError for levels of the wrong count or size.
std::string encode_ktx2(const Ktx2Texture& t);
// Reads and checks a KTX2 file: the identifier, a 2-D texture of one layer and face, no
// supercompression, one of the formats above with a data format descriptor that agrees with it
// (model, transfer, bytes per texel, samples), every level's place and length inside the file,
// sorted key/value data. InputError naming `name` and the first problem otherwise.
Ktx2Texture decode_ktx2(std::string_view bytes, const std::string& name);

}  // namespace tilekit
