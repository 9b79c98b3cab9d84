#include "image/ktx2.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>

#include "base/error.hpp"

namespace tilekit {

namespace {

// KTX 2.0 sec. 3.1: the file identifier «KTX 20»\r\n\x1A\n.
constexpr std::array<std::uint8_t, 12> kIdentifier = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32,
                                                      0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
constexpr std::size_t kHeaderBytes = 80;  // identifier, header (9 words), index (4 words, 2 doublewords)
constexpr std::size_t kLevelIndexBytes = 24;
// Khronos Data Format 1.3 sec. 5: the basic descriptor block.
constexpr std::uint32_t kDfModelRgbsda = 1, kDfPrimariesBt709 = 1, kDfTransferLinear = 1, kDfTransferSrgb = 2;
constexpr std::uint32_t kDfVersion = 2, kDfSampleLinear = 0x10, kDfChannelAlpha = 15;
// A float sample (sec. 5.6 channelType qualifiers float and signed) spans -1.0 .. 1.0 as floats.
constexpr std::uint32_t kDfSampleFloatSigned = 0x80 | 0x40, kDfFloatMinusOne = 0xBF800000, kDfFloatOne = 0x3F800000;
constexpr std::size_t kDfdBytes = 4 + 24 + 4 * 16;  // dfdTotalSize, the block's header, four samples

void put32(std::string& s, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) s.push_back(char((v >> (8 * i)) & 0xFF));
}
void put64(std::string& s, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) s.push_back(char((v >> (8 * i)) & 0xFF));
}
void pad_to(std::string& s, std::size_t align) {
  while (s.size() % align) s.push_back('\0');
}

std::uint32_t texel_bytes(int bytes_per_channel) {
  return 4u * std::uint32_t(bytes_per_channel);
}

std::uint64_t level_bytes(const Ktx2Texture& t, std::size_t k) {
  return std::uint64_t(std::max(1, t.width >> k)) * std::uint64_t(std::max(1, t.height >> k)) *
         texel_bytes(t.bytes_per_channel);
}

// The data format descriptor of an uncompressed RGBA format (what libktx's vk2dfd makes): one
// sample per channel, the alpha sample flagged linear under the sRGB transfer; float samples
// flagged float and signed, their bounds -1.0 and 1.0.
std::string dfd(const Ktx2Texture& t) {
  const bool is_float = t.bytes_per_channel == 4;
  const std::uint32_t bits = 8u * std::uint32_t(t.bytes_per_channel);
  std::string d;
  put32(d, std::uint32_t(kDfdBytes));
  put32(d, 0);                                                  // vendorId 0 (Khronos), descriptorType 0 (basic)
  put32(d, kDfVersion | (std::uint32_t(kDfdBytes - 4) << 16));  // version, descriptorBlockSize
  const std::uint32_t transfer = t.transfer == Ktx2Transfer::Srgb ? kDfTransferSrgb : kDfTransferLinear;
  put32(d, kDfModelRgbsda | (kDfPrimariesBt709 << 8) | (transfer << 16));  // flags 0: straight alpha
  put32(d, 0);                                                             // texel block 1x1x1x1
  put32(d, texel_bytes(t.bytes_per_channel));                              // bytesPlane0
  put32(d, 0);                                                             // bytesPlane4..7
  const std::array<std::uint32_t, 4> channels = {0, 1, 2, kDfChannelAlpha};
  for (std::uint32_t c = 0; c < 4; ++c) {
    std::uint32_t type = channels[c];
    if (c == 3 && t.transfer == Ktx2Transfer::Srgb) type |= kDfSampleLinear;
    if (is_float) type |= kDfSampleFloatSigned;
    put32(d, (c * bits) | ((bits - 1) << 16) | (type << 24));              // bitOffset, bitLength - 1, channelType
    put32(d, 0);                                                           // sample position
    put32(d, is_float ? kDfFloatMinusOne : 0);                             // sampleLower
    put32(d, is_float ? kDfFloatOne : std::uint32_t((1ull << bits) - 1));  // sampleUpper
  }
  return d;
}

struct Reader {
  std::string_view b;
  const std::string& name;
  [[noreturn]] void fail(const std::string& what) const { throw InputError(fmt::format("{}: {}", name, what)); }
  void need(std::uint64_t offset, std::uint64_t length, const char* what) const {
    if (offset > b.size() || length > b.size() - offset)
      fail(fmt::format("{} ({} bytes at {}) runs past the end of the file ({} bytes)", what, length, offset, b.size()));
  }
  std::uint32_t u32(std::size_t at) const {
    need(at, 4, "a field");
    std::uint32_t v = 0;
    for (int i = 3; i >= 0; --i) v = (v << 8) | std::uint8_t(b[at + std::size_t(i)]);
    return v;
  }
  std::uint64_t u64(std::size_t at) const { return std::uint64_t(u32(at)) | (std::uint64_t(u32(at + 4)) << 32); }
};

}  // namespace

