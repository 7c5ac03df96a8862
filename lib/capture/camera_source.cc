#include "capture/camera_source.h"

#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <random>

#include "capture/aravis_source.h"
#include "capture/device.h"
#include "io/error.h"
#include "video/frame_source.h"

namespace rk::capture {
namespace {

bool IsIndex(const std::string& s) {
  if (s.empty() || s.size() > 4) return false;
  for (char c : s) {
    if (c < '0' || c > '9') return false;
  }
  return true;
}

// Colour → grey, other depths → 8 bit; writes into `out`.
void ToMono(const cv::Mat& in, cv::Mat* out) {
  cv::Mat grey;
  switch (in.channels()) {
    case 1: grey = in; break;
    case 2: cv::cvtColor(in, *out, cv::COLOR_YUV2GRAY_YUYV); return;
    case 3: cv::cvtColor(in, *out, cv::COLOR_BGR2GRAY); return;
    case 4: cv::cvtColor(in, *out, cv::COLOR_BGRA2GRAY); return;
    default: throw ProcessingError("camera delivers " + std::to_string(in.channels()) + "-channel frames");
  }
  if (grey.depth() == CV_8U || grey.depth() == CV_16U) {
    grey.copyTo(*out);
  } else {
    grey.convertTo(*out, CV_8U);
  }
}

// The clock starts at the first Wait(), so a source opened early does not deliver a burst.
class Pacer {
 public:
  void Reset(double fps) {
    period_ns_ = static_cast<std::int64_t>(std::llround(1e9 / fps));
    start_ns_ = -1;
    k_ = 0;
  }
  bool Wait(const std::atomic<bool>& stop) {
    if (start_ns_ < 0) start_ns_ = MonoNowNs();
    return SleepUntil(start_ns_ + k_ * period_ns_, stop);
  }
  void Next() { ++k_; }

 private:
  std::int64_t period_ns_ = 50000000, start_ns_ = -1, k_ = 0;
};

class OpenCvSource : public CameraSource {
 public:
  explicit OpenCvSource(CameraSourceOptions o) : o_(std::move(o)) {}
  bool Open(std::string* why) override {
    Close();
    bool ok = false;
    if (IsFile()) {
      ok = cap_.open(o_.source.substr(7), cv::CAP_FFMPEG);
    } else if (o_.source.rfind("gst:", 0) == 0) {
      ok = cap_.open(o_.source.substr(4), cv::CAP_GSTREAMER);
    } else if (IsIndex(o_.source)) {
      ok = cap_.open(std::stoi(o_.source), cv::CAP_V4L2);
    } else {
      ok = cap_.open(o_.source, cv::CAP_V4L2);
    }
    if (!ok || !cap_.isOpened()) {
      if (why) *why = "cannot open camera '" + o_.source + "'";
      return false;
    }
    if (o_.fourcc.size() == 4) {
      cap_.set(cv::CAP_PROP_FOURCC, cv::VideoWriter::fourcc(o_.fourcc[0], o_.fourcc[1], o_.fourcc[2], o_.fourcc[3]));
    }
    if (o_.width > 0) cap_.set(cv::CAP_PROP_FRAME_WIDTH, o_.width);
    if (o_.height > 0) cap_.set(cv::CAP_PROP_FRAME_HEIGHT, o_.height);
    if (!kGst() && !IsFile()) cap_.set(cv::CAP_PROP_FPS, o_.fps);
    const double f = cap_.get(cv::CAP_PROP_FPS);
    fps_ = f > 0 && std::isfinite(f) && f < 10000 ? f : o_.fps;
    pacer_.Reset(fps_);
    return true;
  }
  void Close() override {
    if (cap_.isOpened()) cap_.release();
  }
  GrabResult Grab(cv::Mat* out, Stamp* at, std::string* why, const std::atomic<bool>& stop) override {
    if (stop.load()) return GrabResult::kStopped;
    if (IsFile() && !pacer_.Wait(stop)) return GrabResult::kStopped;  // a file plays at its rate
    bool ok = cap_.isOpened() && cap_.grab();
    if (!ok && IsFile() && cap_.isOpened()) {
      if (!o_.loop) return GrabResult::kEnd;
      cap_.set(cv::CAP_PROP_POS_FRAMES, 0);
      ok = cap_.grab();
    }
    if (!ok) {
      if (why) *why = "camera '" + o_.source + "' delivered no frame";
      return GrabResult::kError;
    }
    if (IsFile()) pacer_.Next();
    *at = Now();
    if (!cap_.retrieve(raw_) || raw_.empty()) {
      if (why) *why = "camera '" + o_.source + "': frame could not be retrieved";
      return GrabResult::kError;
    }
    ToMono(raw_, out);
    return GrabResult::kFrame;
  }
  double fps() const override { return fps_; }
  std::string kind() const override { return IsFile() ? "opencv-file" : kGst() ? "gstreamer" : "v4l2"; }

