// The KTX2 container (image/ktx2.hpp) against the KTX 2.0 specification's layout: header fields at
// their offsets, levels stored smallest first and aligned, the data format descriptor of the format,
// sorted key/value data; decode_ktx2 reads back what encode_ktx2 wrote and refuses damaged files
// naming the problem. (tests/texture/ktx2_three.test.mjs reads the atlas's files with npm's
// ktx-parse and three.js's KTX2Loader.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "base/error.hpp"
#include "image/ktx2.hpp"

using namespace tilekit;

namespace {

Ktx2Texture ramp(int w, int h, int bytes_per_channel, Ktx2Transfer transfer) {
  Ktx2Texture t;
  t.width = w, t.height = h, t.bytes_per_channel = bytes_per_channel, t.transfer = transfer;
  for (int k = 0;; ++k) {
    const std::size_t n =
        std::size_t(std::max(1, w >> k)) * std::size_t(std::max(1, h >> k)) * 4 * std::size_t(bytes_per_channel);
    std::vector<std::uint8_t> level(n);
    for (std::size_t i = 0; i < n; ++i) level[i] = std::uint8_t(i * 31 + std::size_t(k));
    t.levels.push_back(std::move(level));
    if (std::max(1, w >> k) == 1 && std::max(1, h >> k) == 1) break;
  }
  t.key_values = {{"tilekit.atlas", "{\"rows\":9}"}};
  return t;
}

std::uint32_t u32(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | std::uint8_t(b[at + std::size_t(i)]);
  return v;
}
std::uint64_t u64(const std::string& b, std::size_t at) {
  return u32(b, at) | (std::uint64_t(u32(b, at + 4)) << 32);
}

std::string refusal(const std::string& bytes) {
  try {
    decode_ktx2(bytes, "x.ktx2");
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST(Ktx2, HeaderLevelsAndDescriptorFollowTheSpecification) {
  const Ktx2Texture t = ramp(12, 5, 1, Ktx2Transfer::Srgb);  // 12x5 6x2 3x1 1x1
  ASSERT_EQ(t.levels.size(), 4u);
  const std::string b = encode_ktx2(t);
  EXPECT_EQ(b.substr(0, 12), std::string("\xABKTX 20\xBB\r\n\x1A\n", 12));
  EXPECT_EQ(u32(b, 12), kVkR8G8B8A8Srgb);
  EXPECT_EQ(u32(b, 16), 1u);  // typeSize
  EXPECT_EQ(u32(b, 20), 12u);
  EXPECT_EQ(u32(b, 24), 5u);
  EXPECT_EQ(u32(b, 36), 1u);  // faceCount
  EXPECT_EQ(u32(b, 40), 4u);  // levelCount
  // Level data smallest first, 4-byte aligned, each level's bytes where the index says.
  std::uint64_t previous = b.size();
  for (std::size_t k = 0; k < 4; ++k) {
    const std::uint64_t offset = u64(b, 80 + 24 * k), length = u64(b, 88 + 24 * k);
    EXPECT_EQ(length, t.levels[k].size());
    EXPECT_EQ(offset % 4, 0u);
    EXPECT_LT(offset, previous) << "level " << k << " must come before level " << k - 1;
    previous = offset;
    EXPECT_EQ(b.substr(offset, length), std::string(t.levels[k].begin(), t.levels[k].end()));
  }
  // The basic data format descriptor: RGBSDA, BT.709, sRGB transfer, 4 bytes a texel, alpha linear.
  const std::size_t dfd = u32(b, 48);
  EXPECT_EQ(u32(b, dfd), 92u);
  EXPECT_EQ(u32(b, dfd + 12), 1u | (1u << 8) | (2u << 16));
  EXPECT_EQ(u32(b, dfd + 20), 4u);
  EXPECT_EQ(u32(b, dfd + 28 + 3 * 16) >> 24, 15u | 0x10u);
  EXPECT_EQ(u32(b, dfd + 28 + 3 * 16 + 12), 255u);
}

TEST(Ktx2, ReadsBackWhatItWritesAtEightAndSixteenBits) {
  for (const auto& [bytes, transfer, format] :
       {std::tuple{1, Ktx2Transfer::Srgb, kVkR8G8B8A8Srgb}, std::tuple{1, Ktx2Transfer::Linear, kVkR8G8B8A8Unorm},
        std::tuple{2, Ktx2Transfer::Linear, kVkR16G16B16A16Unorm},
        std::tuple{4, Ktx2Transfer::Linear, kVkR32G32B32A32Sfloat}}) {
    const Ktx2Texture t = ramp(9, 16, bytes, transfer);
    const std::string b = encode_ktx2(t);
    EXPECT_EQ(u32(b, 12), format);
    const Ktx2Texture r = decode_ktx2(b, "x.ktx2");
    EXPECT_EQ(r.width, 9);
    EXPECT_EQ(r.height, 16);
    EXPECT_EQ(r.bytes_per_channel, bytes);
    EXPECT_EQ(r.transfer, transfer);
    EXPECT_EQ(r.levels, t.levels);
    // The writer's keys added, all sorted by key.
    ASSERT_EQ(r.key_values.size(), 3u);
    EXPECT_EQ(r.key_values[0], (std::pair<std::string, std::string>{"KTXorientation", "rd"}));
    EXPECT_EQ(r.key_values[1].first, "KTXwriter");
    EXPECT_EQ(r.key_values[2], t.key_values[0]);
  }
  EXPECT_THROW(ramp(4, 4, 2, Ktx2Transfer::Srgb).vk_format(), InputError);  // no 16-bit sRGB format
  EXPECT_THROW(ramp(4, 4, 4, Ktx2Transfer::Srgb).vk_format(), InputError);  // nor a float one
}

// R32G32B32A32_SFLOAT's descriptor as libktx's vk2dfd makes it (Khronos Data Format 1.3 sec. 5.6):
// 16 bytes a texel, 32-bit samples flagged float and signed, bounds -1.0 and 1.0 as floats.
TEST(Ktx2, FloatDescriptorFlagsFloatSignedSamples) {
  const std::string b = encode_ktx2(ramp(4, 4, 4, Ktx2Transfer::Linear));
  const std::uint32_t dfd = u32(b, 48);
  EXPECT_EQ(u32(b, 16), 4u);                                  // typeSize
  EXPECT_EQ(u32(b, dfd + 12), 1u | (1u << 8) | (1u << 16));   // RGBSDA, BT.709, linear
  EXPECT_EQ(u32(b, dfd + 20), 16u);                           // bytesPlane0
  for (std::uint32_t c = 0; c < 4; ++c) {
    const std::uint32_t s = dfd + 28 + c * 16;
    EXPECT_EQ(u32(b, s), (c * 32) | (31u << 16) | ((c == 3 ? 15u : c) | 0xC0u) << 24);
    EXPECT_EQ(u32(b, s + 8), 0xBF800000u);
    EXPECT_EQ(u32(b, s + 12), 0x3F800000u);
  }
}

TEST(Ktx2, RefusesDamagedFilesNamingTheProblem) {
  const Ktx2Texture t = ramp(8, 8, 1, Ktx2Transfer::Linear);
  const std::string good = encode_ktx2(t);
  ASSERT_EQ(refusal(good), "accepted");
  EXPECT_NE(refusal(good.substr(0, 40)).find("not a KTX2 file"), std::string::npos);
  EXPECT_NE(refusal(good.substr(0, good.size() - 1)).find("runs past the end"), std::string::npos);
  std::string b = good;
  b[12] = 44;  // vkFormat 44 (R8G8B8A8_SNORM... not written)
  EXPECT_NE(refusal(b).find("vkFormat 44"), std::string::npos);
  b = good;
  b[12] = char(kVkR8G8B8A8Srgb);  // sRGB format, linear descriptor
  EXPECT_NE(refusal(b).find("disagrees with vkFormat 43"), std::string::npos);
  b = good;
  b[44] = 2;  // zstd
  EXPECT_NE(refusal(b).find("supercompressed"), std::string::npos);
  b = good;
  b[88] = char(b[88] + 4);  // level 0 four bytes longer
  EXPECT_NE(refusal(b).find("level 0 has"), std::string::npos);
  b = good;
  b[40] = 9;  // 9 levels for 8x8
  EXPECT_NE(refusal(b).find("9 levels"), std::string::npos);
  // Unsorted keys: "KTXwriter" renamed to "KTXaaaaaa", now before "KTXorientation".
  b = good;
  b.replace(b.find("KTXwriter"), 9, "KTXaaaaaa");
  EXPECT_NE(refusal(b).find("not sorted"), std::string::npos);
  Ktx2Texture short_level = t;
  short_level.levels[1].pop_back();
  EXPECT_THROW(encode_ktx2(short_level), InputError);
}
