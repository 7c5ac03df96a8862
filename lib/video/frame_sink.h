// Writing lossless mono video: FFV1 in Matroska (".mkv", through an ffmpeg child
// process; 8-bit gray or 16-bit gray16le), or an image sequence
// ("dir/%06d.png", 8- or 16-bit PNG). The caller makes the result atomic
// (write into a temporary folder, rename at the end).
#pragma once

#include <cstdio>
#include <opencv2/core.hpp>
#include <string>

namespace rk::video {

class FrameSink {
 public:
  FrameSink(std::string path, int width, int height, int bit_depth, double fps);
  ~FrameSink();
  FrameSink(const FrameSink&) = delete;
  FrameSink& operator=(const FrameSink&) = delete;

  // Frame must be CV_8UC1 (bit_depth 8) or CV_16UC1 (bit_depth 16) of the size given.
  void Write(const cv::Mat& frame);
  // Finishes the file; throws IoError if the encoder failed.
  void Close();
  std::int64_t frames_written() const { return frames_; }

 private:
  std::string path_;
  int width_, height_, bit_depth_;
  bool sequence_ = false;
  FILE* pipe_ = nullptr;
  std::string stderr_path_;
  std::int64_t frames_ = 0;
};

}  // namespace rk::video
