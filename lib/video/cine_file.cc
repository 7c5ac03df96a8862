// Phantom CINE files (Vision Research "Cine File Format", software 13.5): the parser of camera_file.h.
//
// Layout read here (all little-endian):
//   CINEFILEHEADER at 0 (44 bytes): "CI", header size, compression (0 grey/colour, 1 JPEG, 2 raw Bayer),
//     version (1: 64-bit image offsets), first image number (relative to the trigger), image count, the
//     offsets of the bitmap header, setup and image offsets, and the trigger time (TIME64).
//   BITMAPINFOHEADER at OffImageHeader: width, height (< 0: rows stored top first), bits per pixel,
//     biCompression (0 unpacked; 256 Phantom's packed 10-bit; 1024 packed 12-bit "P12L").
//   SETUP at OffSetup: marker "ST" at +140 and its length at +142; a field is read only when the setup is
//     long enough to hold it (older software wrote shorter setups): FrameRate +768, Shutter (µs) +772,
//     CFA +808, RealBPP +896, ShutterNs +1568, dFrameRate +13472.
//   Tagged blocks from OffSetup + Length up to OffImageOffsets: {u32 size, u16 type, u16 reserved, data};
//     1002 = one TIME64 per image, 1003 = one exposure per image (u32, units of 2^-32 s); others skipped.
//   Image offsets at OffImageOffsets: one u64 per image, each pointing at {u32 annotation size, annotation,
//     u32 image size} followed by the image.
// TIME64 = {u32 fractions (2^-32 s), u32 seconds since 1970 UTC}; in a per-image stamp the two lowest
// fraction bits are flags: bit 0 = 0 IRIG-synchronised, bit 1 = event input.
#include <opencv2/imgproc.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <type_traits>

#include "io/error.h"
#include "video/camera_file.h"