std::uint32_t Ktx2Texture::vk_format() const {
  if (bytes_per_channel == 1) return transfer == Ktx2Transfer::Srgb ? kVkR8G8B8A8Srgb : kVkR8G8B8A8Unorm;
  if (bytes_per_channel == 2 && transfer == Ktx2Transfer::Linear) return kVkR16G16B16A16Unorm;
  if (bytes_per_channel == 4 && transfer == Ktx2Transfer::Linear) return kVkR32G32B32A32Sfloat;
  throw InputError(fmt::format("KTX2: no Vulkan format for {}-bit {} RGBA", 8 * bytes_per_channel,
                               transfer == Ktx2Transfer::Srgb ? "sRGB" : "linear"));
}

std::string encode_ktx2(const Ktx2Texture& t) {
  const std::uint32_t format = t.vk_format();
  if (t.width < 1 || t.height < 1) throw InputError(fmt::format("KTX2: a {}x{} texture", t.width, t.height));
  if (t.levels.empty() || t.levels.size() > 32) throw InputError(fmt::format("KTX2: {} levels", t.levels.size()));
  for (std::size_t k = 0; k < t.levels.size(); ++k)
    if (t.levels[k].size() != level_bytes(t, k))
      throw InputError(fmt::format("KTX2: level {} has {} bytes, not {}", k, t.levels[k].size(), level_bytes(t, k)));
  auto kv = t.key_values;
  auto add = [&kv](const char* key, const char* value) {
    if (std::none_of(kv.begin(), kv.end(), [&](const auto& p) { return p.first == key; })) kv.emplace_back(key, value);
  };
  add("KTXorientation", "rd");
  add("KTXwriter", "tilekit");
  std::sort(kv.begin(), kv.end());  // sec. 3.11: sorted by key, as UTF-8 byte strings
  std::string kvd;
  for (const auto& [key, value] : kv) {
    if (key.empty() || key.find('\0') != std::string::npos || value.find('\0') != std::string::npos)
      throw InputError(fmt::format("KTX2: the key \"{}\" or its value is empty or holds a NUL", key));
    put32(kvd, std::uint32_t(key.size() + 1 + value.size() + 1));
    kvd += key;
    kvd.push_back('\0');
    kvd += value;
    kvd.push_back('\0');
    pad_to(kvd, 4);
  }
  const std::size_t n = t.levels.size();
  const std::size_t dfd_offset = kHeaderBytes + n * kLevelIndexBytes, kvd_offset = dfd_offset + kDfdBytes;
  // Level data after the key/value data, smallest level first, each aligned to lcm(texel bytes, 4).
  const std::size_t align = std::max<std::size_t>(4, texel_bytes(t.bytes_per_channel));
  std::vector<std::uint64_t> offsets(n);
  std::uint64_t at = kvd_offset + kvd.size();
  for (std::size_t k = n; k-- > 0;) {
    at = (at + align - 1) / align * align;
    offsets[k] = at;
    at += t.levels[k].size();
  }
  std::string f(kIdentifier.begin(), kIdentifier.end());
  f.reserve(std::size_t(at));
  put32(f, format);
  put32(f, std::uint32_t(t.bytes_per_channel));  // typeSize
  put32(f, std::uint32_t(t.width));
  put32(f, std::uint32_t(t.height));
  put32(f, 0);  // pixelDepth: 2-D
  put32(f, 0);  // layerCount: not an array
  put32(f, 1);  // faceCount
  put32(f, std::uint32_t(n));
  put32(f, 0);  // supercompressionScheme: none
  put32(f, std::uint32_t(dfd_offset));
  put32(f, std::uint32_t(kDfdBytes));
  put32(f, std::uint32_t(kvd_offset));
  put32(f, std::uint32_t(kvd.size()));
  put64(f, 0);  // no supercompression global data
  put64(f, 0);
  for (std::size_t k = 0; k < n; ++k) {
    put64(f, offsets[k]);
    put64(f, t.levels[k].size());
    put64(f, t.levels[k].size());
  }
  f += dfd(t);
  f += kvd;
  for (std::size_t k = n; k-- > 0;) {
    pad_to(f, align);
    f.append(reinterpret_cast<const char*>(t.levels[k].data()), t.levels[k].size());
  }
  return f;
}

