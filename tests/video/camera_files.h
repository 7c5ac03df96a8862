// Test-side writers of Phantom CINE and Photron MRAW files, written from the format descriptions
// (lib/video/cine_file.cc's layout comment; Photron's CIHX/CIH keys), independent of the parsers: a generic
// most-significant-bit-first bit writer packs the samples. Used by the unit tests and the fuzz seeds.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace rk::video::testing {

// Appends `bits` bits of `v`, most significant first.
class BitWriter {
 public:
  void Put(std::uint32_t v, int bits) {
    for (int b = bits - 1; b >= 0; --b) {
      if (used_ == 0) bytes_.push_back(0);
      if ((v >> b) & 1u) bytes_.back() = static_cast<std::uint8_t>(bytes_.back() | (0x80u >> used_));
      used_ = (used_ + 1) % 8;
    }
  }
  std::vector<std::uint8_t> bytes() const { return bytes_; }

 private:
  std::vector<std::uint8_t> bytes_;
  int used_ = 0;
};

inline void PutLe(std::vector<std::uint8_t>* b, std::size_t at, std::uint64_t v, int n) {
  if (b->size() < at + static_cast<std::size_t>(n)) b->resize(at + static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) (*b)[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(v >> (8 * i));
}

// Samples of one frame, top row first, each of the stored bit depth.
using Samples = std::vector<std::uint16_t>;

struct CineSpec {
  int width = 16, height = 6;
  int bit_count = 16;             // 8 or 16 (biBitCount)
  std::uint32_t compression = 0;  // biCompression: 0, 256 (10-bit packed), 1024 (12-bit packed)
  std::uint16_t file_compression = 0;  // CINEFILEHEADER.Compression: 0 grey, 2 raw Bayer
  std::uint32_t cfa = 0;
  std::uint32_t real_bpp = 12;
  std::uint32_t rate_hz = 1000;
  std::uint32_t shutter_ns = 500000;
  std::int32_t first_image_no = -2;
  std::uint32_t trigger_seconds = 0, trigger_fractions = 0;
  std::vector<std::uint64_t> stamps;      // per image: seconds << 32 | fractions; empty: no time block
  std::vector<std::uint32_t> exposures;   // per image, 2^-32 s; empty: no exposure block
  bool top_down_height = false;           // write a negative biHeight
  std::uint16_t setup_length = 1600;
};

// Stored bits per sample of a spec.
inline int StoredBits(const CineSpec& s) {
  return s.compression == 256 ? 10 : s.compression == 1024 ? 12 : s.bit_count;
}

inline std::vector<std::uint8_t> PackFrame(const CineSpec& s, const Samples& top_down) {
  const int bits = StoredBits(s);
  std::vector<std::uint8_t> out;
  const bool bottom_up = s.compression == 0 && !s.top_down_height;
  for (int r = 0; r < s.height; ++r) {
    const int row = bottom_up ? s.height - 1 - r : r;
    const std::uint16_t* px = top_down.data() + static_cast<std::size_t>(row) * static_cast<std::size_t>(s.width);
    if (bits == 8 || bits == 16) {
      for (int x = 0; x < s.width; ++x) {
        out.push_back(static_cast<std::uint8_t>(px[x]));
        if (bits == 16) out.push_back(static_cast<std::uint8_t>(px[x] >> 8));
      }
    } else {
      BitWriter w;
      for (int x = 0; x < s.width; ++x) w.Put(px[x], bits);
      const auto b = w.bytes();
      out.insert(out.end(), b.begin(), b.end());
    }
  }
  return out;
}

inline std::vector<std::uint8_t> MakeCine(const CineSpec& s, const std::vector<Samples>& frames) {
  std::vector<std::uint8_t> b;
  const std::size_t n = frames.size();
  const std::size_t off_setup = 84;
  // Tagged blocks after the setup.
  std::vector<std::uint8_t> tags;
  if (!s.stamps.empty()) {
    const std::size_t at = tags.size();
    PutLe(&tags, at, 8 + 8 * n, 4);
    PutLe(&tags, at + 4, 1002, 2);
    PutLe(&tags, at + 6, 0, 2);
    for (std::size_t i = 0; i < n; ++i) PutLe(&tags, at + 8 + 8 * i, s.stamps[i], 8);
  }
  if (!s.exposures.empty()) {
    const std::size_t at = tags.size();
    PutLe(&tags, at, 8 + 4 * n, 4);
    PutLe(&tags, at + 4, 1003, 2);
    PutLe(&tags, at + 6, 0, 2);
    for (std::size_t i = 0; i < n; ++i) PutLe(&tags, at + 8 + 4 * i, s.exposures[i], 4);
  }
  const std::size_t off_offsets = off_setup + s.setup_length + tags.size();
  // CINEFILEHEADER
  PutLe(&b, 0, 0x4943, 2);
  PutLe(&b, 2, 44, 2);
  PutLe(&b, 4, s.file_compression, 2);
  PutLe(&b, 6, 1, 2);
  PutLe(&b, 8, static_cast<std::uint32_t>(s.first_image_no), 4);
  PutLe(&b, 12, n, 4);
  PutLe(&b, 16, static_cast<std::uint32_t>(s.first_image_no), 4);
  PutLe(&b, 20, n, 4);
  PutLe(&b, 24, 44, 4);
  PutLe(&b, 28, off_setup, 4);
  PutLe(&b, 32, off_offsets, 4);
  PutLe(&b, 36, s.trigger_fractions, 4);
  PutLe(&b, 40, s.trigger_seconds, 4);
  // BITMAPINFOHEADER
  const std::vector<std::uint8_t> first = PackFrame(s, frames.empty() ? Samples(static_cast<std::size_t>(s.width * s.height)) : frames[0]);
  PutLe(&b, 44, 40, 4);
  PutLe(&b, 48, static_cast<std::uint32_t>(s.width), 4);
  PutLe(&b, 52, static_cast<std::uint32_t>(s.top_down_height ? -s.height : s.height), 4);
  PutLe(&b, 56, 1, 2);
  PutLe(&b, 58, static_cast<std::uint32_t>(s.bit_count), 2);
  PutLe(&b, 60, s.compression, 4);
  PutLe(&b, 64, first.size(), 4);
  PutLe(&b, 80, 0, 4);
  // SETUP
  b.resize(off_setup + s.setup_length, 0);
  PutLe(&b, off_setup + 140, 0x5453, 2);
  PutLe(&b, off_setup + 142, s.setup_length, 2);
  PutLe(&b, off_setup + 768, s.rate_hz, 4);
  PutLe(&b, off_setup + 772, s.shutter_ns / 1000, 4);
  PutLe(&b, off_setup + 808, s.cfa, 4);
  PutLe(&b, off_setup + 896, s.real_bpp, 4);
  if (s.setup_length >= 1572) PutLe(&b, off_setup + 1568, s.shutter_ns, 4);
  b.insert(b.end(), tags.begin(), tags.end());
  // Image offsets, then each image: annotation {size 8 = itself + image size}, image.
  std::size_t at = off_offsets + 8 * n;
  b.resize(at, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::vector<std::uint8_t> img = PackFrame(s, frames[i]);
    PutLe(&b, off_offsets + 8 * i, at, 8);
    PutLe(&b, at, 8, 4);
    PutLe(&b, at + 4, img.size(), 4);
    b.insert(b.end(), img.begin(), img.end());
    at = b.size();
  }
  return b;
}

// A Photron .cihx: Photron's binary preamble (a banner, zeros, "CIHX"), the XML, then a trailing binary block.
inline std::string MakeCihx(int width, int height, int bits, int total, int start, int skip, int rate,
                            int shutter_ns, const std::string& type = "Mono") {
  std::string pre = "!!! This file can not be edited. !!!";
  pre.resize(0x100, '\0');
  pre += "CIHX";
  pre.resize(0x13c, '\0');
  std::string xml = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\r\n<cih>\r\n  <fileInfo><version>1.0</version></fileInfo>\r\n"
                    "  <imageFileInfo><fileFormat>Mraw</fileFormat></imageFileInfo>\r\n"
                    "  <imageDataInfo>\r\n    <resolution>\r\n      <width>" + std::to_string(width) + "</width>\r\n      <height>" +
                    std::to_string(height) + "</height>\r\n    </resolution>\r\n    <colorInfo>\r\n      <type>" + type +
                    "</type>\r\n      <bit>" + std::to_string(bits) + "</bit>\r\n    </colorInfo>\r\n"
                    "    <effectiveBit><depth>12</depth><side>Lower</side></effectiveBit>\r\n  </imageDataInfo>\r\n"
                    "  <frameInfo>\r\n    <totalFrame>" + std::to_string(total) + "</totalFrame>\r\n    <startFrame>" +
                    std::to_string(start) + "</startFrame>\r\n    <skipFrame>" + std::to_string(skip) + "</skipFrame>\r\n  </frameInfo>\r\n"
                    "  <recordInfo>\r\n    <recordRate>" + std::to_string(rate) + "</recordRate>\r\n    <shutterSpeedNsec>" +
                    std::to_string(shutter_ns) + "</shutterSpeedNsec>\r\n  </recordInfo>\r\n</cih>\r\n";
  std::string tail(64, '\x01');
  return pre + xml + tail;
}

// A Photron .cih (text).
inline std::string MakeCih(int width, int height, int bits, int total, int start, int rate, const std::string& shutter) {
  return "#Camera Information Header\nDate : 2016/4/21\nRecord Rate(fps) : " + std::to_string(rate) +
         "\nShutter Speed(s) : " + shutter + "\nTotal Frame : " + std::to_string(total) + "\nStart Frame : " +
         std::to_string(start) + "\nImage Width : " + std::to_string(width) + "\nImage Height : " + std::to_string(height) +
         "\nColor Type : Mono\nColor Bit : " + std::to_string(bits) +
         "\nFile Format : MRaw\nEffectiveBit Depth : 12\nEffectiveBit Side : Lower\n\nEND\n";
}

// MRAW data: frames one after another, 8-bit, 12-bit packed (big-endian bit order) or 16-bit little-endian.
inline std::vector<std::uint8_t> MakeMraw(int bits, const std::vector<Samples>& frames) {
  std::vector<std::uint8_t> out;
  for (const Samples& f : frames) {
    if (bits == 12) {
      BitWriter w;
      for (std::uint16_t v : f) w.Put(v, 12);
      const auto b = w.bytes();
      out.insert(out.end(), b.begin(), b.end());
    } else {
      for (std::uint16_t v : f) {
        out.push_back(static_cast<std::uint8_t>(v));
        if (bits == 16) out.push_back(static_cast<std::uint8_t>(v >> 8));
      }
    }
  }
  return out;
}

}  // namespace rk::video::testing
