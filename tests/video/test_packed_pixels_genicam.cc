// The GenICam packings of lib/video/packed_pixels.h (rk-capture aravis: cameras): PFNC Mono10p / Mono12p (a
// little-endian bit stream) and GigE Vision Mono10Packed / Mono12Packed (high bytes whole, the low bits of two
// pixels shared in the middle byte), packed here by their definitions, bit by bit, and unpacked by Unpack16 —
// copied out and in place — to the values scaled to 16 bits by bit replication.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "video/packed_pixels.h"

namespace rk::video {
namespace packed_genicam_test {  // named: tests/video is one unity build

std::uint16_t Scaled(std::uint32_t v, int b) { return static_cast<std::uint16_t>((v << (16 - b)) | (v >> (2 * b - 16))); }

// PFNC "p" formats: pixel i's bit j is bit (i·b + j) of the stream, the stream's bit k is bit k % 8 of byte k / 8.
std::vector<std::uint8_t> PackLsb(const std::vector<std::uint32_t>& v, int b) {
  std::vector<std::uint8_t> out(v.size() * static_cast<std::size_t>(b) / 8, 0);
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int j = 0; j < b; ++j) {
      const std::size_t k = i * static_cast<std::size_t>(b) + static_cast<std::size_t>(j);
      if ((v[i] >> j) & 1u) out[k / 8] |= static_cast<std::uint8_t>(1u << (k % 8));
    }
  return out;
}

// GigE Vision "Packed": byte 0 = pixel 0's high 8 bits, byte 2 = pixel 1's, byte 1 = pixel 0's low bits in its
// low nibble and pixel 1's in its high nibble (for 10 bits: the nibbles' low 2 bits).
std::vector<std::uint8_t> PackGev(const std::vector<std::uint32_t>& v, int b) {
  std::vector<std::uint8_t> out;
  const int low = b - 8;
  for (std::size_t i = 0; i < v.size(); i += 2) {
    out.push_back(static_cast<std::uint8_t>(v[i] >> low));
    out.push_back(static_cast<std::uint8_t>((v[i] & ((1u << low) - 1)) | ((v[i + 1] & ((1u << low) - 1)) << 4)));
    out.push_back(static_cast<std::uint8_t>(v[i + 1] >> low));
  }
  return out;
}

void Check(Packing packing, int bits, bool lsb) {
  std::mt19937 rng(static_cast<unsigned>(bits) * 7 + (lsb ? 1 : 0));
  std::uniform_int_distribution<std::uint32_t> d(0, (1u << bits) - 1);
  for (std::uint64_t n : {4u, 8u, 12u, 16u, 20u, 64u, 1000u, 2448u * 3u}) {
    std::vector<std::uint32_t> v(n);
    for (auto& x : v) x = d(rng);
    v[0] = 0;
    v[n - 1] = (1u << bits) - 1;
    const std::vector<std::uint8_t> packed = lsb ? PackLsb(v, bits) : PackGev(v, bits);
    ASSERT_EQ(packed.size(), PackedBytes(packing, n));
    std::vector<std::uint16_t> out(n);
    EXPECT_EQ(Unpack16(packing, bits, packed.data(), n, out.data()), 0u);
    // In place: the packed bytes at the end of the 16-bit frame's own buffer.
    std::vector<std::uint16_t> inplace(n);
    auto* bytes = reinterpret_cast<std::uint8_t*>(inplace.data());
    std::memcpy(bytes + 2 * n - packed.size(), packed.data(), packed.size());
    Unpack16(packing, bits, bytes + 2 * n - packed.size(), n, inplace.data());
    for (std::uint64_t i = 0; i < n; ++i) {
      ASSERT_EQ(out[i], Scaled(v[i], bits)) << InfoOf(packing).name << " pixel " << i << " of " << n;
      ASSERT_EQ(inplace[i], out[i]) << InfoOf(packing).name << " in place, pixel " << i << " of " << n;
    }
  }
}

TEST(PackedPixels, GenICamMono10pAndMono12p) {
  Check(Packing::kP10LSB, 10, true);
  Check(Packing::kP12LSB, 12, true);
}

TEST(PackedPixels, GigEVisionMono10PackedAndMono12Packed) {
  Check(Packing::kP10GEV, 10, false);
  Check(Packing::kP12GEV, 12, false);
}

TEST(PackedPixels, GenICamGroups) {
  EXPECT_EQ(PackedBytes(Packing::kP10LSB, 8), 10u);
  EXPECT_EQ(PackedBytes(Packing::kP10GEV, 8), 12u);
  EXPECT_FALSE(FillsGroups(Packing::kP10LSB, 6));
  EXPECT_TRUE(FillsGroups(Packing::kP10GEV, 6));
}

}  // namespace packed_genicam_test
}  // namespace rk::video