 private:
  bool kGst() const { return o_.source.rfind("gst:", 0) == 0; }
  bool IsFile() const { return o_.source.rfind("cvfile:", 0) == 0; }
  Pacer pacer_;
  CameraSourceOptions o_;
  cv::VideoCapture cap_;
  cv::Mat raw_;
  double fps_ = 0;
};

// Paces frames at a fixed rate on CLOCK_MONOTONIC: frame k is due at start + k / fps.
class FileSource : public CameraSource {
 public:
  explicit FileSource(CameraSourceOptions o) : o_(std::move(o)), path_(o_.source.substr(5)) {}
  bool Open(std::string* why) override {
    try {
      reader_ = std::make_unique<video::FrameSource>(std::vector<std::string>{path_});
      reader_->info();
    } catch (const Error& e) {
      if (why) *why = e.what();
      reader_.reset();
      return false;
    }
    fps_ = o_.fps;
    if (!video::IsSequencePattern(path_)) {
      cv::VideoCapture probe(path_, cv::CAP_FFMPEG);
      const double f = probe.isOpened() ? probe.get(cv::CAP_PROP_FPS) : 0.0;
      if (f > 0 && std::isfinite(f) && f < 10000) fps_ = f;
    }
    pacer_.Reset(fps_);
    return true;
  }
  void Close() override { reader_.reset(); }
  GrabResult Grab(cv::Mat* out, Stamp* at, std::string* why, const std::atomic<bool>& stop) override {
    if (!reader_) {
      if (why) *why = "file source not open";
      return GrabResult::kError;
    }
    if (!pacer_.Wait(stop)) return GrabResult::kStopped;
    cv::Mat frame;
    try {
      bool got = reader_->Read(&frame);
      if (!got && o_.loop) {
        reader_ = std::make_unique<video::FrameSource>(std::vector<std::string>{path_});
        got = reader_->Read(&frame);
      }
      if (!got) return GrabResult::kEnd;
    } catch (const Error& e) {
      if (why) *why = e.what();
      return GrabResult::kError;
    }
    frame.copyTo(*out);
    *at = Now();
    pacer_.Next();
    return GrabResult::kFrame;
  }
  double fps() const override { return fps_; }
  std::string kind() const override { return "file"; }

