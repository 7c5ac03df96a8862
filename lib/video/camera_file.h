// High-speed camera files read directly (SPEC.md §1.1 "Recordings"): Phantom CINE and Photron MRAW with
// its .cihx or .cih. A parser turns the file's headers into one CameraFile: frame size, packing, the
// colour filter (a Bayer image is used as grey, by OpenCV's demosaicing), where each frame's bytes are and
// each frame's time as the file gives it. Every fault of the file is a ByteOffsetError (byte offset) or,
// in a CIHX, a DataError with the XML line: exit 3, nothing written.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "io/run_summary.h"
#include "video/binary_file.h"
#include "video/packed_pixels.h"

namespace rk::video {

// Where a frame's time comes from (SPEC.md §2.1 frames.csv `time_source`).
enum class TimeSource { kIrig, kCamera, kContainer, kHost, kNominal };
const char* TimeSourceName(TimeSource source);  // "irig", "camera", "container", "host", "nominal"

// One frame's time as the recording gives it.
struct FrameStamp {
  double t_s = 0.0;  // seconds after RecordingTimes::origin_s (absolute: origin_s + t_s is UTC)
  TimeSource source = TimeSource::kNominal;
  double exposure_s = std::numeric_limits<double>::quiet_NaN();
  double camera_ts_s = std::numeric_limits<double>::quiet_NaN();  // the camera's own clock
  bool event = false;                                              // CINE: the event input was high
};

// The frame times a recording carries.
struct RecordingTimes {
  bool absolute = false;        // origin_s + t_s are UTC (IRIG or the camera's real-time clock)
  double origin_s = 0.0;        // whole UTC seconds the frames' t_s count from, so they keep ns resolution
  double nominal_rate_hz = 0;   // the rate the file states (0: none)
  std::vector<FrameStamp> frames;
  std::string basis;            // one sentence: which of the file's times were used
  // What the file says of its times that the user must know: it disagrees with itself (times_disagree: time
  // block vs trigger time), or it was recorded on IRIG but keeps no stamps rangekit can read (irig_not_read).
  std::vector<io::Warning> warnings;
};

// What a camera file's headers say.
struct CameraFile {
  std::string format;   // "cine", "mraw"
  std::string path;     // the image data file
  std::string header;   // the file the headers were read from (the .cihx/.cih for MRAW; the .cine)
  int width = 0, height = 0;
  Packing packing = Packing::kU8;
  int significant_bits = 8;  // bits of each sample (10 for Phantom's packed 10-bit)
  int bayer_to_gray = -1;    // cv::COLOR_Bayer..2GRAY code for a Bayer image, -1 for mono
  std::string cfa;           // "mono", "GBRG", "RGGB", ...
  bool bottom_up = false;    // rows stored last row first (uncompressed CINE)
  std::vector<std::uint64_t> frame_offsets;  // byte offset of each frame's image data in `path`
  std::uint64_t frame_bytes = 0;
  RecordingTimes times;
};

// Parses a CINE file's header, bitmap header, setup, tagged blocks (time, exposure) and image offsets.
CameraFile ParseCine(const ByteView& file);

// Photron headers: the CIHX (XML after a binary preamble, parsed with tinyxml2; errors name the XML line)
// and the CIH (text "Key : Value" lines). `data_path`/`data_size`: the .mraw they describe; its size must
// hold exactly the frames the header counts.
CameraFile ParseCihx(const ByteView& header, const std::string& data_path, std::uint64_t data_size);
CameraFile ParseCih(const ByteView& header, const std::string& data_path, std::uint64_t data_size);

// True for a path rangekit reads as a camera file: .cine, .mraw, .cihx, .cih (any case).
bool IsCameraFile(const std::string& path);

// Opens a camera file: for MRAW, the .cihx (else .cih) of the same stem beside the .mraw, or the
// .mraw of the .cihx/.cih given. IoError when a file is missing; DataError as above.
class CameraFileReader {
 public:
  explicit CameraFileReader(const std::string& path);
  const CameraFile& file() const { return file_; }
  std::int64_t frames() const { return static_cast<std::int64_t>(file_.frame_offsets.size()); }
  // Frame `index` as CV_8UC1 (8-bit mono) or CV_16UC1 (deeper, scaled to 16 bits), grey from a Bayer
  // mosaic by OpenCV's demosaicing; `out` is reused when it has the size and type.
  void Read(std::int64_t index, cv::Mat* out);
  // Frame `index` as stored (before demosaicing; top row first): CV_8UC1 or CV_16UC1 scaled to 16 bits.
  void ReadMosaic(std::int64_t index, cv::Mat* out);
  // Samples above their bit range, clamped, so far.
  std::uint64_t clamped() const { return clamped_; }

 private:
  std::unique_ptr<MappedFile> data_;
  std::unique_ptr<MappedFile> header_;
  CameraFile file_;
  cv::Mat raw_;  // the mosaic before demosaicing
  std::vector<std::uint8_t> packed_;    // a bottom-up frame as stored (reused)
  std::uint64_t clamped_ = 0;
};

}  // namespace rk::video
