#include "video/frame_sink.h"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <opencv2/imgcodecs.hpp>  // the flags only: the functions come from video/image_codecs.h
#include <sstream>

#include "io/error.h"
#include "video/frame_source.h"
#include "video/image_codecs.h"

namespace rk::video {

FrameSink::FrameSink(std::string path, int width, int height, int bit_depth, double fps)
    : path_(std::move(path)), width_(width), height_(height), bit_depth_(bit_depth) {
  RK_CHECK(bit_depth == 8 || bit_depth == 16, "bit depth must be 8 or 16");
  sequence_ = IsSequencePattern(path_);
  if (sequence_) return;
  stderr_path_ = MakeTempFile();
  // FFV1 version 3 with slices (decodes on several threads) and per-slice CRCs
  // (corruption is detected on reading); every frame a key frame.
  char size[64];
  std::snprintf(size, sizeof size, "%dx%d", width, height);
  char rate[64];
  std::snprintf(rate, sizeof rate, "%.6f", fps);
  std::string cmd = std::string("ffmpeg -v error -nostdin -y -f rawvideo -pix_fmt ") +
                    (bit_depth == 16 ? "gray16le" : "gray") + " -s " + size + " -r " + rate +
                    " -i - -c:v ffv1 -level 3 -slices 4 -slicecrc 1 -g 1 -pix_fmt " +
                    (bit_depth == 16 ? "gray16le" : "gray") + " " + ShellQuote(path_) + " 2>" +
                    ShellQuote(stderr_path_);
  pipe_ = ::popen(cmd.c_str(), "w");
  if (!pipe_) throw IoError(path_, "cannot run ffmpeg");
}

FrameSink::~FrameSink() {
  if (pipe_) ::pclose(pipe_);
  if (!stderr_path_.empty()) ::unlink(stderr_path_.c_str());
}

void FrameSink::Write(const cv::Mat& frame) {
  RK_CHECK(frame.rows == height_ && frame.cols == width_, "frame size");
  RK_CHECK(frame.type() == (bit_depth_ == 16 ? CV_16UC1 : CV_8UC1), "frame type");
  if (sequence_) {
    const std::string file = SequenceFramePath(path_, frames_);
    if (!ImWrite(file, frame, {cv::IMWRITE_PNG_COMPRESSION, 1})) {
      throw IoError(file, "cannot write image");
    }
  } else {
    cv::Mat c = frame.isContinuous() ? frame : frame.clone();
    std::size_t bytes = c.total() * c.elemSize();
    if (std::fwrite(c.data, 1, bytes, pipe_) != bytes) throw IoError(path_, "video encoder stopped accepting frames");
  }
  ++frames_;
}

void FrameSink::Close() {
  if (!pipe_) return;
  int rc = ::pclose(pipe_);
  pipe_ = nullptr;
  if (rc != 0) {
    std::ifstream in(stderr_path_);
    std::stringstream ss;
    ss << in.rdbuf();
    std::string e = ss.str();
    throw IoError(path_, "video encoder failed: " + e.substr(0, e.find('\n')));
  }
}

}  // namespace rk::video
