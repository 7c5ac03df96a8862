// YUV4MPEG2 (y4m) mono video, rk-capture's segment format (capture/segment_writer.h): the header line
// both sides share, and a reader that reads each frame's samples straight into the frame (pread) — one
// copy from the page cache, as dd makes, no decoder process, no pipe (rk-extract on rk-capture's segments reads at
// the speed of the disk; bench_video_read).
//   header  "YUV4MPEG2 W<w> H<h> F<num>:<den> [I.. A.. X..] C<mono|mono16>\n"
//   frame   "FRAME[ params]\n" then w·h samples (mono16: little-endian 16-bit)
#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "video/binary_file.h"

namespace rk::video {

struct FrameFormat {
  int width = 0;
  int height = 0;
  int bit_depth = 8;  // 8 or 16
  double fps = 20.0;
};

// The YUV4MPEG2 header for a format; "F" is the frame rate as a reduced fraction (29.97 → 2997:100).
std::string Y4mHeader(const FrameFormat& format);
// Parses a YUV4MPEG2 header line (without '\n'); false if it is not one rangekit reads itself
// (mono / mono16 only; other colour spaces go to ffmpeg).
bool ParseY4mHeader(const std::string& line, FrameFormat* format);

// True when `path` is a y4m file whose header ParseY4mHeader reads.
bool IsMonoY4m(const std::string& path);

class Y4mReader {
 public:
  // IoError if unreadable; DataError (byte offset) if the header is not a mono y4m header.
  explicit Y4mReader(const std::string& path);
  const FrameFormat& format() const { return format_; }
  // The next frame into `out` (CV_8UC1 / CV_16UC1, reused when it has the size); false at the end.
  // ByteOffsetError for a frame without its "FRAME" line or cut short (a torn last frame).
  bool Read(cv::Mat* out);
  std::int64_t frames_read() const { return frames_read_; }

 private:
  MappedFile file_;
  FrameFormat format_;
  std::uint64_t pos_ = 0;  // start of the next "FRAME" line
  std::uint64_t frame_bytes_ = 0;
  std::int64_t frames_read_ = 0;
};

}  // namespace rk::video
