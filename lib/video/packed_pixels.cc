// Unpacking loops of the camera-file packings; see packed_pixels.h. The 16-bit loop is vectorised by g++
// itself; the 10- and 12-bit packings, whose pixels straddle bytes, are not (-fopt-info-vec), so they have an
// SSSE3 kernel (every x86-64 processor since 2006; chosen at run time, the portable loop otherwise and for the
// last groups): one byte shuffle puts each pixel's two bytes in a 16-bit lane, one multiply shifts each lane
// so that its bits end at the same place, one shift and the widening finish 8 pixels. An AVX2 version (16 pixels
// a step) measured no faster: the unpacking is bound by writing the 16-bit frame, not by its instructions
// (bench/video_read_bench.sh: docs/benchmarks.md "Issue 29").
#include "video/packed_pixels.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define RK_HAVE_SSSE3_KERNEL 1
#endif

#include <algorithm>
#include <array>
#include <cstring>

#include "io/error.h"

namespace rk::video {
namespace {

constexpr std::array<PackingInfo, 8> kPackings{{
    {Packing::kU8, "8-bit", 8, 1, 1},
    {Packing::kU16LE, "16-bit little-endian", 16, 1, 2},
    {Packing::kP10BE, "10-bit packed", 10, 4, 5},
    {Packing::kP12BE, "12-bit packed", 12, 2, 3},
    {Packing::kP10LSB, "Mono10p", 10, 4, 5},
    {Packing::kP12LSB, "Mono12p", 12, 2, 3},
    {Packing::kP10GEV, "Mono10Packed", 10, 2, 3},
    {Packing::kP12GEV, "Mono12Packed", 12, 2, 3},
}};

// v (b significant bits) → 16 bits, by replicating the top bits into the low ones (b ≥ 8).
inline std::uint16_t Widen(std::uint32_t v, int b) {
  return static_cast<std::uint16_t>((v << (16 - b)) | (v >> (2 * b - 16)));
}

#ifdef RK_HAVE_SSSE3_KERNEL
// 8 pixels of `bits` (10 or 12) from the 16 bytes at `src` (only the first 8·bits/8 are used): `order` puts
// pixel k's high byte at lane k's byte 1 and its next byte at byte 0; multiplying by `scale` (2^(16-bits-s),
// s = the pixel's shift in its lane) aligns every pixel's top bit to bit 15, then >> (16 - bits) and the widening.
__attribute__((target("ssse3"))) inline void Unpack8Pixels(const std::uint8_t* src, __m128i order, __m128i scale, int bits,
                                                           std::uint16_t* dst) {
  __m128i v = _mm_shuffle_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(src)), order);
  v = _mm_srli_epi16(_mm_mullo_epi16(v, scale), 16 - bits);
  v = _mm_or_si128(_mm_slli_epi16(v, 16 - bits), _mm_srli_epi16(v, 2 * bits - 16));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(dst), v);
}

// The shuffle order and lane multipliers of 8 pixels of `bits` (10 or 12): pixel k's two bytes (high, low) and
// the factor that moves its top bit to bit 15 of its lane.
void KernelTables(int bits, std::int8_t order[16], std::int16_t scale[8]) {
  for (int k = 0; k < 8; ++k) {
    const int first_bit = k * bits;  // of the pixel, from the start of the 8-pixel group
    const int hi = first_bit / 8;
    const int s = 16 - bits - (first_bit % 8);  // its lowest bit in the 16-bit lane (hi, hi + 1)
    order[2 * k] = static_cast<std::int8_t>(hi + 1);
    order[2 * k + 1] = static_cast<std::int8_t>(hi);
    scale[k] = static_cast<std::int16_t>(1 << (16 - bits - s));
  }
}

// Groups of 8 pixels while 16 bytes can be loaded; returns the pixels done.
__attribute__((target("ssse3"))) std::uint64_t UnpackSsse3(int bits, const std::uint8_t* src, std::uint64_t pixels,
                                                           std::uint16_t* dst) {
  alignas(16) std::int8_t order[16];
  alignas(16) std::int16_t scale[8];
  KernelTables(bits, order, scale);
  const __m128i o = _mm_load_si128(reinterpret_cast<const __m128i*>(order));
  const __m128i m = _mm_load_si128(reinterpret_cast<const __m128i*>(scale));
  const std::uint64_t in_step = static_cast<std::uint64_t>(bits);  // bytes per 8 pixels
  std::uint64_t done = 0;
  const std::uint64_t bytes = pixels * in_step / 8;
  while (done + 8 <= pixels && done / 8 * in_step + 16 <= bytes) {
    Unpack8Pixels(src + done / 8 * in_step, o, m, bits, dst + done);
    done += 8;
  }
  return done;
}

bool HaveSsse3() {
  static const bool have = __builtin_cpu_supports("ssse3");
  return have;
}
#endif