namespace rk::video {
namespace {

constexpr std::uint64_t kSetupMark = 140, kSetupLength = 142;

// A setup field: its offset in SETUP and its size, read only when SETUP's Length holds it.
struct SetupField {
  std::uint64_t offset, size;
  const char* name;
};
constexpr SetupField kFrameRate{768, 4, "setup FrameRate"};
constexpr SetupField kShutterUs{772, 4, "setup Shutter"};
constexpr SetupField kCfa{808, 4, "setup CFA"};
constexpr SetupField kRealBpp{896, 4, "setup RealBPP"};
constexpr SetupField kShutterNs{1568, 4, "setup ShutterNs"};
constexpr SetupField kDFrameRate{13472, 8, "setup dFrameRate"};

constexpr std::uint16_t kTimeBlock = 1002, kExposureBlock = 1003;
constexpr double kTwoTo32 = 4294967296.0;

// The CFA codes (low 24 bits of SETUP.CFA) rangekit reads and OpenCV's conversion of each to grey.
struct CfaEntry {
  std::uint32_t code;
  const char* pattern;
  int to_gray;
};
constexpr std::array<CfaEntry, 3> kCfas{{
    {0, "mono", -1},
    {3, "GBRG", cv::COLOR_BayerGR2GRAY},  // CFA_BAYER: gb/rg (OpenCV names the pattern from the second row)
    {4, "RGGB", cv::COLOR_BayerBG2GRAY},  // CFA_BAYERFLIP: rg/gb
}};

// The biCompression values and their packing.
struct CompressionEntry {
  std::uint32_t code;
  int bit_count;  // biBitCount it goes with (0: any of 8, 16)
  Packing packing;
};
constexpr std::array<CompressionEntry, 4> kCompressions{{
    {0, 8, Packing::kU8},
    {0, 16, Packing::kU16LE},
    {256, 0, Packing::kP10BE},
    {1024, 0, Packing::kP12BE},
}};

std::string UtcText(double unix_s) {
  const std::time_t t = static_cast<std::time_t>(std::floor(unix_s));
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[96];
  std::snprintf(buf, sizeof buf, "%04d-%02d-%02dT%02d:%02d:%02d.%06dZ", tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday,
                tm.tm_hour, tm.tm_min, tm.tm_sec, static_cast<int>((unix_s - std::floor(unix_s)) * 1e6));
  return buf;
}

struct Header {
  std::uint16_t compression = 0;
  std::int32_t first_image_no = 0;
  std::uint32_t image_count = 0;
  std::uint32_t off_image_header = 0, off_setup = 0, off_image_offsets = 0;
  std::uint32_t trigger_fractions = 0, trigger_seconds = 0;
  std::uint16_t setup_length = 0;
};

Header ReadFileHeader(const ByteView& v) {
  Header h;
  if (v.U16(0, "file header") != 0x4943) v.Fail(0, "not a Phantom CINE file (no \"CI\" at the start)");
  const std::uint16_t header_size = v.U16(2, "header size");
  if (header_size < 44) v.Fail(2, "header size " + std::to_string(header_size) + " is below the 44 bytes of CINEFILEHEADER");
  h.compression = v.U16(4, "compression");
  if (h.compression == 1) v.Fail(4, "JPEG-compressed CINE is not supported (save the cine uncompressed or packed)");
  if (h.compression > 2) v.Fail(4, "unknown compression " + std::to_string(h.compression) + " (0, 1 or 2)");
  const std::uint16_t version = v.U16(6, "version");
  if (version != 1) v.Fail(6, "CINE version " + std::to_string(version) + " (only version 1, 64-bit image offsets)");
  h.first_image_no = v.I32(16, "first image number");
  h.image_count = v.U32(20, "image count");
  if (h.image_count == 0) v.Fail(20, "the file holds no image (image count 0)");
  h.off_image_header = v.U32(24, "bitmap header offset");
  h.off_setup = v.U32(28, "setup offset");
  h.off_image_offsets = v.U32(32, "image offsets offset");
  h.trigger_fractions = v.U32(36, "trigger time");
  h.trigger_seconds = v.U32(40, "trigger time");
  if (v.U16(h.off_setup + kSetupMark, "setup marker") != 0x5453) v.Fail(h.off_setup + kSetupMark, "no \"ST\" marker of the setup");
  h.setup_length = v.U16(h.off_setup + kSetupLength, "setup length");
  if (h.setup_length < kCfa.offset + kCfa.size) {
    v.Fail(h.off_setup + kSetupLength, "setup length " + std::to_string(h.setup_length) + " is too short for the frame rate and colour filter");
  }
  if (h.off_image_offsets < std::uint64_t{h.off_setup} + h.setup_length) {
    v.Fail(32, "image offsets at byte " + std::to_string(h.off_image_offsets) + " overlap the setup");
  }
  return h;
}

// Reads a setup field if the setup holds it.
template <typename T>
bool SetupValue(const ByteView& v, const Header& h, const SetupField& f, T* out) {
  if (f.offset + f.size > h.setup_length) return false;
  if constexpr (std::is_same_v<T, double>) {
    *out = v.F64(h.off_setup + f.offset, f.name);
  } else {
    *out = v.U32(h.off_setup + f.offset, f.name);
  }
  return true;
}

void ReadBitmap(const ByteView& v, const Header& h, CameraFile* cf) {
  const std::uint64_t b = h.off_image_header;
  const std::uint32_t size = v.U32(b, "bitmap header");
  if (size < 40) v.Fail(b, "bitmap header size " + std::to_string(size) + " is below 40");
  const std::int32_t width = v.I32(b + 4, "image width");
  const std::int32_t height = v.I32(b + 8, "image height");
  const std::uint16_t bit_count = v.U16(b + 14, "bits per pixel");
  const std::uint32_t compression = v.U32(b + 16, "biCompression");
  if (width <= 0 || width > 65536) v.Fail(b + 4, "image width " + std::to_string(width) + " out of 1..65536");
  if (height == 0 || height < -65536 || height > 65536) v.Fail(b + 8, "image height " + std::to_string(height) + " out of 1..65536");
  if (bit_count == 24 || bit_count == 48) v.Fail(b + 14, "colour-interpolated CINE (" + std::to_string(bit_count) + " bits per pixel) is not supported: save it as raw Bayer or grey");
  const CompressionEntry* entry = nullptr;
  for (const CompressionEntry& e : kCompressions) {
    if (e.code == compression && (e.bit_count == 0 || e.bit_count == bit_count)) entry = &e;
  }
  if (!entry) {
    v.Fail(compression == 0 ? b + 14 : b + 16, "unknown bit depth or packing: " + std::to_string(bit_count) +
                                                   " bits per pixel, biCompression " + std::to_string(compression) +
                                                   " (known: 8 or 16 bits unpacked, 256 packed 10-bit, 1024 packed 12-bit)");
  }
  cf->width = width;
  cf->height = height < 0 ? -height : height;
  cf->packing = entry->packing;
  // Uncompressed images are stored bottom-up (a negative height says top-down); packed ones top-down.
  cf->bottom_up = compression == 0 && height > 0;
  if (!FillsGroups(cf->packing, static_cast<std::uint64_t>(cf->width))) {
    v.Fail(b + 4, "image width " + std::to_string(width) + " is not a whole number of " + InfoOf(cf->packing).name + " groups");
  }
  cf->frame_bytes = PackedBytes(cf->packing, static_cast<std::uint64_t>(cf->width) * static_cast<std::uint64_t>(cf->height));
}

void ReadSetup(const ByteView& v, const Header& h, CameraFile* cf, double* rate_hz, double* shutter_s) {
  std::uint32_t cfa = 0, real_bpp = 0, rate = 0, shutter = 0;
  SetupValue(v, h, kCfa, &cfa);
  const std::uint32_t code = cfa & 0xFFFFFFu;
  const CfaEntry* entry = nullptr;
  for (const CfaEntry& e : kCfas) {
    if (e.code == code) entry = &e;
  }
  if (h.compression == 2 && (!entry || code == 0)) {
    v.Fail(h.off_setup + kCfa.offset, "raw CINE with colour filter code " + std::to_string(code) + " (known: 3 GBRG, 4 RGGB)");
  }
  cf->bayer_to_gray = h.compression == 2 ? entry->to_gray : -1;
  cf->cfa = h.compression == 2 ? entry->pattern : "mono";
  const int stored = InfoOf(cf->packing).bits_per_pixel;
  cf->significant_bits = stored;
  if (cf->packing == Packing::kU16LE && SetupValue(v, h, kRealBpp, &real_bpp)) {
    if (real_bpp < 8 || real_bpp > 16) v.Fail(h.off_setup + kRealBpp.offset, "RealBPP " + std::to_string(real_bpp) + " out of 8..16");
    cf->significant_bits = static_cast<int>(real_bpp);
  }
  double d_rate = 0;
  if (SetupValue(v, h, kDFrameRate, &d_rate) && std::isfinite(d_rate) && d_rate > 0 && d_rate < 1e8) {
    *rate_hz = d_rate;
  } else if (SetupValue(v, h, kFrameRate, &rate)) {
    *rate_hz = rate;
  }
  if (SetupValue(v, h, kShutterNs, &shutter) && shutter > 0) {
    *shutter_s = shutter * 1e-9;
  } else if (SetupValue(v, h, kShutterUs, &shutter) && shutter > 0) {
    *shutter_s = shutter * 1e-6;
  }
}

// The tagged blocks between the setup and the image offsets: per-image time and exposure.
void ReadTaggedBlocks(const ByteView& v, const Header& h, std::vector<std::uint64_t>* stamps,
                      std::vector<std::uint32_t>* exposures) {
  std::uint64_t pos = std::uint64_t{h.off_setup} + h.setup_length;
  const std::uint64_t end = h.off_image_offsets;
  while (pos + 8 <= end) {
    const std::uint32_t size = v.U32(pos, "tagged block size");
    const std::uint16_t type = v.U16(pos + 4, "tagged block type");
    if (size < 8 || pos + size > end) {
      v.Fail(pos, "tagged block " + std::to_string(type) + " of " + std::to_string(size) + " bytes runs past the image offsets at byte " + std::to_string(end));
    }
    const std::uint64_t n = h.image_count;
    if (type == kTimeBlock || type == kExposureBlock) {
      const std::uint64_t each = type == kTimeBlock ? 8 : 4;
      if ((size - 8) / each < n) {
        v.Fail(pos, std::string(type == kTimeBlock ? "time" : "exposure") + " block holds " + std::to_string((size - 8) / each) + " entries for " + std::to_string(n) + " images");
      }
      for (std::uint64_t i = 0; i < n; ++i) {
        if (type == kTimeBlock) {
          stamps->push_back(v.U64(pos + 8 + 8 * i, "time stamp"));
        } else {
          exposures->push_back(v.U32(pos + 8 + 4 * i, "exposure"));
        }
      }
    }
    pos += size;
  }
}

void ReadImageOffsets(const ByteView& v, const Header& h, CameraFile* cf) {
  v.Need(h.off_image_offsets, 8 * std::uint64_t{h.image_count}, std::to_string(h.image_count) + " image offsets");
  cf->frame_offsets.reserve(h.image_count);
  for (std::uint64_t i = 0; i < h.image_count; ++i) {
    const std::uint64_t at = h.off_image_offsets + 8 * i;
    const std::uint64_t p = v.U64(at, "image offset");
    const std::uint32_t annotation = v.U32(p, "annotation of image " + std::to_string(i));
    if (annotation < 8) v.Fail(p, "annotation size " + std::to_string(annotation) + " of image " + std::to_string(i) + " is below 8");
    const std::uint64_t image = p + annotation;
    const std::uint32_t image_size = v.U32(image - 4, "image size");
    if (image_size != 0 && image_size < cf->frame_bytes) {
      v.Fail(image - 4, "image " + std::to_string(i) + " holds " + std::to_string(image_size) + " bytes; its size needs " + std::to_string(cf->frame_bytes));
    }
    v.Need(image, cf->frame_bytes, "image " + std::to_string(i));
    cf->frame_offsets.push_back(image);
  }
}

// Frame times: the time block's stamps when there is one (absolute, IRIG flag per image), else the
// trigger time plus the image number over the frame rate (nominal). A trigger time that disagrees with the
// time block by more than a frame interval is said.
void BuildTimes(const Header& h, double rate_hz, double shutter_s, const std::vector<std::uint64_t>& stamps,
                const std::vector<std::uint32_t>& exposures, CameraFile* cf) {
  RecordingTimes& t = cf->times;
  t.nominal_rate_hz = rate_hz;
  const double trigger = h.trigger_seconds + (h.trigger_fractions & ~3u) / kTwoTo32;
  const std::size_t n = h.image_count;
  // Whole seconds of the first stamp (or the trigger): every t_s counts from them, exact to the fraction.
  t.origin_s = !stamps.empty() ? static_cast<double>(stamps[0] >> 32) : h.trigger_seconds;
  t.frames.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    FrameStamp& f = t.frames[i];
    f.exposure_s = !exposures.empty() ? exposures[i] / kTwoTo32 : (shutter_s > 0 ? shutter_s : f.exposure_s);
    if (!stamps.empty()) {
      const auto fractions = static_cast<std::uint32_t>(stamps[i] & 0xFFFFFFFFu);
      const auto seconds = static_cast<std::uint32_t>(stamps[i] >> 32);
      f.t_s = (static_cast<double>(seconds) - t.origin_s) + (fractions & ~3u) / kTwoTo32;
      f.source = (fractions & 1u) == 0 ? TimeSource::kIrig : TimeSource::kCamera;
      f.event = (fractions & 2u) != 0;
      f.camera_ts_s = t.origin_s + f.t_s;
    } else if (rate_hz > 0) {
      f.camera_ts_s = (h.first_image_no + static_cast<double>(i)) / rate_hz;  // since the trigger
      f.t_s = (h.trigger_seconds ? trigger - t.origin_s : 0.0) + f.camera_ts_s;
      f.source = TimeSource::kNominal;
    }
  }
  t.absolute = !stamps.empty() || h.trigger_seconds != 0;
  if (!stamps.empty()) {
    t.basis = "per-image time block (tagged block 1002), UTC";
    if (h.trigger_seconds != 0 && rate_hz > 0) {
      // The image numbered 0 is the trigger frame: its stamp, from the first image's, against the trigger time.
      const double from_block = t.origin_s + t.frames[0].t_s - h.first_image_no / rate_hz;
      if (std::fabs(from_block - trigger) > 1.0 / rate_hz) {
        t.warnings.push_back({"times_disagree", "the time block (trigger frame at " + UtcText(from_block) + ") and the header's trigger time (" +
                             UtcText(trigger) + ") differ by " + std::to_string(std::fabs(from_block - trigger)) +
                             " s, more than a frame interval; the time block's stamps are used"});
      }
    }
  } else if (h.trigger_seconds != 0) {
    t.basis = "no time block: the trigger time (UTC) plus the image number over the frame rate";
  } else {
    t.basis = "no time block and no trigger time: the image number over the frame rate";
  }
}

}  // namespace

// Parses a CINE file (layout at the top of this file).
CameraFile ParseCine(const ByteView& v) {
  CameraFile cf;
  cf.format = "cine";
  cf.path = cf.header = v.file();
  const Header h = ReadFileHeader(v);
  ReadBitmap(v, h, &cf);
  double rate_hz = 0, shutter_s = 0;
  ReadSetup(v, h, &cf, &rate_hz, &shutter_s);
  std::vector<std::uint64_t> stamps;
  std::vector<std::uint32_t> exposures;
  ReadTaggedBlocks(v, h, &stamps, &exposures);
  ReadImageOffsets(v, h, &cf);
  if (stamps.empty() && !(rate_hz > 0)) v.Fail(h.off_setup + kFrameRate.offset, "no time block and no frame rate: the frames have no time");
  BuildTimes(h, rate_hz, shutter_s, stamps, exposures, &cf);
  return cf;
}

}  // namespace rk::video
