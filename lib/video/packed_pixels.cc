// Unpacking loops of the camera-file packings; see packed_pixels.h. Each loop works group by group on
// fixed-size groups with no branch, so g++ -O2 vectorises it (bench_video_read: 12-bit packed at the speed
// of reading the file from the page cache).
#include "video/packed_pixels.h"

#include <algorithm>
#include <array>
#include <cstring>

#include "io/error.h"

namespace rk::video {
namespace {

constexpr std::array<PackingInfo, 4> kPackings{{
    {Packing::kU8, "8-bit", 8, 1, 1},
    {Packing::kU16LE, "16-bit little-endian", 16, 1, 2},
    {Packing::kP10BE, "10-bit packed", 10, 4, 5},
    {Packing::kP12BE, "12-bit packed", 12, 2, 3},
}};

// v (b significant bits) → 16 bits, by replicating the top bits into the low ones (b ≥ 8).
inline std::uint16_t Widen(std::uint32_t v, int b) {
  return static_cast<std::uint16_t>((v << (16 - b)) | (v >> (2 * b - 16)));
}

void UnpackP12(const std::uint8_t* src, std::uint64_t pixels, std::uint16_t* dst) {
  const std::uint64_t groups = pixels / 2;
  for (std::uint64_t g = 0; g < groups; ++g) {
    const std::uint32_t b0 = src[3 * g], b1 = src[3 * g + 1], b2 = src[3 * g + 2];
    const std::uint32_t v0 = (b0 << 4) | (b1 >> 4);
    const std::uint32_t v1 = ((b1 & 0x0Fu) << 8) | b2;
    dst[2 * g] = static_cast<std::uint16_t>((v0 << 4) | (v0 >> 8));
    dst[2 * g + 1] = static_cast<std::uint16_t>((v1 << 4) | (v1 >> 8));
  }
}

void UnpackP10(const std::uint8_t* src, std::uint64_t pixels, std::uint16_t* dst) {
  const std::uint64_t groups = pixels / 4;
  for (std::uint64_t g = 0; g < groups; ++g) {
    const std::uint8_t* s = src + 5 * g;
    const std::uint32_t b0 = s[0], b1 = s[1], b2 = s[2], b3 = s[3], b4 = s[4];
    const std::uint32_t v0 = (b0 << 2) | (b1 >> 6);
    const std::uint32_t v1 = ((b1 & 0x3Fu) << 4) | (b2 >> 4);
    const std::uint32_t v2 = ((b2 & 0x0Fu) << 6) | (b3 >> 2);
    const std::uint32_t v3 = ((b3 & 0x03u) << 8) | b4;
    std::uint16_t* d = dst + 4 * g;
    d[0] = static_cast<std::uint16_t>((v0 << 6) | (v0 >> 4));
    d[1] = static_cast<std::uint16_t>((v1 << 6) | (v1 >> 4));
    d[2] = static_cast<std::uint16_t>((v2 << 6) | (v2 >> 4));
    d[3] = static_cast<std::uint16_t>((v3 << 6) | (v3 >> 4));
  }
}

// 16-bit little-endian samples of `bits` significant bits.
std::uint64_t UnpackU16(int bits, const std::uint8_t* src, std::uint64_t pixels, std::uint16_t* dst) {
  std::memcpy(dst, src, pixels * 2);  // x86-64 and every target Debian builds rangekit for: little-endian
  if (bits >= 16) return 0;
  const std::uint32_t max = (1u << bits) - 1;
  std::uint64_t clamped = 0;
  for (std::uint64_t i = 0; i < pixels; ++i) {
    const std::uint32_t v = dst[i];
    clamped += v > max;
    dst[i] = v > max ? std::uint16_t{0xFFFF} : Widen(v, bits);
  }
  return clamped;
}

}  // namespace

const PackingInfo& InfoOf(Packing packing) {
  for (const PackingInfo& p : kPackings) {
    if (p.packing == packing) return p;
  }
  throw std::logic_error("video: unknown packing");
}

bool FillsGroups(Packing packing, std::uint64_t pixels) {
  return pixels % static_cast<std::uint64_t>(InfoOf(packing).pixels_per_group) == 0;
}

std::uint64_t PackedBytes(Packing packing, std::uint64_t pixels) {
  const PackingInfo& p = InfoOf(packing);
  return pixels / static_cast<std::uint64_t>(p.pixels_per_group) * static_cast<std::uint64_t>(p.bytes_per_group);
}

std::uint64_t Unpack16(Packing packing, int significant_bits, const std::uint8_t* src, std::uint64_t pixels,
                       std::uint16_t* dst16) {
  RK_CHECK(FillsGroups(packing, pixels), "pixel count is not a whole number of groups");
  RK_CHECK(significant_bits >= 8 && significant_bits <= 16, "significant bits out of 8..16");
  switch (packing) {
    case Packing::kP12BE:
      UnpackP12(src, pixels, dst16);
      return 0;
    case Packing::kP10BE:
      UnpackP10(src, pixels, dst16);
      return 0;
    case Packing::kU16LE:
      return UnpackU16(significant_bits, src, pixels, dst16);
    case Packing::kU8:
      break;
  }
  throw std::logic_error("video: Unpack16 of an 8-bit packing");
}

void Unpack8(const std::uint8_t* src, std::uint64_t pixels, std::uint8_t* dst8) { std::memcpy(dst8, src, pixels); }

}  // namespace rk::video