void UnpackP12(const std::uint8_t* src, std::uint64_t pixels, std::uint16_t* dst) {
  std::uint64_t first = 0;
#ifdef RK_HAVE_SSSE3_KERNEL
  if (HaveSsse3()) first = UnpackSsse3(12, src, pixels, dst) / 2;
#endif
  const std::uint64_t groups = pixels / 2;
  for (std::uint64_t g = first; g < groups; ++g) {
    const std::uint32_t b0 = src[3 * g], b1 = src[3 * g + 1], b2 = src[3 * g + 2];
    const std::uint32_t v0 = (b0 << 4) | (b1 >> 4);
    const std::uint32_t v1 = ((b1 & 0x0Fu) << 8) | b2;
    dst[2 * g] = Widen(v0, 12);
    dst[2 * g + 1] = Widen(v1, 12);
  }
}

void UnpackP10(const std::uint8_t* src, std::uint64_t pixels, std::uint16_t* dst) {
  std::uint64_t first = 0;
#ifdef RK_HAVE_SSSE3_KERNEL
  if (HaveSsse3()) first = UnpackSsse3(10, src, pixels, dst) / 4;
#endif
  const std::uint64_t groups = pixels / 4;
  for (std::uint64_t g = first; g < groups; ++g) {
    const std::uint8_t* s = src + 5 * g;
    const std::uint32_t b0 = s[0], b1 = s[1], b2 = s[2], b3 = s[3], b4 = s[4];
    const std::uint32_t v0 = (b0 << 2) | (b1 >> 6);
    const std::uint32_t v1 = ((b1 & 0x3Fu) << 4) | (b2 >> 4);
    const std::uint32_t v2 = ((b2 & 0x0Fu) << 6) | (b3 >> 2);
    const std::uint32_t v3 = ((b3 & 0x03u) << 8) | b4;
    std::uint16_t* d = dst + 4 * g;
    d[0] = Widen(v0, 10);
    d[1] = Widen(v1, 10);
    d[2] = Widen(v2, 10);
    d[3] = Widen(v3, 10);
  }
}

// The GenICam packings (a camera's stream, not a file read in place: no SIMD kernel, the frame is small
// beside the network's time).
void UnpackGenICam(Packing packing, const std::uint8_t* src, std::uint64_t pixels, std::uint16_t* dst) {
  switch (packing) {
    case Packing::kP10LSB:
      for (std::uint64_t g = 0; g < pixels / 4; ++g) {
        const std::uint8_t* s = src + 5 * g;
        const std::uint32_t b0 = s[0], b1 = s[1], b2 = s[2], b3 = s[3], b4 = s[4];
        std::uint16_t* d = dst + 4 * g;
        d[0] = Widen(b0 | ((b1 & 0x03u) << 8), 10);
        d[1] = Widen((b1 >> 2) | ((b2 & 0x0Fu) << 6), 10);
        d[2] = Widen((b2 >> 4) | ((b3 & 0x3Fu) << 4), 10);
        d[3] = Widen((b3 >> 6) | (b4 << 2), 10);
      }
      return;
    case Packing::kP12LSB:
      for (std::uint64_t g = 0; g < pixels / 2; ++g) {
        const std::uint32_t b0 = src[3 * g], b1 = src[3 * g + 1], b2 = src[3 * g + 2];
        dst[2 * g] = Widen(b0 | ((b1 & 0x0Fu) << 8), 12);
        dst[2 * g + 1] = Widen((b1 >> 4) | (b2 << 4), 12);
      }
      return;
    case Packing::kP10GEV:
      for (std::uint64_t g = 0; g < pixels / 2; ++g) {
        const std::uint32_t b0 = src[3 * g], b1 = src[3 * g + 1], b2 = src[3 * g + 2];
        dst[2 * g] = Widen((b0 << 2) | (b1 & 0x03u), 10);
        dst[2 * g + 1] = Widen((b2 << 2) | ((b1 >> 4) & 0x03u), 10);
      }
      return;
    case Packing::kP12GEV:
      for (std::uint64_t g = 0; g < pixels / 2; ++g) {
        const std::uint32_t b0 = src[3 * g], b1 = src[3 * g + 1], b2 = src[3 * g + 2];
        dst[2 * g] = Widen((b0 << 4) | (b1 & 0x0Fu), 12);
        dst[2 * g + 1] = Widen((b2 << 4) | (b1 >> 4), 12);
      }
      return;
    default:
      throw std::logic_error("video: not a GenICam packing");
  }
}

// 16-bit little-endian samples of `bits` significant bits.
std::uint64_t UnpackU16(int bits, const std::uint8_t* src, std::uint64_t pixels, std::uint16_t* dst) {
  if (static_cast<const void*>(dst) != static_cast<const void*>(src)) std::memcpy(dst, src, pixels * 2);  // x86-64 and every target Debian builds rangekit for: little-endian
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
    case Packing::kP10LSB:
    case Packing::kP12LSB:
    case Packing::kP10GEV:
    case Packing::kP12GEV:
      UnpackGenICam(packing, src, pixels, dst16);
      return 0;
    case Packing::kU8:
      break;
  }
  throw std::logic_error("video: Unpack16 of an 8-bit packing");
}

void Unpack8(const std::uint8_t* src, std::uint64_t pixels, std::uint8_t* dst8) { std::memcpy(dst8, src, pixels); }

}  // namespace rk::video