Ktx2Texture decode_ktx2(std::string_view bytes, const std::string& name) {
  const Reader r{bytes, name};
  if (bytes.size() < kHeaderBytes || std::memcmp(bytes.data(), kIdentifier.data(), kIdentifier.size()) != 0)
    r.fail("not a KTX2 file (no KTX 20 identifier)");
  Ktx2Texture t;
  const std::uint32_t format = r.u32(12), type_size = r.u32(16);
  if (format == kVkR8G8B8A8Srgb || format == kVkR8G8B8A8Unorm) {
    t.bytes_per_channel = 1;
    t.transfer = format == kVkR8G8B8A8Srgb ? Ktx2Transfer::Srgb : Ktx2Transfer::Linear;
  } else if (format == kVkR16G16B16A16Unorm || format == kVkR32G32B32A32Sfloat) {
    t.bytes_per_channel = format == kVkR16G16B16A16Unorm ? 2 : 4;
    t.transfer = Ktx2Transfer::Linear;
  } else {
    r.fail(fmt::format("vkFormat {} is not RGBA8 (37, 43), RGBA16 (91) or RGBA32 float (109)", format));
  }
  if (type_size != std::uint32_t(t.bytes_per_channel))
    r.fail(fmt::format("typeSize {} for vkFormat {}", type_size, format));
  const std::uint32_t w = r.u32(20), h = r.u32(24);
  if (w < 1 || h < 1 || w > 1u << 16 || h > 1u << 16) r.fail(fmt::format("a {}x{} texture", w, h));
  t.width = int(w), t.height = int(h);
  if (r.u32(28) != 0 || r.u32(32) != 0 || r.u32(36) != 1) r.fail("not a 2-D texture of one layer and one face");
  const std::uint32_t n = r.u32(40);
  const std::uint32_t full = 1 + std::uint32_t(std::max(0, int(std::bit_width(std::max(w, h))) - 1));
  if (n < 1 || n > full) r.fail(fmt::format("{} levels (1..{} for {}x{})", n, full, w, h));
  if (r.u32(44) != 0) r.fail("supercompressed (scheme " + std::to_string(r.u32(44)) + ")");
  if (r.u64(64) != 0 || r.u64(72) != 0) r.fail("supercompression global data without supercompression");
  // The data format descriptor must say what the format says.
  const std::uint32_t dfd_offset = r.u32(48), dfd_length = r.u32(52);
  r.need(dfd_offset, dfd_length, "the data format descriptor");
  if (dfd_length != kDfdBytes || r.u32(dfd_offset) != kDfdBytes)
    r.fail(fmt::format("a data format descriptor of {} bytes, not {} (one basic block, 4 samples)", dfd_length,
                       kDfdBytes));
  const std::string expected = dfd(t);
  if (bytes.substr(dfd_offset, kDfdBytes) != expected) {
    const std::uint32_t model = r.u32(dfd_offset + 12);
    r.fail(fmt::format("the data format descriptor (model {}, primaries {}, transfer {}) disagrees with vkFormat {}",
                       model & 0xFF, (model >> 8) & 0xFF, (model >> 16) & 0xFF, format));
  }
  // Key/value data: sorted, NUL-terminated keys.
  const std::uint32_t kvd_offset = r.u32(56), kvd_length = r.u32(60);
  if (kvd_length) r.need(kvd_offset, kvd_length, "the key/value data");
  for (std::uint64_t at = kvd_offset, end = std::uint64_t(kvd_offset) + kvd_length; at < end;) {
    const std::uint32_t len = r.u32(std::size_t(at));
    if (len < 2 || at + 4 + len > end) r.fail(fmt::format("a key/value entry of {} bytes at {}", len, at));
    const std::string_view kv = bytes.substr(std::size_t(at + 4), len);
    const std::size_t nul = kv.find('\0');
    if (nul == 0 || nul == std::string_view::npos) r.fail(fmt::format("a key/value entry at {} without a key", at));
    std::string value(kv.substr(nul + 1));
    if (!value.empty() && value.back() == '\0') value.pop_back();
    std::string key(kv.substr(0, nul));
    if (!t.key_values.empty() && key <= t.key_values.back().first)
      r.fail(
          fmt::format("the key/value data is not sorted by key (\"{}\" after \"{}\")", key, t.key_values.back().first));
    t.key_values.emplace_back(std::move(key), std::move(value));
    at += (4 + std::uint64_t(len) + 3) / 4 * 4;
  }
  // Every level inside the file, of its size, aligned.
  const std::size_t align = std::max<std::size_t>(4, texel_bytes(t.bytes_per_channel));
  t.levels.resize(n);
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::size_t at = kHeaderBytes + std::size_t(k) * kLevelIndexBytes;
    const std::uint64_t offset = r.u64(at), length = r.u64(at + 8), raw = r.u64(at + 16);
    if (length != level_bytes(t, k) || raw != length)
      r.fail(fmt::format("level {} has {} bytes, not {}", k, length, level_bytes(t, k)));
    if (offset % align) r.fail(fmt::format("level {} at offset {}, not a multiple of {}", k, offset, align));
    r.need(offset, length, fmt::format("level {}", k).c_str());
    const auto* p = reinterpret_cast<const std::uint8_t*>(bytes.data() + offset);
    t.levels[k].assign(p, p + length);
  }
  return t;
}

}  // namespace tilekit