 private:
  CameraSourceOptions o_;
  std::string path_;
  std::unique_ptr<video::FrameSource> reader_;
  Pacer pacer_;
  double fps_ = 0;
};

class SyntheticSource : public CameraSource {
 public:
  explicit SyntheticSource(CameraSourceOptions o) : o_(std::move(o)) {
    int w = 0, h = 0, depth = 8;
    const std::string spec = o_.source.substr(10);
    char tail[16] = {0};
    const int n = std::sscanf(spec.c_str(), "%dx%d%15s", &w, &h, tail);
    if (n < 2 || w < 16 || h < 16 || w > 20000 || h > 20000) {
      throw UsageError("camera source '" + o_.source + "': expected synthetic:WIDTHxHEIGHT[:16]");
    }
    if (n == 3) {
      if (std::string(tail) == ":16") {
        depth = 16;
      } else if (std::string(tail) != ":8") {
        throw UsageError("camera source '" + o_.source + "': expected synthetic:WIDTHxHEIGHT[:16]");
      }
    }
    width_ = w;
    height_ = h;
    depth_ = depth;
  }
  bool Open(std::string*) override {
    if (base_.empty()) {
      // Fixed random texture (a fixed seed: the same station config gives the same frames).
      base_.create(height_, width_, depth_ == 16 ? CV_16UC1 : CV_8UC1);
      cv::RNG rng(12345);
      rng.fill(base_, cv::RNG::UNIFORM, 0, depth_ == 16 ? 4096 : 64);
    }
    pacer_.Reset(o_.fps);
    return true;
  }
  void Close() override {}
  GrabResult Grab(cv::Mat* out, Stamp* at, std::string*, const std::atomic<bool>& stop) override {
    if (!pacer_.Wait(stop)) return GrabResult::kStopped;
    base_.copyTo(*out);
    // A bright 9×9 spot circling the centre, one turn per 10 s.
    const double a = 2.0 * M_PI * static_cast<double>(seq_) / (10.0 * o_.fps);
    const int cx = width_ / 2 + static_cast<int>(std::lround(0.3 * width_ * std::cos(a)));
    const int cy = height_ / 2 + static_cast<int>(std::lround(0.3 * height_ * std::sin(a)));
    cv::rectangle(*out, cv::Rect(cx - 4, cy - 4, 9, 9), cv::Scalar(depth_ == 16 ? 60000 : 250), cv::FILLED);
    // Sequence number in the first 8 pixels, one byte each, little-endian.
    for (int i = 0; i < 8; ++i) {
      const unsigned v = static_cast<unsigned>((static_cast<std::uint64_t>(seq_) >> (8 * i)) & 0xff);
      if (depth_ == 16) {
        out->at<std::uint16_t>(0, i) = static_cast<std::uint16_t>(v);
      } else {
        out->at<std::uint8_t>(0, i) = static_cast<std::uint8_t>(v);
      }
    }
    *at = Now();
    ++seq_;
    pacer_.Next();
    return GrabResult::kFrame;
  }
  double fps() const override { return o_.fps; }
  std::string kind() const override { return "synthetic"; }

 private:
  CameraSourceOptions o_;
  int width_ = 0, height_ = 0, depth_ = 8;
  cv::Mat base_;
  Pacer pacer_;
  std::int64_t seq_ = 0;
};

}  // namespace

std::int64_t SyntheticFrameSeq(const cv::Mat& frame) {
  if (frame.empty() || frame.cols < 8 || frame.channels() != 1) return -1;
  std::uint64_t v = 0;
  for (int i = 0; i < 8; ++i) {
    const unsigned b = frame.depth() == CV_16U ? frame.at<std::uint16_t>(0, i) : frame.at<std::uint8_t>(0, i);
    if (b > 255) return -1;
    v |= static_cast<std::uint64_t>(b) << (8 * i);
  }
  return static_cast<std::int64_t>(v);
}

std::unique_ptr<CameraSource> MakeCameraSource(const CameraSourceOptions& o) {
  if (o.source.empty()) throw UsageError("camera source is empty");
  if (o.source.rfind("file:", 0) == 0) return std::make_unique<FileSource>(o);
  if (o.source.rfind("synthetic:", 0) == 0) return std::make_unique<SyntheticSource>(o);
  if (o.source.rfind("aravis:", 0) == 0) {
    if (o.source.size() == std::string("aravis:").size()) throw UsageError("camera source 'aravis:' names no camera");
    return std::make_unique<AravisSource>(o);
  }
  return std::make_unique<OpenCvSource>(o);
}

}  // namespace rk::capture
