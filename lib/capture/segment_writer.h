// Video of one camera, written as segments that rk-extract --video reads unchanged (SPEC.md §6).
//
// Lossless and cheap enough for 2 × 2448×2048 × 20 fps (200 MB/s) on 2 cores, where FFV1 cannot keep
// up (≈ 58 ms to decode one 5-Mpixel frame here, more to encode):
//   y4m  "<cam>/seg_000.y4m": YUV4MPEG2, uncompressed 8-bit mono (C mono) or 16-bit little-endian
//        (C mono16); header line "YUV4MPEG2 W<w> H<h> F<num>:<den> Ip A1:1 C<mono|mono16>\n", then
//        per frame "FRAME\n" + w·h samples. One write per frame; a torn last frame (power cut) is
//        cut off by `rk-capture recover` (ffmpeg skips it even without that).
//   pgm  "<cam>/seg_000/%06d.pgm": one binary PGM (P5; 16-bit big-endian) per frame, written to a
//        hidden temporary and renamed, so a frame file is either complete or absent.
// Segment k holds frames [k·n, (k+1)·n) of the camera's frames.csv, n = round(segment_s · fps).
#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "capture/durable_file.h"
#include "video/y4m.h"

namespace rk::capture {

// The frame format and its YUV4MPEG2 header line live with the reader (video/y4m.h).
using video::FrameFormat;
using video::ParseY4mHeader;
using video::Y4mHeader;


class SegmentWriter {
 public:
  virtual ~SegmentWriter() = default;
  // Path of segment `index`, relative to the trial folder, as listed in the manifest.
  virtual std::string SegmentPath(int index) const = 0;
  // Starts segment `index` (a file or folder). False with the reason on failure.
  virtual bool Begin(int index, std::string* why) = 0;
  // Writes one frame (CV_8UC1 or CV_16UC1 of the format's size), all or nothing.
  virtual bool Write(const cv::Mat& frame, std::string* why) = 0;
  // Removes the frame written last (when its frames.csv row could not be written).
  virtual bool UndoLast(std::string* why) = 0;
  // Ends the segment (handed to the Syncer for its last sync).
  virtual void End() = 0;
  std::int64_t frames_in_segment() const { return frames_; }
  bool open() const { return open_; }
  // The last Write failed because the file reached its size limit (EFBIG): a new segment helps.
  bool file_too_large() const { return too_large_; }

 protected:
  std::int64_t frames_ = 0;
  bool open_ = false;
  bool too_large_ = false;
};

// format "y4m" or "pgm"; `trial_dir` the trial folder, `camera` the camera's folder name in it.
std::unique_ptr<SegmentWriter> MakeSegmentWriter(const std::string& format, const std::string& trial_dir,
                                                 const std::string& camera, const FrameFormat& frame_format,
                                                 Syncer* syncer);

}  // namespace rk::capture
