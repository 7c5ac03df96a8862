// Pixel packings of high-speed camera files and of GenICam cameras (rk-capture aravis:), as one table (kPackings): how many pixels a group of bytes
// holds and in which bit order, and the one unpacking loop per packing. Deep samples are delivered as
// 16-bit, scaled to the full 16-bit range by bit replication (v << (16 - b) | v >> (2b - 16)), as ffmpeg
// delivers a 10- or 12-bit source as gray16le: a recording read here and the same recording decoded by
// ffmpeg give equal frames.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace rk::video {

enum class Packing {
  kU8,      // one byte per pixel
  kU16LE,   // two bytes per pixel, little-endian (Phantom 16-bit, Photron 16-bit MRAW)
  kP10BE,   // four pixels in five bytes, most significant bit first (Phantom "packed 10-bit", biCompression 256)
  kP12BE,   // two pixels in three bytes, most significant bit first (Photron 12-bit MRAW, Phantom P12L, 1024)
  kP10LSB,  // four pixels in five bytes, least significant bit first (GenICam PFNC Mono10p)
  kP12LSB,  // two pixels in three bytes, least significant bit first (GenICam PFNC Mono12p)
  kP10GEV,  // two pixels in three bytes: each pixel's 8 high bits in its own byte, both pixels' 2 low bits in the
            // middle one, pixel 0's in bits 0–1, pixel 1's in bits 4–5 (GigE Vision Mono10Packed)
  kP12GEV,  // the same with 4 low bits: pixel 0's in bits 0–3, pixel 1's in bits 4–7 (GigE Vision Mono12Packed)
};

struct PackingInfo {
  Packing packing;
  const char* name;        // for messages and reports: "8-bit", "16-bit LE", "10-bit packed", "12-bit packed"
  int bits_per_pixel;      // stored bits per pixel: 8, 16, 10, 12
  int pixels_per_group;    // 1, 1, 4, 2
  int bytes_per_group;     // 1, 2, 5, 3
};

const PackingInfo& InfoOf(Packing packing);

// Bytes that `pixels` pixels take in `packing`; `pixels` must fill whole groups (CheckPixelCount).
std::uint64_t PackedBytes(Packing packing, std::uint64_t pixels);
// True when `pixels` fills whole groups of `packing` (a 10-bit packed row of 6 pixels does not).
bool FillsGroups(Packing packing, std::uint64_t pixels);

// Unpacks `pixels` pixels from `src` (PackedBytes(packing, pixels) bytes) into `dst`: 8-bit packings into
// 8-bit `dst8`, the others into 16-bit `dst16`, each sample of `significant_bits` (its low bits; 1..16)
// scaled to 16 bits by bit replication. `significant_bits` 16 copies; a sample above its bit range (a 12-bit
// sample > 4095 in a 16-bit container) is clamped to 65535 and counted in the return value.
// In place: `src` may be the last PackedBytes(packing, pixels) bytes of `dst16`'s own buffer (the frame is read
// there and widened forward): every group is loaded before its pixels are stored, and a group's output ends at
// or before the first packed byte not yet loaded (for N pixels the packed bytes start at 2N − PackedBytes; the
// output of pixels [i, i + 8) ends at 2i + 16, the next group starts at 2N − PackedBytes + PackedBytes(i + 8),
// which is ≥ 2i + 16 while i ≤ N − 8; likewise for the scalar groups). Tested at every length.
std::uint64_t Unpack16(Packing packing, int significant_bits, const std::uint8_t* src, std::uint64_t pixels,
                       std::uint16_t* dst16);
void Unpack8(const std::uint8_t* src, std::uint64_t pixels, std::uint8_t* dst8);

}  // namespace rk::video
