// Reading recorded video frame by frame, 8- or 16-bit mono, in decode order.
//
// A source is a list of segments (SPEC.md §1.1: --video may repeat), each
//   - a high-speed camera file, Phantom CINE or Photron MRAW (+ .cihx/.cih), read and unpacked here
//     (video/camera_file.h; a Bayer mosaic becomes grey by OpenCV's demosaicing);
//   - a mono y4m (rk-capture's segments), read here from the mapped file (video/y4m.h);
//   - any other video file, decoded by an ffmpeg child process into raw gray / gray16le (so 16-bit
//     FFV1 keeps all its bits and decoding runs beside the caller's work on another core);
//   - an image-sequence pattern such as "frames/%06d.png" (numbering starts at 0 or 1, read until
//     the first missing index).
// Frame numbers count on across segments.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace rk::video {

struct VideoInfo {
  int width = 0;
  int height = 0;
  int bit_depth = 8;  // 8 or 16 (deeper samples are scaled to 16 bits)
};

class CameraFileReader;
class Y4mReader;

class FrameSource {
 public:
  // Opens all segments lazily; throws IoError if a path cannot be read and
  // DataError if a file is not a decodable video / image.
  explicit FrameSource(std::vector<std::string> segments);
  ~FrameSource();
  FrameSource(const FrameSource&) = delete;
  FrameSource& operator=(const FrameSource&) = delete;

  // Next frame as CV_8UC1 or CV_16UC1 (the buffer may be reused between
  // calls). Returns false at the end of the last segment. Throws DataError
  // naming the segment if a video is truncated or corrupt, or if segments
  // differ in size or depth.
  bool Read(cv::Mat* frame);

  // Size and depth of the first segment (opens it if needed).
  VideoInfo info();
  std::int64_t frames_read() const { return frames_read_; }

 private:
  bool OpenNext();
  void CloseCurrent(bool at_eof);
  bool ReadFromPipe(cv::Mat* frame);
  bool ReadFromSequence(cv::Mat* frame);
  bool ReadFromCamera(cv::Mat* frame);

  std::vector<std::string> segments_;
  std::size_t next_segment_ = 0;
  std::string current_;
  bool is_sequence_ = false;
  // Video-file state.
  FILE* pipe_ = nullptr;
  std::string stderr_path_;
  // Camera-file (CINE, MRAW) and y4m state: read in-process.
  std::unique_ptr<CameraFileReader> camera_;
  std::int64_t camera_next_ = 0;
  std::unique_ptr<Y4mReader> y4m_;
  // Image-sequence state.
  std::int64_t seq_index_ = 0;
  VideoInfo info_;
  bool have_info_ = false;
  std::int64_t frames_read_ = 0;
  std::int64_t segment_frames_ = 0;
  cv::Mat buffer_;
};

// Probes a video file (ffprobe) or the first image of a sequence.
VideoInfo ProbeVideo(const std::string& path);

// True if `path` is an image-sequence pattern (contains a printf '%…d').
bool IsSequencePattern(const std::string& path);

// Single-quotes a string for /bin/sh.
std::string ShellQuote(const std::string& s);

// Path of frame `index` of an image-sequence pattern ("dir/%06d.png" → "dir/000012.png").
std::string SequenceFramePath(const std::string& pattern, std::int64_t index);

// Creates an empty temporary file in $TMPDIR (or /tmp) for a child process's
// stderr and returns its path; the caller unlinks it.
std::string MakeTempFile();

}  // namespace rk::video
